// What a new user meets first: a glTF file
// without lights or cameras, camera flags, and the messages of the mistakes everyone makes once.
// Each case failed before its fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_util.h"
#include "image.h"

namespace gis::test {
namespace {

const std::string kBox = std::string(GIS_SHARED_DIR) + "/assets/gltf/Box/glTF/Box.gltf";

double meanLevel(const ImageU8& img) {
    double sum = 0.0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) sum += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
    return sum / double(img.rgba.size() / 4 * 3);
}

TEST(Newcomer, ALightlessFileGetsTheDefaultSunAndSkyAndSaysSo) {
    const std::string dir = tempDir("newcomer_light");
    const CliResult lit = runCli("render --scene " + kBox + " --size 48x48 --out " + dir + "/lit.png");
    ASSERT_EQ(lit.status, 0) << lit.err;
    EXPECT_EQ(countLines(lit.err), 1) << lit.err;
    EXPECT_NE(lit.err.find("added the default sun"), std::string::npos) << lit.err;
    const CliResult dark = runCli("render --scene " + kBox + " --size 48x48 --lighting scene --out " + dir + "/dark.png");
    ASSERT_EQ(dark.status, 0) << dark.err;
    EXPECT_EQ(dark.err.find("default sun"), std::string::npos);
    const double litMean = meanLevel(readPng(dir + "/lit.png")), darkMean = meanLevel(readPng(dir + "/dark.png"));
    std::printf("Box: mean level %.1f with the default light, %.1f with the scene's (none)\n", litMean, darkMean);
    EXPECT_GT(litMean, 3.0 * darkMean + 20.0);
    // The path tracer sees the same sun and sky.
    const CliResult traced = runCli("render --scene " + kBox + " --size 24x24 --gi pathtrace --spp 4 --out " + dir + "/pt.png");
    ASSERT_EQ(traced.status, 0) << traced.err;
    EXPECT_GT(meanLevel(readPng(dir + "/pt.png")), 20.0);
    EXPECT_NE(runCli("render --scene " + kBox + " --lighting sunny --out " + dir + "/x.png").status, 0);
}

TEST(Newcomer, CameraFlags) {
    const std::string dir = tempDir("newcomer_camera");
    // Box.gltf has no camera: --camera 1 is an error, not silently the default one.
    const CliResult none = runCli("render --scene " + kBox + " --camera 1 --out " + dir + "/x.png");
    EXPECT_NE(none.status, 0);
    EXPECT_NE(none.err.find("no cameras"), std::string::npos) << none.err;
    EXPECT_FALSE(fileExists(dir + "/x.png"));
    // --camera-pos / --look-at: looking at the Cornell box's back wall from inside, close up, the
    // image is the wall's white (no red or green wall in view).
    const CliResult close = runCli("render --scene builtin:cornell --size 32x32 --camera-pos 0,1,0 --look-at 0,1,-1 "
                                   "--fov 30 --out " + dir + "/close.exr");
    ASSERT_EQ(close.status, 0) << close.err;
    const ImageF wall = readExr(dir + "/close.exr");
    const float* c = wall.at(16, 16);
    EXPECT_NEAR(c[0] / c[1], 1.0, 0.05) << "the centre sees a white wall";
    EXPECT_NE(runCli("render --scene builtin:cornell --camera-pos 0,1,0 --out " + dir + "/y.png").status, 0);
    EXPECT_NE(runCli("render --scene builtin:cornell --camera-pos 0,1,0 --look-at 0,1,0 --out " + dir + "/y.png").status, 0);
    // --camera auto frames the bounds: a different image from the file's camera.
    ASSERT_EQ(runCli("render --scene builtin:cornell --size 32x32 --camera auto --out " + dir + "/auto.exr").status, 0);
    ASSERT_EQ(runCli("render --scene builtin:cornell --size 32x32 --out " + dir + "/file.exr").status, 0);
    EXPECT_NE(readExr(dir + "/auto.exr").rgba, readExr(dir + "/file.exr").rgba);
}

TEST(Newcomer, MessagesForCommonMistakes) {
    const std::string dir = tempDir("newcomer_messages");
    struct Case {
        std::string args, needle;
    };
    const std::vector<Case> cases = {
        {"render --scene builtin:cornell --size 100000x100000 --out " + dir + "/a.png", "out of range"},
        {"render --scene builtin:cornell --size -1x-1 --out " + dir + "/a.png", "out of range"},
        {"frobnicate", "unknown command 'frobnicate'"},
        {"render --scene " + std::string(GIS_SOURCE_DIR) + "/tests/golden/cornell_128.png --out " + dir + "/a.png",
         "not a glTF file"},
        {"render --scene builtin:cornell --out " + dir, "is a directory"},
        {"render --scene builtin:cornell --out /proc/no/such/a.png", "does not exist"},
        {"render --scene builtin:cornell --nosuchflag --out " + dir + "/a.png", "nosuchflag"},
    };
    for (const Case& c : cases) {
        const CliResult r = runCli(c.args);
        EXPECT_EQ(r.status, 1) << c.args << ": every failure exits 1";
        EXPECT_EQ(countLines(r.err), 1) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    }
    EXPECT_FALSE(fileExists(dir + "/a.png"));
    // Upper-case extensions are extensions.
    const CliResult upper = runCli("render --scene builtin:cornell --size 16x16 --out " + dir + "/b.PNG");
    EXPECT_EQ(upper.status, 0) << upper.err;
    EXPECT_TRUE(fileExists(dir + "/b.PNG"));
    // A parameter the chosen method does not use is a warning, not silence.
    const CliResult spp = runCli("render --scene builtin:cornell --size 16x16 --spp 8 --out " + dir + "/c.png");
    EXPECT_EQ(spp.status, 0);
    EXPECT_NE(spp.err.find("pathtrace.spp is a parameter of another method"), std::string::npos) << spp.err;
    const CliResult version = runCli("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.out.find("gisandbox "), std::string::npos);
}

TEST(Newcomer, InfoOnAnEmptySceneSaysEmpty) {
    const std::string dir = tempDir("newcomer_empty");
    std::ofstream(dir + "/empty.gltf") << R"({"asset": {"version": "2.0"}})";
    const CliResult r = runCli("info --no-gpu --scene " + dir + "/empty.gltf");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("bounds     empty"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("1e+30"), std::string::npos) << r.out;
}

// Two files whose glTF scenes carry the same internal name no longer overwrite each other's rows.
TEST(Newcomer, BenchNamesResultsByFileStem) {
    const std::string dir = tempDir("newcomer_bench");
    const std::string copy = dir + "/Box2.gltf";
    std::filesystem::copy_file(kBox, copy);
    std::filesystem::copy_file(std::string(GIS_SHARED_DIR) + "/assets/gltf/Box/glTF/Box0.bin", dir + "/Box0.bin");
    const CliResult r = runCli("bench --scenes " + kBox + "," + copy + " --size 16x16 --frames 2 --warmup 1 "
                               "--methods none --presets low --reference-spp 2 --out-dir " + dir + "/out");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fileExists(dir + "/out/Box_chart.png"));
    EXPECT_TRUE(fileExists(dir + "/out/Box2_chart.png"));
    const CliResult warm = runCli("bench --frames 2 --out-dir " + dir + "/out2");
    EXPECT_NE(warm.status, 0);
    EXPECT_NE(warm.err.find("default warm-up is 5"), std::string::npos) << warm.err;
}

}  // namespace
}  // namespace gis::test

namespace gis::test {
namespace {

// The built-in scenes written to glTF render the same through the loader: other renderers can
// load what we compare against. (The atrium's sky is not in glTF: --background gives it back.)
TEST(Export, BuiltinScenesRoundTripThroughGltf) {
    const std::string dir = tempDir("export_roundtrip");
    for (const char* scene : {"leak", "room", "mirror", "cornell-area", "atrium"}) {
        const std::string gltf = dir + "/" + scene + ".gltf";
        const CliResult w = runCli(std::string("export --scene builtin:") + scene + " --out " + gltf);
        ASSERT_EQ(w.status, 0) << w.err;
        EXPECT_TRUE(fileExists(dir + "/" + scene + ".bin"));
        const std::string sky = std::string(scene) == "atrium" ? " --background 0.35,0.45,0.6" : "";
        for (const std::string& spec : {std::string("builtin:") + scene, gltf}) {
            const std::string out = dir + "/" + scene + (spec == gltf ? "_file" : "_builtin") + ".exr";
            const CliResult r = runCli("render --scene " + spec + " --size 48x48 --hdr32 --lighting scene" + sky +
                                       " --out " + out);
            ASSERT_EQ(r.status, 0) << r.err;
        }
        const ImageF a = readExr(dir + "/" + scene + "_builtin.exr"), b = readExr(dir + "/" + scene + "_file.exr");
        double diff = 0.0, sum = 0.0;
        for (size_t i = 0; i < a.rgba.size(); ++i)
            if (i % 4 != 3) diff += std::abs(double(a.rgba[i]) - b.rgba[i]), sum += a.rgba[i];
        std::printf("%s: builtin vs exported glTF, mean |difference| %.4f%% of the mean\n", scene, 100.0 * diff / sum);
        EXPECT_LT(diff, 0.002 * sum) << scene;
    }
    EXPECT_NE(runCli("export --scene builtin:leak --out " + dir + "/x.glb").status, 0);
}

}  // namespace
}  // namespace gis::test
