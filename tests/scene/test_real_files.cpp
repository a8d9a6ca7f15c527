// Every real glTF under shared/assets/gltf/ (outside _edge_cases) loads, with triangle and
// material counts equal to what the file's JSON says (computed here independently of the
// loader, with nlohmann-json), plus feature checks on particular files.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "test_util.h"

using namespace gistest;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::vector<std::string> realFiles() {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(gltfDir())) {
        if (!e.is_regular_file()) continue;
        const std::string rel = fs::relative(e.path(), gltfDir()).string();
        if (rel.rfind("_edge_cases", 0) == 0) continue;
        const std::string ext = e.path().extension().string();
        if (ext == ".gltf" || ext == ".glb") out.push_back(rel);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Triangles drawn by the default scene, from the JSON alone: per node instance of a mesh, per
// primitive, indices (or POSITION) count / 3 for TRIANGLES, count - 2 for strips and fans.
size_t expectedTriangles(const json& j) {
    size_t total = 0;
    std::function<void(size_t)> visit = [&](size_t n) {
        const json& node = j["nodes"][n];
        if (node.contains("mesh"))
            for (const json& p : j["meshes"][node["mesh"].get<size_t>()]["primitives"]) {
                const size_t acc = p.contains("indices") ? p["indices"].get<size_t>()
                                                         : p["attributes"]["POSITION"].get<size_t>();
                const size_t count = j["accessors"][acc]["count"].get<size_t>();
                const int mode = p.value("mode", 4);
                total += mode == 4 ? count / 3 : (count >= 3 ? count - 2 : 0);
            }
        if (node.contains("children"))
            for (const json& c : node["children"]) visit(c.get<size_t>());
    };
    const size_t scene = j.value("scene", 0);
    for (const json& n : j["scenes"][scene]["nodes"]) visit(n.get<size_t>());
    return total;
}

bool hasWarning(const gis::Scene& s, const std::string& text) {
    for (const auto& w : s.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

gis::Scene load(const std::string& rel) { return gis::loadGltfFile(gltfDir() + "/" + rel); }

}  // namespace

TEST(RealFiles, AllLoadWithCountsFromTheirJson) {
    const std::vector<std::string> files = realFiles();
    ASSERT_GE(files.size(), 30u) << "shared assets not found under " << gltfDir();
    for (const std::string& rel : files) {
        SCOPED_TRACE(rel);
        const json j = readGltfJson(gltfDir() + "/" + rel);
        gis::Scene s;
        ASSERT_NO_THROW(s = load(rel));
        EXPECT_EQ(s.triangleCount(), expectedTriangles(j));
        EXPECT_EQ(s.materials.size(), j.contains("materials") ? j["materials"].size() : 0u);
        EXPECT_FALSE(s.bounds.empty());
        size_t nodeCameras = 0;
        for (const json& n : j["nodes"]) nodeCameras += n.contains("camera");
        EXPECT_EQ(s.cameras.size(), nodeCameras);
        for (const auto& p : s.primitives)
            for (const auto& v : p.vertices) {
                ASSERT_TRUE(finite(v.normal) && finite(glm::vec3(v.tangent)));
                ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f);
            }
        std::printf("  %-70s %7zu tris %3zu mats %2zu imgs %zu warnings\n", rel.c_str(),
                    s.triangleCount(), s.materials.size(), s.images.size(), s.warnings.size());
        for (const auto& w : s.warnings) std::printf("      warning: %s\n", w.c_str());
    }
}

TEST(RealFiles, Cameras) {
    // Cameras.gltf: perspective (yfov 0.7, znear 0.01, zfar 100) and orthographic (xmag = ymag
    // = 1), both on nodes translated to (0.5, 0.5, 3).
    const gis::Scene s = load("Cameras/Cameras.gltf");
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_FALSE(s.cameras[0].orthographic);
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7f);
    EXPECT_FLOAT_EQ(s.cameras[0].znear, 0.01f);
    EXPECT_FLOAT_EQ(s.cameras[0].zfar, 100.0f);
    EXPECT_TRUE(s.cameras[1].orthographic);
    EXPECT_FLOAT_EQ(s.cameras[1].xmag, 1.0f);
    EXPECT_FLOAT_EQ(s.cameras[1].ymag, 1.0f);
    for (const auto& c : s.cameras) EXPECT_EQ(glm::vec3(c.cameraToWorld[3]), glm::vec3(0.5f, 0.5f, 3.0f));
    // geosphere.gltf: one perspective camera with a rotated node.
    const gis::Scene g = load("VulkanSamplesAssets/geosphere.gltf");
    ASSERT_EQ(g.cameras.size(), 1u);
    EXPECT_FLOAT_EQ(g.cameras[0].yfov, 0.5033799372418416f);
    EXPECT_NEAR(glm::determinant(glm::mat3(g.cameras[0].cameraToWorld)), 1.0f, 1e-5f);
}

TEST(RealFiles, LightsFile) {
    // 04_lights.gltf names its nodes after lights but carries no KHR_lights_punctual data (the
    // Blender round-trip input has "extensions": {}), so no lights; nodes still load.
    const gis::Scene s = load("BlenderIO_roundtrip/04_lights/04_lights.gltf");
    EXPECT_TRUE(s.lights.empty());
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_EQ(s.triangleCount(), 2u);
    // The reference scene has the one real point light of the shared files.
    const gis::Scene p = gis::loadGltfFile(referenceScene("cornell_point"));
    ASSERT_EQ(p.lights.size(), 1u);
    EXPECT_EQ(p.lights[0].type, gis::LightType::Point);
    EXPECT_FLOAT_EQ(p.lights[0].intensity, 1.2f);
    EXPECT_EQ(p.lights[0].position, glm::vec3(0.0f, 1.8f, 0.0f));
}

TEST(RealFiles, VertexColors) {
    const gis::Scene s = load("BoxVertexColors/BoxVertexColors.glb");
    size_t coloured = 0, total = 0;
    for (const auto& p : s.primitives)
        for (const auto& v : p.vertices) {
            ++total;
            coloured += v.color != glm::vec4(1.0f);
            EXPECT_TRUE(v.color.r >= 0 && v.color.r <= 1 && v.color.a >= 0 && v.color.a <= 1);
        }
    EXPECT_GT(total, 0u);
    EXPECT_GT(coloured, total / 2);
}

TEST(RealFiles, AlphaMask) {
    const gis::Scene s = load("BlenderIO_roundtrip/01_alpha_mask/01_alpha_mask.gltf");
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].alphaMode, gis::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(s.materials[0].alphaCutoff, 0.42f);
    EXPECT_TRUE(s.materials[0].doubleSided);
    ASSERT_GE(s.materials[0].baseColorTexture, 0);
    EXPECT_TRUE(s.images[size_t(s.materials[0].baseColorTexture)].srgb);
    const gis::Scene b = load("BlenderIO_roundtrip/01_alpha_blend/01_alpha_blend.gltf");
    EXPECT_TRUE(hasWarning(b, "BLEND"));
}

TEST(RealFiles, EmissionStrength) {
    const gis::Scene s = load("BlenderIO_roundtrip/14_emission_strength/14_emission_strength.gltf");
    auto find = [&](const std::string& name) {
        for (const auto& m : s.materials)
            if (m.name == name) return m;
        ADD_FAILURE() << name;
        return gis::Material{};
    };
    // emissiveFactor (0.9, 0.8, 0.7) * emissiveStrength 5.
    const glm::vec3 e = find("pbrEmissiveStrength").emissive;
    EXPECT_NEAR(e.x, 4.5f, 1e-5f);
    EXPECT_NEAR(e.y, 4.0f, 1e-5f);
    EXPECT_NEAR(e.z, 3.5f, 1e-5f);
    EXPECT_NEAR(find("pbrEmissive").emissive.x, 0.9f, 1e-6f);  // no strength: factor only
    EXPECT_GE(find("pbrEmissiveStrengthTexture").emissiveTexture, 0);
    // It *requires* KHR_materials_pbrSpecularGlossiness: loaded with a warning, not an error.
    EXPECT_TRUE(hasWarning(s, "KHR_materials_pbrSpecularGlossiness"));
}

TEST(RealFiles, AnimatedMorphCubeWarns) {
    const gis::Scene s = load("AnimatedMorphCube/glTF/AnimatedMorphCube.gltf");
    EXPECT_TRUE(hasWarning(s, "animations"));
    EXPECT_TRUE(hasWarning(s, "morph targets"));
    // Each unsupported feature once.
    std::vector<std::string> w = s.warnings;
    std::sort(w.begin(), w.end());
    EXPECT_EQ(std::unique(w.begin(), w.end()), w.end());
}

TEST(RealFiles, TextureTransformWarns) {
    EXPECT_TRUE(hasWarning(load("BlenderIO_roundtrip/09_texture_transform/09_texture_transform.gltf"),
                           "KHR_texture_transform"));
}

TEST(RealFiles, DamagedHelmetTexturesAndTangents) {
    for (const char* rel : {"DamagedHelmet/glTF/DamagedHelmet.gltf", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb"}) {
        SCOPED_TRACE(rel);
        const gis::Scene s = load(rel);
        ASSERT_EQ(s.materials.size(), 1u);
        const gis::Material& m = s.materials[0];
        ASSERT_GE(m.baseColorTexture, 0);
        ASSERT_GE(m.normalTexture, 0);
        ASSERT_GE(m.emissiveTexture, 0);
        ASSERT_GE(m.metallicRoughnessTexture, 0);
        ASSERT_GE(m.occlusionTexture, 0);
        EXPECT_EQ(s.images.size(), 5u);
        EXPECT_TRUE(s.images[size_t(m.baseColorTexture)].srgb);
        EXPECT_TRUE(s.images[size_t(m.emissiveTexture)].srgb);
        EXPECT_FALSE(s.images[size_t(m.normalTexture)].srgb);
        EXPECT_FALSE(s.images[size_t(m.metallicRoughnessTexture)].srgb);
        for (const auto& img : s.images)
            EXPECT_EQ(img.rgba8.size(), size_t(img.width) * size_t(img.height) * 4);
        // No TANGENT in the file but a normal map: tangents generated, unit, orthogonal.
        for (const auto& v : s.primitives[0].vertices) {
            ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-3f);
            ASSERT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-3f);
        }
        EXPECT_EQ(s.triangleCount(), 15452u);  // accessors[0] (indices) count 46356 / 3
    }
}
