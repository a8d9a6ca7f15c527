// The sphere tracer (shaders/volume/sdf_march.glsl) through shaders/volume/sdf_march_probe.comp: a plane
// and a sphere at their analytic distances, from head-on to grazing, on exact fields and on fields
// jump-flooded from voxelized seeds; misses are misses; the cascade hand-over finds planes outside
// the fine cascades; a grazing hit on a floor stays short of a wall standing on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "render_test_util.h"
#include "volume/volume_cascades.h"
#include "march_test_util.h"
#include "sdf_test_util.h"

namespace gis::test {
namespace {

// A field sampled from an analytic signed distance at every cell centre.
std::unique_ptr<DistanceField> analyticField(const SdfVolume& v, const std::function<float(glm::vec3)>& sdf,
                                             gl::MemoryLedger& ledger) {
    context();
    auto field = std::make_unique<DistanceField>(v, gl::MemoryScope{&ledger, "sdf_test"});
    const int n = v.resolution;
    std::vector<float> d(size_t(n) * n * n);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                d[(size_t(z) * n + y) * n + x] = sdf(v.origin + (glm::vec3(x, y, z) + 0.5f) * v.cellSize());
    field->upload(d);
    return field;
}

const SdfVolume kVolume{glm::vec3(-1.0f), 2.0f, 32};
constexpr float kPlaneY = -0.437f;  // not on a cell centre or a cell face
const glm::vec3 kSphereCentre(0.06f, -0.03f, 0.11f);
constexpr float kSphereRadius = 0.55f;

// Rays towards the plane y = kPlaneY at elevations from 90 (head-on) down to 2 degrees (grazing).
std::vector<Ray> planeRays(std::vector<float>& elevations) {
    std::vector<Ray> rays;
    for (float e : {90.0f, 60.0f, 30.0f, 15.0f, 8.0f, 4.0f, 2.0f})
        for (float azimuth : {0.0f, 0.7f, 1.9f, 3.3f}) {
            const float el = glm::radians(e);
            const glm::vec3 dir(std::cos(el) * std::cos(azimuth), -std::sin(el), std::cos(el) * std::sin(azimuth));
            // Aim at a point of the plane near the middle, from 8 cells above along the ray... or
            // from where the ray enters the volume when that is nearer.
            const glm::vec3 target(0.1f * std::cos(azimuth * 3.0f), kPlaneY, 0.1f);
            const float back = std::min(1.2f, (1.0f - target.y - 0.01f) / std::sin(el));
            rays.push_back({glm::vec4(target - dir * back, 10.0f), glm::vec4(dir, 0.0f)});
            elevations.push_back(e);
        }
    return rays;
}

// Rays at the sphere from outside with impact parameters 0 ... 0.97 R (the last ones graze it).
std::vector<Ray> sphereRays(std::vector<float>& impacts) {
    std::vector<Ray> rays;
    const glm::vec3 axes[3] = {{1, 0, 0}, {0, 0.6f, 0.8f}, glm::normalize(glm::vec3(-1, 1, 1))};
    for (const glm::vec3& a : axes)
        for (float b : {0.0f, 0.3f, 0.6f, 0.8f, 0.9f, 0.95f, 0.97f}) {
            const glm::vec3 side = glm::normalize(glm::cross(a, glm::vec3(0.3f, 0.4f, 0.5f)));
            const glm::vec3 origin = kSphereCentre - a * 0.95f + side * (b * kSphereRadius);
            rays.push_back({glm::vec4(origin, 10.0f), glm::vec4(a, 0.0f)});
            impacts.push_back(b);
        }
    return rays;
}

// Distance along the ray to the analytic sphere (negative: no intersection).
float sphereT(const Ray& r) {
    const glm::vec3 o = glm::vec3(r.origin) - kSphereCentre, d = glm::vec3(r.direction);
    const float b = glm::dot(o, d), c = glm::dot(o, o) - kSphereRadius * kSphereRadius, disc = b * b - c;
    return disc < 0.0f ? -1.0f : -b - std::sqrt(disc);
}

// Checks each hit lies on its ray within `tolerance` (world) of the analytic intersection, and
// returns the largest error in cells.
double checkHits(const std::vector<Ray>& rays, const std::vector<Hit>& hits, const std::function<float(const Ray&)>& exactT,
                 float tolerance, const char* what) {
    double worst = 0.0, steps = 0.0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const glm::vec3 expected = glm::vec3(rays[i].origin) + glm::vec3(rays[i].direction) * exactT(rays[i]);
        EXPECT_TRUE(hits[i].hit) << what << " ray " << i;
        const float err = glm::length(hits[i].position - expected);
        EXPECT_LE(err, tolerance) << what << " ray " << i;
        worst = std::max(worst, double(err));
        steps += hits[i].steps;
    }
    std::printf("%s: worst hit error %.3f cells, %.1f steps per ray\n", what, worst / kVolume.cellSize(),
                steps / double(rays.size()));
    return worst / kVolume.cellSize();
}

float planeT(const Ray& r) { return (kPlaneY - r.origin.y) / r.direction.y; }

TEST(SdfMarch, FindsAPlaneWithinHalfACellFromGrazingAngles) {
    gl::MemoryLedger ledger;
    auto field = analyticField(kVolume, [](glm::vec3 p) { return p.y - kPlaneY; }, ledger);
    std::vector<float> elevations;
    const auto rays = planeRays(elevations);
    for (float relaxation : {1.0f, 1.6f}) {
        MarchSettings m;
        m.relaxation = relaxation;
        const auto hits = march(*field, rays, m);
        checkHits(rays, hits, planeT, 0.5f * kVolume.cellSize(), relaxation > 1.0f ? "plane, relaxed" : "plane");
        for (const Hit& h : hits) EXPECT_GT(h.normal.y, 0.999f);
    }
}

TEST(SdfMarch, FindsASphereWithinHalfACellFromGrazingAngles) {
    gl::MemoryLedger ledger;
    auto field = analyticField(kVolume, [](glm::vec3 p) { return glm::length(p - kSphereCentre) - kSphereRadius; }, ledger);
    std::vector<float> impacts;
    const auto rays = sphereRays(impacts);
    const auto hits = march(*field, rays);
    checkHits(rays, hits, sphereT, 0.5f * kVolume.cellSize(), "sphere");
    for (size_t i = 0; i < hits.size(); ++i) {
        const glm::vec3 exactNormal = glm::normalize(hits[i].position - kSphereCentre);
        // Central differences one cell apart: within 9 degrees even at the grazing rays.
        EXPECT_GT(glm::dot(hits[i].normal, exactNormal), 0.985f) << "ray " << i;
    }
}

TEST(SdfMarch, MissesAreMisses) {
    gl::MemoryLedger ledger;
    auto field = analyticField(kVolume, [](glm::vec3 p) { return glm::length(p - kSphereCentre) - kSphereRadius; }, ledger);
    std::vector<Ray> rays;
    // Away from the sphere, past it, outside the volume entirely, and a max distance short of it.
    rays.push_back({glm::vec4(kSphereCentre + glm::vec3(0.7f, 0, 0), 10.0f), glm::vec4(1, 0, 0, 0)});
    rays.push_back({glm::vec4(kSphereCentre + glm::vec3(-0.9f, 0.6f, 0), 10.0f), glm::vec4(1, 0, 0, 0)});
    rays.push_back({glm::vec4(3, 3, 3, 10.0f), glm::vec4(0, 1, 0, 0)});
    rays.push_back({glm::vec4(kSphereCentre + glm::vec3(-0.9f, 0, 0), 0.2f), glm::vec4(1, 0, 0, 0)});
    for (const Hit& h : march(*field, rays)) EXPECT_FALSE(h.hit);
    // A ray that runs out of steps is a miss, not a hit at its last point.
    MarchSettings few;
    few.maxSteps = 1;
    EXPECT_FALSE(march(*field, {{glm::vec4(-0.95f, -0.03f, 0.11f, 10.0f), glm::vec4(1, 0, 0, 0)}}, few)[0].hit);
    // A ray from outside the volume enters it and hits.
    EXPECT_TRUE(march(*field, {{glm::vec4(-5.0f, -0.03f, 0.11f, 10.0f), glm::vec4(1, 0, 0, 0)}})[0].hit);
}

// The whole module: a sphere voxelized on the CPU (every cell the surface passes through, with its
// outward normal), jump-flooded, resolved and traced. The zero level set is the outer seed cells'
// centres, up to sqrt(3)/2 cell outside the surface, so hits are within a cell rather than half.
TEST(SdfMarch, FindsAJumpFloodedSphereWithinACell) {
    const int n = kVolume.resolution;
    SeedGrid g = uniformSeeds(n, 0, 1);
    const float h = kVolume.cellSize();
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec3 c = kVolume.origin + (glm::vec3(x, y, z) + 0.5f) * h;
                // Conservatively, like the voxelizer: every cell the surface may pass through.
                if (std::abs(glm::length(c - kSphereCentre) - kSphereRadius) > 0.8660254f * h) continue;
                g.seed[g.index(x, y, z)] = 1;
                g.normal[g.index(x, y, z)] = glm::normalize(c - kSphereCentre);
            }
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    DistanceField field(kVolume, scope);
    field.build(textures.seeds(true), JfaVariant::JfaPlusTwo);
    // Inside is negative: the centre cell.
    const auto d = field.readBack();
    const glm::ivec3 centre = glm::ivec3((kSphereCentre - kVolume.origin) / h);
    EXPECT_LT(d[g.index(centre.x, centre.y, centre.z)], -0.4f);
    std::vector<float> impacts;
    const auto rays = sphereRays(impacts);
    // Distance of each hit from the analytic surface (at grazing impact the inflated level set is
    // met far along the ray from the analytic intersection, so the along-ray error is not the measure).
    const auto hits = march(field, rays);
    double worst = 0.0;
    for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_TRUE(hits[i].hit) << "ray " << i;
        const double err = std::abs(glm::length(hits[i].position - kSphereCentre) - kSphereRadius) / h;
        EXPECT_LE(err, 1.0) << "ray " << i << " impact " << impacts[i];
        worst = std::max(worst, err);
    }
    std::printf("jump-flooded sphere: worst distance of a hit from the surface %.3f cells\n", worst);
}

// Three cascades centred on the origin (edges 2, 4 and 8, 32 cells each, as volume_cascades.h
// places them), each layer holding the exact distance to the part of the plane y = planeY inside its cube
// and the "far" value where the plane misses the cube - what a cascade jump-flooded from its own
// voxels holds.
struct PlaneCascades {
    CascadeLayout layout;
    std::unique_ptr<DistanceField> field;
};

PlaneCascades planeCascades(float planeY, gl::MemoryLedger& ledger) {
    context();
    PlaneCascades c;
    c.layout.scene.origin = glm::vec3(-4.0f);
    c.layout.scene.size = 8.0f;
    c.layout.scene.resolution = 32;
    c.layout.count = 3;
    const int n = 32;
    for (int i = 0; i < c.layout.count; ++i) {
        const SdfVolume v = c.layout.volume(i, c.layout.centredOffset(i, glm::vec3(0.0f)));
        if (!c.field) c.field = std::make_unique<DistanceField>(v, gl::MemoryScope{&ledger, "sdf_test"}, c.layout.count);
        c.field->setVolume(i, v);
        const bool crosses = planeY > v.origin.y && planeY < v.origin.y + v.size;
        std::vector<float> d(size_t(n) * n * n);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    d[(size_t(z) * n + y) * n + x] =
                        crosses ? v.origin.y + (float(y) + 0.5f) * v.cellSize() - planeY : v.farValue();
        c.field->upload(d, i);
    }
    return c;
}

// Rays from near the camera down to the plane, from head-on to 45 degrees.
std::vector<Ray> downRays() {
    std::vector<Ray> rays;
    for (float e : {90.0f, 70.0f, 55.0f, 45.0f})
        for (float azimuth : {0.3f, 1.9f, 3.3f, 4.8f}) {
            const float el = glm::radians(e);
            const glm::vec3 dir(std::cos(el) * std::cos(azimuth), -std::sin(el), std::cos(el) * std::sin(azimuth));
            rays.push_back({glm::vec4(0.05f, 0.3f, -0.02f, 20.0f), glm::vec4(dir, 0.0f)});
        }
    return rays;
}

// Hands over: a plane outside the two fine cascades is found in the coarsest, within half of its
// cell, relaxed or not; one inside the finest is found there, within half of its (finer) cell.
TEST(SdfMarch, CascadeHandOverFindsAFarPlaneWithinHalfACoarseCell) {
    for (const auto& [planeY, cascade] : {std::pair<float, int>{-3.1f, 2}, {-0.437f, 0}}) {
        gl::MemoryLedger ledger;
        PlaneCascades c = planeCascades(planeY, ledger);
        const std::vector<Ray> rays = downRays();
        const float cell = c.layout.cellSize(cascade);
        for (float relaxation : {1.0f, 1.6f}) {
            MarchSettings m;
            m.relaxation = relaxation;
            const auto hits = march(*c.field, rays, m);
            double worst = 0.0, steps = 0.0;
            for (size_t i = 0; i < rays.size(); ++i) {
                const float t = (planeY - rays[i].origin.y) / rays[i].direction.y;
                const glm::vec3 expected = glm::vec3(rays[i].origin) + glm::vec3(rays[i].direction) * t;
                ASSERT_TRUE(hits[i].hit) << "plane " << planeY << " ray " << i;
                EXPECT_EQ(hits[i].cascade, cascade) << "plane " << planeY << " ray " << i;
                const float err = glm::length(hits[i].position - expected);
                EXPECT_LE(err, 0.5f * cell) << "plane " << planeY << " ray " << i;
                EXPECT_GT(hits[i].normal.y, 0.999f);
                worst = std::max(worst, double(err));
                steps += hits[i].steps;
            }
            std::printf("cascades, plane at y=%g (cascade %d), relaxation %.1f: worst hit error %.3f of its cells, "
                        "%.1f steps per ray\n",
                        planeY, cascade, relaxation, worst / cell, steps / double(rays.size()));
        }
    }
}

// A plane just beyond the finest cascade, which that cascade's field does not contain (its value
// there is "far"): the marcher may not step by that value past the cube's faces, so the plane is
// found in the next cascade rather than jumped over.
TEST(SdfMarch, CascadeHandOverDoesNotJumpSurfacesJustOutsideAFineCascade) {
    gl::MemoryLedger ledger;
    const float planeY = -1.05f;  // the finest cascade spans [-1, 1]
    PlaneCascades c = planeCascades(planeY, ledger);
    const std::vector<Ray> rays = downRays();
    const auto hits = march(*c.field, rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        const float t = (planeY - rays[i].origin.y) / rays[i].direction.y;
        const glm::vec3 expected = glm::vec3(rays[i].origin) + glm::vec3(rays[i].direction) * t;
        ASSERT_TRUE(hits[i].hit) << "ray " << i;
        EXPECT_EQ(hits[i].cascade, 1) << "ray " << i;
        EXPECT_LE(glm::length(hits[i].position - expected), 0.5f * c.layout.cellSize(1)) << "ray " << i;
    }
}

// Rays that leave every cascade are misses; nothing a ray returns through cascades is NaN or Inf,
// including rays starting outside all of them and along the cubes' faces.
TEST(SdfMarch, CascadesGiveFiniteResultsAndMisses) {
    gl::MemoryLedger ledger;
    PlaneCascades c = planeCascades(-3.1f, ledger);
    std::vector<Ray> rays = {{glm::vec4(0.0f, 0.3f, 0.0f, 20.0f), glm::vec4(0, 1, 0, 0)},     // up: nothing
                             {glm::vec4(9.0f, 9.0f, 9.0f, 20.0f), glm::vec4(0, 1, 0, 0)},     // outside all
                             {glm::vec4(-1.0f, -1.0f, 0.0f, 20.0f), glm::vec4(1, 0, 0, 0)},   // along faces
                             {glm::vec4(-9.0f, -2.0f, 0.1f, 20.0f), glm::vec4(1, -0.2f, 0, 0)}};
    rays.back().direction = glm::vec4(glm::normalize(glm::vec3(rays.back().direction)), 0.0f);
    const auto hits = march(*c.field, rays);
    EXPECT_FALSE(hits[0].hit);
    EXPECT_FALSE(hits[1].hit);
    EXPECT_FALSE(hits[2].hit);
    EXPECT_TRUE(hits[3].hit);   // enters the coarsest cascade from outside and meets the plane
    for (const Hit& h : hits)
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(h.position[k]) && std::isfinite(h.normal[k]));
}


// A floor and a wall one cell thick standing on it (jump-flooded seeds, as the voxelizer leaves a
// wall thinner than a cell). Rays start just above the floor, within the hit threshold, and run at
// grazing angles towards the wall: near the floor the field is the floor's, so the refinement's
// Newton step onto the floor's plane, many cells along the ray, would land beyond the wall, in
// the next room. Every hit stays on the near side of the wall.
TEST(SdfMarch, AGrazingHitOnAFloorDoesNotPassAWallStandingOnIt) {
    const int n = kVolume.resolution;
    const float h = kVolume.cellSize();
    const int floorY = 8, wallX = 16;
    SeedGrid g = uniformSeeds(n, 0, 1);
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) {
            g.seed[g.index(x, floorY, z)] = 1;
            g.normal[g.index(x, floorY, z)] = glm::vec3(0, 1, 0);
        }
    for (int z = 0; z < n; ++z)
        for (int y = floorY + 1; y < n; ++y) g.seed[g.index(wallX, y, z)] = 1;  // both faces: no orientation
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    DistanceField field(kVolume, scope);
    field.build(textures.seeds(true), JfaVariant::JfaPlusTwo);
    const float floorLevel = kVolume.origin.y + (float(floorY) + 0.5f) * h;
    const float wallFar = kVolume.origin.x + (float(wallX) + 1.0f) * h;
    std::vector<Ray> rays;
    for (float cellsFromWall : {1.0f, 2.5f, 4.0f})
        for (float height : {0.2f, 0.35f, 0.45f})
            for (float e : {1.0f, 2.0f, 4.0f})
                for (float azimuth : {-0.3f, 0.0f, 0.4f}) {
                    const float el = glm::radians(e);
                    const glm::vec3 dir(std::cos(el) * std::cos(azimuth), -std::sin(el), std::cos(el) * std::sin(azimuth));
                    const glm::vec3 origin(wallFar - (1.0f + cellsFromWall) * h, floorLevel + height * h, 0.05f);
                    rays.push_back({glm::vec4(origin, 10.0f), glm::vec4(dir, 0.0f)});
                }
    const auto hits = march(field, rays);
    float furthest = -1e9f;
    for (size_t i = 0; i < rays.size(); ++i) {
        ASSERT_TRUE(hits[i].hit) << "ray " << i;
        EXPECT_LE(hits[i].position.x, wallFar) << "ray " << i << " from x " << rays[i].origin.x;
        furthest = std::max(furthest, hits[i].position.x);
    }
    std::printf("grazing rays towards a wall on a floor: furthest hit %.2f cells past the wall's far face\n",
                (furthest - wallFar) / h);
}

}  // namespace
}  // namespace gis::test
