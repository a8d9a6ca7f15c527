// Where the distance field's cascades lie (renderer/volume/volume_cascades.h), on the CPU: how many a
// scene gets, that they nest, that a camera move within the snap moves none of them and a longer
// one moves only those whose position changed.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

#include "bvh.h"
#include "render_test_util.h"
#include "volume/scene_volume.h"
#include "volume/volume_cascades.h"

namespace gis::test {
namespace {

// An extent given in world units (sdf.cascade-extent > 0; its default, 0, takes it from the view):
// the fixed 8 m the count once followed.
constexpr float kExtent = 8.0f;

// The Cornell box, the room and the two rooms of the leak scene fit in one volume; the atrium's
// 29 m cube gets three cascades (7.2, 14.4 and 28.9 m at 64^3). Prints the README's table
// ("SDF-TABLE cascades").
TEST(SdfCascades, OneForSmallScenesSeveralForTheAtrium) {
    for (const char* name : {"cornell", "room", "leak", "atrium"}) {
        const Scene scene = makeBuiltinScene(name);
        for (int n : {32, 64}) {
            const CascadeLayout l = layoutCascades(scene.bounds, n, kExtent, 0, "sdf");
            std::printf("SDF-TABLE cascades %s at %d^3: %d (scene cube %.3f; finest cascade %.3f, cells of %.4f)\n",
                        name, n, l.count, double(l.scene.size), double(l.extent(0)), double(l.cellSize(0)));
            EXPECT_EQ(l.count, std::string(name) == "atrium" ? 3 : 1) << name << " " << n;
            EXPECT_LE(l.extent(0), kExtent) << name;
        }
    }
}

// The count follows the scene's extent against sdf.cascade-extent: scaling both together changes
// nothing; capped; sdf.cascades forces it; bad requests are one clear error.
TEST(SdfCascades, CountFollowsTheExtentCappedAndCanBeForced) {
    const Scene atrium = makeBuiltinScene("atrium");
    const int unit = layoutCascades(atrium.bounds, 64, kExtent, 0, "sdf").count;
    for (float scale : {1e-3f, 1e3f})
        EXPECT_EQ(layoutCascades(scaledScene(atrium, scale).bounds, 64, kExtent * scale, 0, "sdf").count, unit) << scale;
    VolumeFit cube;
    cube.size = 100.0f;
    cube.resolution = 32;
    EXPECT_EQ(chooseCascadeCount(cube, 100.0f, 0, "sdf"), 1);
    EXPECT_EQ(chooseCascadeCount(cube, 99.0f, 0, "sdf"), 2);
    EXPECT_EQ(chooseCascadeCount(cube, 50.0f, 0, "sdf"), 2);
    EXPECT_EQ(chooseCascadeCount(cube, 1.0f, 0, "sdf"), kMaxCascades);  // capped
    EXPECT_EQ(chooseCascadeCount(cube, 1.0f, 2, "sdf"), 2);                // sdf.cascades
    EXPECT_THROW(chooseCascadeCount(cube, 1.0f, kMaxCascades + 1, "sdf"), Error);
    EXPECT_THROW(chooseCascadeCount(cube, 1.0f, -1, "sdf"), Error);
    EXPECT_THROW(chooseCascadeCount(cube, 0.0f, 0, "sdf"), Error);
    try {  // the requesting method's parameter, whichever method asks
        chooseCascadeCount(cube, 1.0f, -1, "hddagi");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("hddagi.cascades"), std::string::npos) << e.what();
    }
    Scene empty;
    finalizeScene(empty);
    EXPECT_EQ(layoutCascades(empty.bounds, 32, kExtent, 0, "sdf").count, 1);
}

// The count from the view (cascade-extent 0, the default): a scene and its camera scaled together
// get the same count at every unit of length; the rooms and single models one volume; the
// building and the courtyard, where the camera stands among walls far smaller than the scene,
// several. Prints the README's table ("VIEW-TABLE").
TEST(SdfCascades, TheCountFromTheViewIsTheSameAtEveryUnitOfLength) {
    const std::vector<std::pair<const char*, int>> expected = {
        {"cornell", 1}, {"room", 1}, {"leak", 1}, {"building", kMaxCascades}, {"atrium", 3}};
    for (const auto& [name, count] : expected) {
        const Scene unit = makeBuiltinScene(name);
        for (float scale : {1.0f, 1e-3f, 1e3f}) {
            const Scene scene = scale == 1.0f ? unit : scaledScene(unit, scale);
            RenderSettings settings;
            settings.width = settings.height = 128;
            for (int n : {32, 64}) {
                VolumeRequest request;
                request.method = "sdf";
                request.resolution = n;
                request.cascades = 0;
                request.cascadeExtent = 0.0f;
                const float depth = viewDepthFor(request, scene, settings);
                const CascadeLayout l = volumeLayout(sceneAirBounds(scene), request, depth);
                // How far the finest extent from the view sits from the scene cube's nearest
                // power-of-two division, where the count would change.
                const float perCube = finestCascadeExtent(0.0f, depth) / l.scene.size;
                if (scale == 1.0f)
                    std::printf("VIEW-TABLE %s at %d^3: view depth %.3g, scene cube %.3g, %.3g of it from the view: "
                                "%d cascade(s), the finest %.3g\n",
                                name, n, double(depth), double(l.scene.size), double(perCube), l.count,
                                double(l.extent(0)));
                EXPECT_EQ(l.count, count) << name << " at " << n << "^3, scale " << scale << ": view depth " << depth;
            }
        }
    }
}

// A view that sees nothing of the scene (every ray leaves it) gets one volume, not an error.
TEST(SdfCascades, AViewOfNothingGetsOneVolume) {
    const Scene scene = makeBuiltinScene("atrium");
    CameraMatrices away = cameraMatrices(scene, 0, 1.0f);
    const glm::vec3 outside = scene.bounds.max + glm::vec3(10.0f);
    away.view = glm::lookAt(outside, outside + glm::vec3(1.0f), glm::vec3(0, 1, 0));
    away.position = outside;
    away.viewProj = away.proj * away.view;
    away.invViewProj = glm::inverse(away.viewProj);
    const float depth = nearViewDepth(buildBvh(scene), away);
    EXPECT_TRUE(std::isinf(depth)) << depth;
    EXPECT_EQ(layoutCascades(scene.bounds, 64, finestCascadeExtent(0.0f, depth), 0, "sdf").count, 1);
}

// The CPU walk of the BVH finds what a walk of every triangle finds.
TEST(SdfCascades, TheBvhWalkFindsTheNearestTriangle) {
    const Scene scene = makeBuiltinScene("building");
    const Bvh bvh = buildBvh(scene);
    uint32_t rng = 3;
    auto uniform = [&rng] {
        rng = rng * 1664525u + 1013904223u;
        return float(rng >> 8) / 16777216.0f;
    };
    const glm::vec3 lo = scene.bounds.min, size = scene.bounds.max - scene.bounds.min;
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 origin = lo + glm::vec3(uniform(), uniform(), uniform()) * size;
        const glm::vec3 dir = glm::normalize(glm::vec3(uniform(), uniform(), uniform()) * 2.0f - 1.0f);
        float brute = std::numeric_limits<float>::infinity();
        for (const TraceTriangle& t : bvh.triangles) {
            const glm::vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, p = glm::cross(dir, e2), s = origin - t.p0;
            const float det = glm::dot(e1, p), u = glm::dot(s, p) / det;
            const glm::vec3 q = glm::cross(s, e1);
            const float v = glm::dot(dir, q) / det, d = glm::dot(e2, q) / det;
            if (det != 0.0f && u >= 0.0f && v >= 0.0f && u + v <= 1.0f && d > 0.0f) brute = std::min(brute, d);
        }
        const float walked = nearestHit(bvh, origin, dir);
        hits += std::isfinite(brute);
        if (std::isinf(brute)) EXPECT_TRUE(std::isinf(walked)) << i;
        else EXPECT_NEAR(walked, brute, 1e-4f * brute) << i;
    }
    EXPECT_GT(hits, 100);  // most rays from inside the building hit something
}

CascadeLayout testLayout() {
    CascadeLayout l;
    l.scene.origin = glm::vec3(-10.0f);
    l.scene.size = 20.0f;
    l.scene.resolution = 32;
    l.count = 4;
    return l;
}

bool inside(const SdfVolume& inner, const SdfVolume& outer) {
    for (int a = 0; a < 3; ++a)
        if (inner.origin[a] < outer.origin[a] - 1e-4f || inner.origin[a] + inner.size > outer.origin[a] + outer.size + 1e-4f)
            return false;
    return true;
}

// Each cascade lies inside the next and the coarsest is the scene's cube, wherever the camera is
// and however the snap left the cascades (placed for an earlier camera position within the snap).
TEST(SdfCascades, CascadesNestInsideTheSceneCube) {
    const CascadeLayout l = testLayout();
    uint32_t rng = 7;
    auto uniform = [&rng] {
        rng = rng * 1664525u + 1013904223u;
        return float(rng >> 8) / 16777216.0f;
    };
    for (int trial = 0; trial < 500; ++trial) {
        const glm::vec3 camera = glm::vec3(uniform(), uniform(), uniform()) * 24.0f - 12.0f;  // some outside
        std::vector<glm::ivec3> offsets;
        for (int i = 0; i < l.count; ++i) {
            // Placed for a camera up to the snap away, then not moved.
            const glm::vec3 earlier = camera + (glm::vec3(uniform(), uniform(), uniform()) * 2.0f - 1.0f) *
                                                   (float(l.snapCells()) * l.cellSize(i));
            glm::ivec3 o = l.centredOffset(i, earlier);
            if (l.mustMove(o, l.centredOffset(i, camera))) o = l.centredOffset(i, camera);
            offsets.push_back(o);
        }
        EXPECT_EQ(l.volume(l.count - 1, offsets.back()).origin, l.scene.origin);
        for (int i = 0; i + 1 < l.count; ++i)
            ASSERT_TRUE(inside(l.volume(i, offsets[size_t(i)]), l.volume(i + 1, offsets[size_t(i) + 1])))
                << "trial " << trial << " cascade " << i;
    }
}

TEST(SdfCascades, SmallMovesKeepEveryCascadeLongerOnesMoveOnlyTheFineOnes) {
    const CascadeLayout l = testLayout();
    const glm::vec3 start(0.3f, -0.2f, 0.1f);
    std::vector<glm::ivec3> placed;
    for (int i = 0; i < l.count; ++i) placed.push_back(l.centredOffset(i, start));
    const float snap0 = float(l.snapCells()) * l.cellSize(0);
    // Within the snap of the finest cascade: nothing moves.
    for (const glm::vec3 d : {glm::vec3(0.9f * snap0, 0, 0), glm::vec3(0, -0.9f * snap0, 0.5f * snap0)})
        for (int i = 0; i < l.count; ++i) EXPECT_FALSE(l.mustMove(placed[size_t(i)], l.centredOffset(i, start + d))) << i;
    // 1.5 snaps of the finest: it moves; cascade 1's cells are twice as large, so for it that is
    // 0.75 of its snap: it stays, and so do the coarser ones.
    const glm::vec3 moved = start + glm::vec3(1.5f * snap0, 0, 0);
    EXPECT_TRUE(l.mustMove(placed[0], l.centredOffset(0, moved)));
    for (int i = 1; i < l.count; ++i) EXPECT_FALSE(l.mustMove(placed[size_t(i)], l.centredOffset(i, moved))) << i;
    // The coarsest never moves.
    EXPECT_EQ(l.centredOffset(l.count - 1, glm::vec3(1e6f)), glm::ivec3(0));
}

}  // namespace
}  // namespace gis::test
