// `--lighting auto` and emission: which scenes count as lit by their emitters. A model whose
// emission is a texture detail (DamagedHelmet) gets the default sun and sky like any unlit model;
// the emitter-lit Cornell boxes keep exactly their own light.
#include <gtest/gtest.h>

#include <cstdio>

#include "scene/scene_lighting.h"
#include "test_util.h"

namespace {

gis::Scene loadAny(const std::string& spec) { return gis::loadScene(spec); }

TEST(AutoLighting, EmitterLitScenesKeepTheirLightTextureEmissionDoesNot) {
    struct Case {
        std::string spec;
        bool emittersLight;
    };
    const std::vector<Case> cases = {
        {gistest::referenceScene("cornell_box"), true},
        {"builtin:cornell-area", true},
        {gistest::gltfDir() + "/DamagedHelmet/glTF/DamagedHelmet.gltf", false},
        {gistest::gltfDir() + "/DamagedHelmet/glTF-Binary/DamagedHelmet.glb", false},
        {gistest::gltfDir() + "/Box/glTF/Box.gltf", false},
        {gistest::gltfDir() + "/nvpro_CornellBox/cornellBox.gltf", true},
        {gistest::gltfDir() + "/BlenderIO_roundtrip/14_emission_strength/14_emission_strength.gltf", true},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.spec);
        const gis::Scene s = loadAny(c.spec);
        const double mean = gis::meanEmittedRadiance(s);
        std::printf("%-80s mean emitted radiance %.5f (floor %.3f)\n", c.spec.c_str(), mean, gis::kEmitterLightingFloor);
        EXPECT_EQ(gis::emissionLightsScene(s), c.emittersLight) << mean;
        // A margin of 3x on either side of the floor, so the rule is not a coin toss for these.
        if (c.emittersLight) EXPECT_GT(mean, 3.0 * gis::kEmitterLightingFloor);
        else EXPECT_LT(mean, gis::kEmitterLightingFloor / 3.0);
    }
}

TEST(AutoLighting, NoBuiltinSceneChangesItsLighting) {
    // Under the old rule any emissive material was the scene's light; every built-in scene is
    // built to be lit as it is, so the new rule must agree on all of them.
    for (const std::string& name : gis::builtinSceneNames()) {
        SCOPED_TRACE(name);
        const gis::Scene s = loadAny("builtin:" + name);
        bool emissive = false;
        for (const gis::Material& m : s.materials) emissive = emissive || m.emissive != glm::vec3(0.0f);
        std::printf("builtin:%-14s lights %zu, mean emitted radiance %.5f\n", name.c_str(), s.lights.size(),
                    gis::meanEmittedRadiance(s));
        EXPECT_EQ(gis::hasOwnLighting(s), !s.lights.empty() || emissive);
    }
}

TEST(AutoLighting, AutoAddsTheDefaultLightToDamagedHelmetOnly) {
    gis::Scene helmet = loadAny(gistest::gltfDir() + "/DamagedHelmet/glTF/DamagedHelmet.gltf");
    ASSERT_NE(helmet.materials[0].emissive, glm::vec3(0.0f)) << "the test needs an emissive helmet";
    EXPECT_TRUE(gis::applyLighting(helmet, gis::LightingMode::Auto));
    ASSERT_EQ(helmet.lights.size(), 1u);
    EXPECT_EQ(helmet.lights[0].type, gis::LightType::Directional);
    EXPECT_EQ(helmet.background, glm::vec3(gis::kDefaultSkyRadiance));

    gis::Scene box = loadAny(gistest::referenceScene("cornell_box"));
    const gis::Scene before = box;
    EXPECT_FALSE(gis::applyLighting(box, gis::LightingMode::Auto));
    EXPECT_TRUE(box.lights.empty());
    EXPECT_EQ(box.background, before.background);
    gis::Scene area = loadAny("builtin:cornell-area");
    const size_t lights = area.lights.size();
    EXPECT_FALSE(gis::applyLighting(area, gis::LightingMode::Auto));
    EXPECT_EQ(area.lights.size(), lights);
}

}  // namespace
