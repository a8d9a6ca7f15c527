// Hostile input that used to hang or load silently (the first hardening round): loading cost linear in the number
// of JSON elements, no blocking on a FIFO, and values the glTF spec forbids refused by name.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <stdexcept>
#include <string>

#include "scene/limits.h"
#include "test_util.h"

using namespace gistest;
namespace fs = std::filesystem;

namespace {

// AddressSanitizer makes the loader 5-10x slower (scene_asan_tests runs these tests too: 2.9 s
// and 10 s alone, more beside other tests); quadratic cost grows by the same factor (the old
// loader: 13 s and 16 s unsanitized), so the bounds scale with it.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kSlowdown = 8.0;
#else
constexpr double kSlowdown = 1.0;
#endif

double secondsToLoad(const std::string& json, gis::Scene* out = nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    gis::Scene s = loadString(json);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (out) *out = std::move(s);
    return dt;
}

// One private directory per test process, made by mkdtemp (a name nobody can predict or pre-create)
// and removed when the process ends.
std::string tempPath(const std::string& name) {
    struct PrivateDir {
        std::string path;
        PrivateDir() {
            std::string pattern = (fs::temp_directory_path() / "gis_hardening_XXXXXX").string();
            if (::mkdtemp(pattern.data())) path = pattern;
        }
        ~PrivateDir() {
            std::error_code ec;
            if (!path.empty()) fs::remove_all(path, ec);
        }
    };
    static const PrivateDir dir;
    if (dir.path.empty()) throw std::runtime_error("mkdtemp failed");
    return (fs::path(dir.path) / name).string();
}

}  // namespace

// 2*10^5 empty nodes took 8.7 s with the depth-limited callback parser (it rescans the parent
// array after each element, quadratic); linear parsing takes 0.6 s (2.9 s under AddressSanitizer).
// The bound leaves room for a loaded machine but not for quadratic cost.
TEST(Hardening, TwoHundredThousandEmptyNodesLoadQuickly) {
    std::string json = R"({"asset":{"version":"2.0"},"nodes":[)";
    const int n = 200000;
    json.reserve(size_t(n) * 3 + 64);
    for (int i = 0; i < n; ++i) json += i ? ",{}" : "{}";
    json += "]}";
    const double dt = secondsToLoad(json);
    std::printf("%d empty nodes: %.3f s\n", n, dt);
    EXPECT_LT(dt, 4.0 * kSlowdown);
}

// The same with every node an instance of one mesh (10.5 s before): the scene, node and draw
// bookkeeping must be linear too.
TEST(Hardening, TwoHundredThousandMeshInstancesLoadQuickly) {
    GltfBuilder b;
    const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int mesh = b.addMesh({{"attributes", {{"POSITION", pos}}}});
    const int n = 200000;
    for (int i = 0; i < n; ++i) b.addMeshNode(mesh, {{"translation", {i % 100, i / 100, 0}}});
    gis::Scene s;
    const double dt = secondsToLoad(b.json(), &s);
    std::printf("%d mesh instances: %.3f s\n", n, dt);
    EXPECT_EQ(s.draws.size(), size_t(n));
    EXPECT_LT(dt, 6.0 * kSlowdown);
}

// The nesting limit (tinygltf recurses on extras) still holds with the linear check, counting
// brackets inside strings as text.
TEST(Hardening, NestingLimitIgnoresBracketsInStrings) {
    std::string deep = R"({"asset":{"version":"2.0"},"extras":)";
    for (int i = 0; i < 100; ++i) deep += "[";
    for (int i = 0; i < 100; ++i) deep += "]";
    deep += "}";
    EXPECT_NE(errorOf([&] { loadString(deep); }).find("nested deeper than 64"), std::string::npos);

    std::string text = R"({"asset":{"version":"2.0","generator":"[[[[\"[[[[)";
    for (int i = 0; i < 100; ++i) text += "[{";
    text += R"("},"nodes":[]})";
    EXPECT_NO_THROW(loadString(text));
}

// Opening a FIFO for reading blocks until a writer comes: the loader must refuse it without
// opening it that way. Run in a thread so that a regression fails instead of hanging the suite.
TEST(Hardening, FifoIsRefusedWithoutBlocking) {
    const std::string path = tempPath("fifo.gltf");
    ::unlink(path.c_str());
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    auto result = std::async(std::launch::async, [&] { return errorOf([&] { gis::loadGltfFile(path); }); });
    if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
        std::ofstream unblock(path);  // let the blocked open return so the test can end
        ADD_FAILURE() << "loading a FIFO blocked";
    }
    const std::string err = result.get();
    EXPECT_NE(err.find("not a regular file"), std::string::npos) << err;
    EXPECT_EQ(err.rfind(path, 0), 0u) << err;
    ::unlink(path.c_str());
}

// Spec violations that tinygltf reads as "not given": refused, naming the element.
TEST(Hardening, NegativeByteStrideRefused) {
    GltfBuilder b;
    const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    b.j["bufferViews"][0]["byteStride"] = -12;
    b.addMeshNode(b.addMesh({{"attributes", {{"POSITION", pos}}}}));
    const std::string err = errorOf([&] { b.load(); });
    EXPECT_NE(err.find("bufferViews[0].byteStride is -12"), std::string::npos) << err;
    b.j["bufferViews"][0]["byteStride"] = 12;
    EXPECT_NO_THROW(b.load());
}

TEST(Hardening, ZeroLightRangeRefusedWhenUsed) {
    GltfBuilder b;
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"range", 0}}};
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.j["scenes"][0]["nodes"] = {0};
    const std::string err = errorOf([&] { b.load(); });
    EXPECT_NE(err.find("lights[0].range is 0"), std::string::npos) << err;
    b.j["extensions"]["KHR_lights_punctual"]["lights"][0].erase("range");  // absent: infinite
    EXPECT_EQ(b.load().lights.size(), 1u);
}

TEST(Hardening, ZeroCameraAspectRatioRefusedWhenUsed) {
    GltfBuilder b;
    b.j["cameras"] = {{{"type", "perspective"},
                       {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"aspectRatio", 0}}}}};
    b.addNode({{"camera", 0}});
    b.j["scenes"][0]["nodes"] = {0};
    const std::string err = errorOf([&] { b.load(); });
    EXPECT_NE(err.find("cameras[0].perspective.aspectRatio is 0"), std::string::npos) << err;
    b.j["cameras"][0]["perspective"]["aspectRatio"] = 1.5;
    EXPECT_EQ(b.load().cameras.size(), 1u);
}

// color x intensity is what the renderers use, in float: a product past FLT_MAX would be Inf.
TEST(Hardening, LightColorTimesIntensityOverflowRefused) {
    GltfBuilder b;
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    b.j["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1.0, 2.0, 1.0}}, {"intensity", 3e38}}};
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.j["scenes"][0]["nodes"] = {0};
    const std::string err = errorOf([&] { b.load(); });
    EXPECT_NE(err.find("light 0: color x intensity = 6e+38 overflows a float"), std::string::npos) << err;
    b.j["extensions"]["KHR_lights_punctual"]["lights"][0]["color"] = {1.0, 1.0, 1.0};
    EXPECT_EQ(b.load().lights.size(), 1u);  // 3e38 itself is finite
}

// Messages that used to name nothing: each names the element and the
// problem in one short line.
TEST(Hardening, BufferAndSchemaMessagesNameTheElement) {
    struct Case {
        const char* json;
        const char* expected;
    } cases[] = {
        {R"({})", "asset: missing"},
        {R"({"asset":{"version":"2.0"},"skins":[{}]})", "skins[0]: 'joints' is missing"},
        {R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4}]})", "buffers[0]: no uri"},
        {R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"http://example.com/a.bin"}]})",
         "buffers[0].uri 'http://example.com/a.bin' is not a relative file path"},
        {R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"data:application/x;base64,AAAA"}]})",
         "buffers[0].uri: data URI 'data:application/x;base64,AAAA' is not supported"},
        {R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"missing.bin"}]})",
         "buffers[0].uri 'missing.bin': No such file or directory"},
        {R"({"asset":{"version":"2.0"},"accessors":[{"count":1,"type":"SCALAR"}]})",
         "accessors[0]: 'componentType' is missing (required)"},
        {R"({"asset":{"version":"2.0"},"materials":[{},"material"]})", "materials[1] is \"material\", not an object"},
        {R"({"asset":{"version":"2.0"},"bufferViews":[{"buffer":0,"byteLength":1e300}]})",
         "bufferViews[0].byteLength is 1e+300"},
    };
    for (const Case& c : cases) {
        const std::string err = errorOf([&] { loadString(c.json); });
        EXPECT_NE(err.find(c.expected), std::string::npos) << c.json << " -> " << err;
        EXPECT_LE(err.size(), 200u) << err;
    }
    // A byteLength mismatch used to print the whole data: URI (700 characters of it).
    std::string big = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":17,"uri":"data:application/octet-stream;base64,)";
    big += std::string(4000, 'A') + "\"}]}";
    const std::string err = errorOf([&] { loadString(big); });
    EXPECT_NE(err.find("buffers[0]: byteLength is 17 but its data: URI decodes to 3000 bytes"), std::string::npos) << err;
    EXPECT_LE(err.size(), 200u) << err;
}

// znear far below the scene's depth used to render black (1e-7) or wrong (1e-6: mean 0.011
// against 0.056 at 0.01) without a word. Refused below 1e-6 of the depth, warned below 1e-4.
TEST(Hardening, TinyZnearRefusedOrWarnedRelativeToSceneDepth) {
    for (double znear : {0.01, 1e-5, 1e-6, 1e-8}) {
        GltfBuilder b;
        const int pos = b.addVec3({{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}});
        b.addMeshNode(b.addMesh({{"attributes", {{"POSITION", pos}}}}));
        b.j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", znear}}}}};
        b.addNode({{"camera", 0}, {"translation", {0, 0, 5}}});
        b.j["scenes"][0]["nodes"].push_back(1);
        gis::Scene s;
        const std::string err = errorOf([&] { s = b.load(); });
        std::string warnings;
        for (const std::string& w : s.warnings) warnings += w + "\n";
        if (znear >= 0.01) {
            EXPECT_EQ(err, "");
            EXPECT_EQ(warnings.find("znear"), std::string::npos) << warnings;
        } else if (znear >= 1e-5) {
            EXPECT_EQ(err, "");
            EXPECT_NE(warnings.find("camera 0: znear 1e-05"), std::string::npos) << warnings;
        } else {
            EXPECT_NE(err.find("camera 0: znear"), std::string::npos) << err;
            EXPECT_NE(err.find("the depth buffer cannot resolve that"), std::string::npos) << err;
        }
    }
}

namespace {
// A one-triangle scene whose material 0, 'glow', has `material` merged into it.
gis::Scene loadGlow(const nlohmann::json& material) {
    GltfBuilder b;
    const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    nlohmann::json m = {{"name", "glow"}};
    m.update(material);
    b.j["materials"] = {m};
    b.j["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    b.addMeshNode(b.addMesh({{"attributes", {{"POSITION", pos}}}, {"material", 0}}));
    return b.load();
}
}  // namespace

// glTF's emissiveFactor is in [0, 1]: a negative one gave negative radiance (-14.8 in the EXR).
TEST(Hardening, NegativeEmissiveFactorRefusedNamingTheMaterial) {
    const std::string err = errorOf([&] { loadGlow({{"emissiveFactor", {1.0, -0.5, 0.0}}}); });
    EXPECT_NE(err.find("material 0 ('glow'): emissiveFactor -0.5 is outside [0, 1]"), std::string::npos) << err;
    EXPECT_EQ(errorOf([&] { loadGlow({{"emissiveFactor", {1.0, 0.5, 0.0}}}); }), "");
}

// An emissive radiance past the renderer's radiance limit (3e38 speckled the direct term black):
// refused, whether it comes from the factor or KHR_materials_emissive_strength; the limit loads.
TEST(Hardening, EmissiveRadiancePastTheLimitRefused) {
    const nlohmann::json strong = {{"emissiveFactor", {1.0, 1.0, 1.0}},
                                   {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3e38}}}}}};
    std::string err = errorOf([&] { loadGlow(strong); });
    EXPECT_NE(err.find("material 0 ('glow'): emissive radiance 3e+38"), std::string::npos) << err;
    EXPECT_NE(err.find("1e+18"), std::string::npos) << err;
    nlohmann::json atLimit = strong;
    atLimit["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = double(gis::kMaxRadiance);
    EXPECT_EQ(errorOf([&] { loadGlow(atLimit); }), "");
    err = errorOf([&] { loadGlow({{"emissiveFactor", {3e38, 0.0, 0.0}}}); });
    EXPECT_NE(err.find("material 0 ('glow')"), std::string::npos) << err;
}
