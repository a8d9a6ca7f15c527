// Golden images of the built-in scenes through both headless backends, and the two backends
// against each other. Goldens live in tests/golden/ and change only with a stated reason: to
// regenerate after an intended change, run this test with GIS_UPDATE_GOLDEN=1 and commit the
// images with a message that says why they changed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "cli_util.h"
#include "image.h"

namespace gis::test {
namespace {

struct Tolerance {
    double meanAbs;        // mean |difference| over all channels, in 8-bit levels
    double outlierShare;   // share of pixels allowed to differ by more than `outlierLevels`
    int outlierLevels;
};

struct Comparison {
    double meanAbs = 0.0;
    double outlierShare = 0.0;
};

Comparison compare(const ImageU8& a, const ImageU8& b, int outlierLevels) {
    Comparison c;
    size_t outliers = 0;
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (int k = 0; k < 3; ++k) {
            const int d = std::abs(int(a.rgba[i * 4 + k]) - int(b.rgba[i * 4 + k]));
            c.meanAbs += d;
            worst = std::max(worst, d);
        }
        outliers += worst > outlierLevels;
    }
    c.meanAbs /= double(pixels * 3);
    c.outlierShare = double(outliers) / double(pixels);
    return c;
}

struct GoldenCase {
    const char* scene;
    const char* backend;
    Tolerance tolerance;
    const char* size = "128x128";
    const char* golden = "128";  // tests/golden/SCENE_GOLDEN.png
    const char* flags = "";      // more render flags
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.scene << " via " << c.backend; }

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, MatchesCommittedImage) {
    const GoldenCase& c = GetParam();
    const std::string dir = tempDir(std::string("golden_") + c.scene + "_" + c.backend);
    const std::string out = dir + "/render.png";
    CliResult r = runCli(std::string("render --scene builtin:") + c.scene + " --size " + c.size + " --backend " +
                         c.backend + " --out " + out + c.flags);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string golden = std::string(GIS_SOURCE_DIR) + "/tests/golden/" + c.scene + "_" + c.golden + ".png";
    const char* update = std::getenv("GIS_UPDATE_GOLDEN");
    if (update && std::string(update) == "1" && std::string(c.backend) == "osmesa") {
        std::filesystem::copy_file(out, golden, std::filesystem::copy_options::overwrite_existing);
        GTEST_SKIP() << "golden written: " << golden;
    }
    ASSERT_TRUE(fileExists(golden)) << golden << " is missing (GIS_UPDATE_GOLDEN=1 writes it)";
    const ImageU8 expected = readPng(golden), actual = readPng(out);
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    const Comparison d = compare(actual, expected, c.tolerance.outlierLevels);
    std::printf("%s via %s: mean |diff| %.4f levels, %.4f%% pixels off by > %d levels\n", c.scene, c.backend,
                d.meanAbs, 100.0 * d.outlierShare, c.tolerance.outlierLevels);
    EXPECT_LE(d.meanAbs, c.tolerance.meanAbs);
    EXPECT_LE(d.outlierShare, c.tolerance.outlierShare);
}

// llvmpipe renders the same bits through either backend on one machine; the tolerance leaves room
// for another Mesa build's rounding (0.25 level on average, 0.5% of pixels off by more than 4 levels).
constexpr Tolerance kLlvmpipe{0.25, 0.005, 4};

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, Golden,
                         ::testing::Values(GoldenCase{"cornell", "osmesa", kLlvmpipe},
                                           GoldenCase{"cornell", "egl", kLlvmpipe},
                                           // The emitter through the G-buffer's emission only (as
                                           // before emitter lights); the lights mode has analytic
                                           // tests in tests/emitters/.
                                           GoldenCase{"cornell-area", "osmesa", kLlvmpipe, "128x128", "128", " --emitters gi"},
                                           GoldenCase{"cornell-area", "egl", kLlvmpipe, "128x128", "128", " --emitters gi"},
                                           // Every BRDF model, one row each (README, BRDF section).
                                           GoldenCase{"brdf-gallery", "osmesa", kLlvmpipe, "192x128", "192x128"},
                                           GoldenCase{"brdf-gallery", "egl", kLlvmpipe, "192x128", "192x128"},
                                           // The GI test scenes (README, Scenes).
                                           GoldenCase{"leak", "osmesa", kLlvmpipe},
                                           GoldenCase{"room", "osmesa", kLlvmpipe},
                                           GoldenCase{"mirror", "osmesa", kLlvmpipe},
                                           GoldenCase{"atrium", "osmesa", kLlvmpipe}),
                         [](const auto& info) {
                             std::string n = std::string(info.param.scene) + "_" + info.param.backend;
                             for (char& ch : n) if (ch == '-') ch = '_';
                             return n;
                         });

// The window backend (GLFW on GLX) under a virtual X server matches the same golden.
TEST(Backends, GlfwWindowUnderXvfbMatchesGolden) {
    const std::string dir = tempDir("golden_glfw");
    CliResult r = runCli("render --scene builtin:cornell --size 128x128 --backend glfw -v --out " + dir + "/glfw.png",
                         "xvfb-run -a");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("backend: glfw"), std::string::npos) << r.err;
    const ImageU8 expected = readPng(std::string(GIS_SOURCE_DIR) + "/tests/golden/cornell_128.png");
    const Comparison d = compare(readPng(dir + "/glfw.png"), expected, kLlvmpipe.outlierLevels);
    EXPECT_LE(d.meanAbs, kLlvmpipe.meanAbs);
    EXPECT_LE(d.outlierShare, kLlvmpipe.outlierShare);
}

// The same scene through EGL and OSMesa: linear radiance agrees to 1e-3 relative everywhere.
TEST(Backends, EglAndOSMesaAgree) {
    const std::string dir = tempDir("backends_agree");
    for (const char* backend : {"egl", "osmesa"}) {
        CliResult r = runCli(std::string("render --scene builtin:cornell --size 128x128 --hdr32 --backend ") + backend +
                             " --out " + dir + "/" + backend + ".exr -v");
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.err.find(std::string("backend: ") + backend), std::string::npos) << r.err;
    }
    const ImageF a = readExr(dir + "/egl.exr"), b = readExr(dir + "/osmesa.exr");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    double worst = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i)
        worst = std::max(worst, std::abs(double(a.rgba[i]) - b.rgba[i]) / std::max(1e-3, std::abs(double(b.rgba[i]))));
    std::printf("EGL vs OSMesa: worst relative difference %.2e\n", worst);
    EXPECT_LE(worst, 1e-3);
}

}  // namespace
}  // namespace gis::test
