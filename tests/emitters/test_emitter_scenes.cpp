// The emitter scenes other checks rely on: builtin:cornell-area?emitter-size=S keeps the emitter's
// power, builtin:room?lamp=panel has the point lamp's power, and the scenes without options are
// unchanged.
#include <gtest/gtest.h>

#include "scene/scene.h"

namespace gis {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct EmitterSum {
    double power = 0.0;  // one-sided Lambertian emitters: pi * L * area (luminance-free: channel R)
    double area = 0.0;
    float radiance = 0.0f;
};

EmitterSum emitters(const Scene& s) {
    EmitterSum e;
    for (const DrawItem& d : s.draws) {
        const Primitive& p = s.primitives[d.primitive];
        if (p.material < 0 || s.materials[p.material].emissive.r <= 0.0f) continue;
        e.radiance = s.materials[p.material].emissive.r;
        for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
            const glm::vec3 a = glm::vec3(d.world * glm::vec4(p.vertices[p.indices[t]].position, 1.0f));
            const glm::vec3 b = glm::vec3(d.world * glm::vec4(p.vertices[p.indices[t + 1]].position, 1.0f));
            const glm::vec3 c = glm::vec3(d.world * glm::vec4(p.vertices[p.indices[t + 2]].position, 1.0f));
            const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
            e.area += area;
            e.power += kPi * e.radiance * area;
        }
    }
    return e;
}

TEST(EmitterScenes, CornellAreaDefaultIsTheReferenceQuad) {
    const EmitterSum e = emitters(makeBuiltinScene("cornell-area"));
    EXPECT_EQ(e.radiance, 15.0f);
    EXPECT_NEAR(e.area, 0.25, 1e-6);
    const EmitterSum same = emitters(makeBuiltinScene("cornell-area?emitter-size=0.5"));
    EXPECT_NEAR(same.power, e.power, 1e-6 * e.power);
}

TEST(EmitterScenes, CornellAreaEmitterSizeKeepsThePower) {
    const EmitterSum reference = emitters(makeBuiltinScene("cornell-area"));
    for (const char* size : {"0.04", "0.2", "1"}) {
        const EmitterSum e = emitters(makeBuiltinScene(std::string("cornell-area?emitter-size=") + size));
        EXPECT_NEAR(e.area, std::stod(size) * std::stod(size), 1e-6) << size;
        EXPECT_NEAR(e.power, reference.power, 1e-4 * reference.power) << size;
    }
    EXPECT_THROW(makeBuiltinScene("cornell-area?emitter-size=0"), Error);
    EXPECT_THROW(makeBuiltinScene("cornell-area?size=1"), Error);
}

TEST(EmitterScenes, CornellAreaEmitterTilesKeepTheLightAndCountTheTriangles) {
    // emitter-tiles=K: the bench's emissive-triangle sweep (2 K^2 triangles) over the same light.
    const EmitterSum reference = emitters(makeBuiltinScene("cornell-area"));
    for (int tiles : {1, 7, 71}) {
        const Scene s = makeBuiltinScene("cornell-area?emitter-tiles=" + std::to_string(tiles));
        const EmitterSum e = emitters(s);
        EXPECT_NEAR(e.area, 0.25, 1e-5) << tiles;
        EXPECT_NEAR(e.power, reference.power, 1e-4 * reference.power) << tiles;
        size_t triangles = 0;
        for (const DrawItem& d : s.draws)
            if (s.materials[s.primitives[d.primitive].material].emissive.r > 0.0f)
                triangles += s.primitives[d.primitive].indices.size() / 3;
        EXPECT_EQ(triangles, size_t(2 * tiles * tiles)) << tiles;
    }
    for (const char* bad : {"0", "101", "2.5"})
        EXPECT_THROW(makeBuiltinScene(std::string("cornell-area?emitter-tiles=") + bad), Error) << bad;
}

TEST(EmitterScenes, RoomPanelHasTheLampsPower) {
    const Scene point = makeBuiltinScene("room");
    ASSERT_EQ(point.lights.size(), 1u);
    const double lampPower = 4 * kPi * point.lights[0].intensity;  // isotropic point light, W
    const Scene panel = makeBuiltinScene("room?lamp=panel");
    EXPECT_TRUE(panel.lights.empty());
    EXPECT_NEAR(emitters(panel).power, lampPower, 1e-4 * lampPower);
    EXPECT_EQ(emitters(makeBuiltinScene("room?lamp=point")).area, 0.0);
    EXPECT_THROW(makeBuiltinScene("room?lamp=candle"), Error);
}

}  // namespace
}  // namespace gis
