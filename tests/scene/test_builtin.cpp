// The built-in scenes must be the reference glTFs (shared/assets/reference/scenes/) exactly:
// geometry (as world-space triangles with their winding), materials, light, camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "test_util.h"

using namespace gistest;

namespace {

struct Tri {
    glm::vec3 v[3];
    glm::vec4 albedo;
    glm::vec3 emissive;
    float metallic, roughness, specular;
    bool doubleSided;
};

// World-space triangles, each rotated so its lexicographically smallest vertex comes first
// (keeps the winding), with the material it is drawn with.
std::vector<Tri> worldTriangles(const gis::Scene& s) {
    std::vector<Tri> out;
    for (const auto& d : s.draws) {
        const auto& p = s.primitives[size_t(d.primitive)];
        const gis::Material m = p.material >= 0 ? s.materials[size_t(p.material)] : gis::Material{};
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            Tri t;
            for (int k = 0; k < 3; ++k)
                t.v[k] = glm::vec3(d.world * glm::vec4(p.vertices[p.indices[i + size_t(k)]].position, 1.0f));
            auto less = [](const glm::vec3& a, const glm::vec3& b) {
                if (std::fabs(a.x - b.x) > 1e-4f) return a.x < b.x;
                if (std::fabs(a.y - b.y) > 1e-4f) return a.y < b.y;
                return a.z < b.z - 1e-4f;
            };
            int first = 0;
            for (int k = 1; k < 3; ++k)
                if (less(t.v[k], t.v[first])) first = k;
            std::rotate(t.v, t.v + first, t.v + 3);
            t.albedo = m.baseColorFactor;
            t.emissive = m.emissive;
            t.metallic = m.metallicFactor;
            t.roughness = m.roughnessFactor;
            t.specular = m.specularFactor;
            t.doubleSided = m.doubleSided;
            out.push_back(t);
        }
    }
    return out;
}

bool near3(const glm::vec3& a, const glm::vec3& b, float tol = 1e-4f) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)));
}

bool same(const Tri& a, const Tri& b) {
    for (int k = 0; k < 3; ++k)
        if (!near3(a.v[k], b.v[k])) return false;
    return glm::all(glm::lessThanEqual(glm::abs(a.albedo - b.albedo), glm::vec4(1e-6f))) &&
           near3(a.emissive, b.emissive, 1e-5f) && a.metallic == b.metallic &&
           a.roughness == b.roughness && a.specular == b.specular && a.doubleSided == b.doubleSided;
}

void compareWithReference(const std::string& builtin, const std::string& ref) {
    const gis::Scene b = gis::makeBuiltinScene(builtin);
    const gis::Scene r = gis::loadGltfFile(referenceScene(ref));
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();

    EXPECT_EQ(b.triangleCount(), r.triangleCount());
    EXPECT_TRUE(near3(b.bounds.min, r.bounds.min)) << builtin;
    EXPECT_TRUE(near3(b.bounds.max, r.bounds.max)) << builtin;
    EXPECT_EQ(b.background, glm::vec3(0.0f));

    // Materials as sets of (albedo, emission, parameters).
    ASSERT_EQ(b.materials.size(), r.materials.size());
    for (const auto& rm : r.materials) {
        bool found = false;
        for (const auto& bm : b.materials)
            found = found || (bm.name == rm.name && bm.baseColorFactor == rm.baseColorFactor &&
                              near3(bm.emissive, rm.emissive, 1e-6f) &&
                              bm.metallicFactor == rm.metallicFactor &&
                              bm.roughnessFactor == rm.roughnessFactor &&
                              bm.specularFactor == rm.specularFactor && bm.doubleSided == rm.doubleSided &&
                              bm.alphaMode == rm.alphaMode);
        EXPECT_TRUE(found) << "reference material " << rm.name << " missing from " << builtin;
    }

    // Same triangles (set equality up to tolerance; winding kept), each with the same material.
    std::vector<Tri> bt = worldTriangles(b), rt = worldTriangles(r);
    ASSERT_EQ(bt.size(), rt.size());
    std::vector<char> used(rt.size(), 0);
    for (const Tri& t : bt) {
        bool matched = false;
        for (size_t i = 0; i < rt.size() && !matched; ++i)
            if (!used[i] && same(t, rt[i])) used[i] = matched = true;
        EXPECT_TRUE(matched) << builtin << ": triangle (" << t.v[0].x << "," << t.v[0].y << ","
                             << t.v[0].z << ") has no match in the reference";
    }
    // Normals agree with the winding (single-sided quads face the inside of the box).
    for (const auto& p : b.primitives)
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            const auto& a = p.vertices[p.indices[i]];
            const glm::vec3 n = glm::cross(p.vertices[p.indices[i + 1]].position - a.position,
                                           p.vertices[p.indices[i + 2]].position - a.position);
            EXPECT_GT(glm::dot(n, a.normal), 0.0f);
        }

    ASSERT_EQ(b.lights.size(), r.lights.size());
    for (size_t i = 0; i < b.lights.size(); ++i) {
        EXPECT_EQ(b.lights[i].type, r.lights[i].type);
        EXPECT_TRUE(near3(b.lights[i].position, r.lights[i].position));
        EXPECT_EQ(b.lights[i].color, r.lights[i].color);
        EXPECT_FLOAT_EQ(b.lights[i].intensity, r.lights[i].intensity);
        EXPECT_EQ(b.lights[i].range, r.lights[i].range);
        EXPECT_EQ(b.lights[i].name, r.lights[i].name);
    }
    ASSERT_EQ(b.cameras.size(), 1u);
    ASSERT_EQ(r.cameras.size(), 1u);
    const gis::Camera &bc = b.cameras[0], &rc = r.cameras[0];
    EXPECT_FALSE(bc.orthographic);
    EXPECT_FLOAT_EQ(bc.yfov, rc.yfov);
    EXPECT_FLOAT_EQ(bc.znear, rc.znear);
    EXPECT_FLOAT_EQ(bc.zfar, rc.zfar);
    for (int c = 0; c < 4; ++c)
        EXPECT_TRUE(near3(glm::vec3(bc.cameraToWorld[c]), glm::vec3(rc.cameraToWorld[c]), 1e-6f));
    EXPECT_TRUE(near3(glm::vec3(bc.cameraToWorld[3]), glm::vec3(0.0f, 1.0f, 3.9f), 1e-6f));
}

}  // namespace

TEST(Builtin, Names) {
    EXPECT_EQ(gis::builtinSceneNames(), (std::vector<std::string>{"cornell", "cornell-area", "brdf-gallery", "leak", "room",
                                                                  "mirror", "atrium", "building"}));
}

namespace {

// Distance along the unit ray to the nearest triangle (Moller & Trumbore 1997), or infinity.
float nearestHit(const std::vector<Tri>& tris, glm::vec3 o, glm::vec3 d) {
    float best = std::numeric_limits<float>::infinity();
    for (const Tri& tri : tris) {
        const glm::vec3 e1 = tri.v[1] - tri.v[0], e2 = tri.v[2] - tri.v[0], p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 s = o - tri.v[0];
        const float u = glm::dot(s, p) / det;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) / det, hit = glm::dot(e2, q) / det;
        if (u >= 0.0f && v >= 0.0f && u + v <= 1.0f && hit > 0.0f) best = std::min(best, hit);
    }
    return best;
}

}  // namespace

// builtin:building's leak cameras: the dark one stands in a room no ray leaves (every direction
// meets a wall, the floor or the roof within the room's diagonal), the lit one sees the sky
// through a window. What the leak number divides is then light that came through a wall.
TEST(Builtin, BuildingsClosedRoomHasNoOpening) {
    const gis::Scene s = gis::makeBuiltinScene("building");
    ASSERT_GE(s.leakCameras.dark, 0);
    ASSERT_GE(s.leakCameras.lit, 0);
    const std::vector<Tri> tris = worldTriangles(s);
    auto escapes = [&](int camera, float reach) {
        const glm::vec3 eye(s.cameras[size_t(camera)].cameraToWorld[3]);
        int escaped = 0;
        constexpr int kRays = 2000;  // a spherical Fibonacci set
        for (int i = 0; i < kRays; ++i) {
            const float z = 1.0f - 2.0f * (float(i) + 0.5f) / kRays, r = std::sqrt(1.0f - z * z);
            const float phi = 2.39996323f * float(i);
            escaped += nearestHit(tris, eye, glm::vec3(r * std::cos(phi), z, r * std::sin(phi))) > reach;
        }
        return escaped;
    };
    EXPECT_EQ(escapes(s.leakCameras.dark, 15.0f), 0) << "the closed room has an opening";
    EXPECT_GT(escapes(s.leakCameras.lit, 100.0f), 0) << "the corridor sees no sky";
}

// The BRDF chart: 6 rows x 10 spheres, each row one BRDF combination (per-material override), the
// columns roughness 0..1 dielectric then metal, on a Lambert floor, one directional light.
TEST(Builtin, BrdfGalleryLayout) {
    const gis::Scene s = gis::makeBuiltinScene("brdf-gallery");
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, gis::LightType::Directional);
    ASSERT_EQ(s.cameras.size(), 1u);
    ASSERT_EQ(s.materials.size(), 62u);
    std::set<int> diffuse, specular;
    for (int i = 0; i < 60; ++i) {
        const gis::Material& m = s.materials[i];
        EXPECT_EQ(m.roughnessFactor, 0.25f * float(i % 5)) << m.name;
        EXPECT_EQ(m.metallicFactor, (i % 10) >= 5 ? 1.0f : 0.0f) << m.name;
        EXPECT_EQ(m.diffuseModel, s.materials[(i / 10) * 10].diffuseModel) << "one combination per row";
        EXPECT_EQ(m.specularModel, s.materials[(i / 10) * 10].specularModel) << "one combination per row";
        diffuse.insert(m.diffuseModel);
        specular.insert(m.specularModel);
    }
    EXPECT_EQ(diffuse, (std::set<int>{0, 1, 2, 3})) << "every diffuse model appears";
    EXPECT_EQ(specular, (std::set<int>{0, 1, 2, 3})) << "every specular model appears";
    for (int i = 60; i < 62; ++i) EXPECT_EQ(s.materials[i].specularModel, 3) << "the floor has no specular";
    // Spheres: unit normals pointing away from the centre, winding that agrees with them.
    for (const auto& p : s.primitives) {
        if (p.material >= 60) continue;
        for (const auto& v : p.vertices) {
            EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
            EXPECT_GT(glm::dot(v.normal, v.position), 0.0f);
        }
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            const auto& a = p.vertices[p.indices[i]];
            const glm::vec3 n = glm::cross(p.vertices[p.indices[i + 1]].position - a.position,
                                           p.vertices[p.indices[i + 2]].position - a.position);
            EXPECT_GT(glm::dot(n, a.position), 0.0f);
        }
    }
}

TEST(Builtin, CornellMatchesCornellPointReference) {
    compareWithReference("cornell", "cornell_point");
    const gis::Scene b = gis::makeBuiltinScene("cornell");
    ASSERT_EQ(b.lights.size(), 1u);
    EXPECT_EQ(b.lights[0].position, glm::vec3(0.0f, 1.8f, 0.0f));
    EXPECT_FLOAT_EQ(b.lights[0].intensity, 1.2f);
    EXPECT_EQ(b.triangleCount(), 10u + 12u + 12u);
    for (const auto& m : b.materials) EXPECT_EQ(m.emissive, glm::vec3(0.0f));
}

TEST(Builtin, CornellAreaMatchesCornellBoxReference) {
    compareWithReference("cornell-area", "cornell_box");
    const gis::Scene b = gis::makeBuiltinScene("cornell-area");
    EXPECT_TRUE(b.lights.empty());
    EXPECT_EQ(b.triangleCount(), 10u + 2u + 12u + 12u);
    int emitters = 0;
    for (const auto& m : b.materials)
        if (m.emissive == glm::vec3(15.0f)) {
            ++emitters;
            EXPECT_EQ(m.baseColorFactor, glm::vec4(0, 0, 0, 1));
            EXPECT_FALSE(m.doubleSided);
        }
    EXPECT_EQ(emitters, 1);
}

// The GI test scenes: options change what they say, and only known options in range are taken.
TEST(Builtin, LeakSceneWallThicknessAndDoorway) {
    auto sharedWall = [](const gis::Scene& s) {
        float thinnest = 1e9f;  // the shared wall is the box whose x extent is smallest
        for (const auto& d : s.draws) thinnest = std::min(thinnest, std::abs(d.world[0][0]));
        return thinnest;
    };
    EXPECT_NEAR(sharedWall(gis::makeBuiltinScene("leak")), 0.02f, 1e-6f);
    EXPECT_NEAR(sharedWall(gis::makeBuiltinScene("leak?thickness=0.01")), 0.01f, 1e-6f);
    const gis::Scene door = gis::makeBuiltinScene("leak?thickness=0.05&doorway=1");
    EXPECT_EQ(door.draws.size(), gis::makeBuiltinScene("leak").draws.size() + 2) << "three boxes frame the doorway";
    ASSERT_EQ(door.lights.size(), 1u);
    EXPECT_LT(door.lights[0].position.x, 0.0f) << "the lamp is in the left room";
    EXPECT_THROW(gis::makeBuiltinScene("leak?thickness=0.001"), gis::Error);
    EXPECT_THROW(gis::makeBuiltinScene("leak?colour=1"), gis::Error);
    EXPECT_THROW(gis::makeBuiltinScene("leak?thickness"), gis::Error);
    EXPECT_THROW(gis::makeBuiltinScene("cornell?detail=2"), gis::Error);
}

TEST(Builtin, AtriumDetailScalesTrianglesPastOneMillion) {
    const size_t low = gis::makeBuiltinScene("atrium").triangleCount();
    EXPECT_GT(low, 10000u);
    EXPECT_LT(low, 20000u);
    const size_t high = gis::makeBuiltinScene("atrium?detail=10").triangleCount();
    EXPECT_GT(high, 1000000u);
    const gis::Scene a = gis::makeBuiltinScene("atrium");
    ASSERT_EQ(a.lights.size(), 1u);
    EXPECT_EQ(a.lights[0].type, gis::LightType::Directional);
    EXPECT_GT(a.background.b, 0.0f) << "a sky";
    EXPECT_THROW(gis::makeBuiltinScene("atrium?detail=13"), gis::Error);
}

TEST(Builtin, RoomIsClosedAndMirrorHasTwoMetalSpheres) {
    const gis::Scene room = gis::makeBuiltinScene("room");
    ASSERT_EQ(room.cameras.size(), 1u);
    const glm::vec3 eye(room.cameras[0].cameraToWorld[3]);
    EXPECT_TRUE(glm::all(glm::greaterThan(eye, room.bounds.min)) && glm::all(glm::lessThan(eye, room.bounds.max)))
        << "the camera is inside";
    const gis::Scene mirror = gis::makeBuiltinScene("mirror");
    int metals = 0;
    for (const auto& m : mirror.materials) metals += m.metallicFactor == 1.0f;
    EXPECT_EQ(metals, 2);
}
