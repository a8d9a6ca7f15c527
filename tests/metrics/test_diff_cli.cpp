// `gisandbox diff` as users run it, and the CPU tone mapping against the GPU's tonemap pass.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <limits>

#include "../render/cli_util.h"
#include "image.h"
#include "metrics.h"
#include "tonemap.h"

namespace gis {
namespace {

using test::countLines;
using test::fileExists;
using test::runCli;
using test::tempDir;

ImageF pattern(int w, int h, float gain) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.resize(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.at(x, y);
            p[0] = gain * (0.1f + 1.5f * float(x) / float(w));
            p[1] = gain * (0.2f + 0.6f * float(y) / float(h));
            p[2] = gain * ((x / 4 + y / 4) % 2 ? 0.8f : 0.05f);
            p[3] = 1.0f;
        }
    return img;
}

void expectOneLineError(const test::CliResult& r, const std::string& needle) {
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("gisandbox: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
}

class DiffCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = tempDir(std::string("metrics_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        ref = dir + "/ref.exr";
        test = dir + "/test.exr";
        writeExr(ref, pattern(48, 32, 1.0f));
        writeExr(test, pattern(48, 32, 1.1f));
    }
    std::string dir, ref, test;
};

TEST_F(DiffCli, PrintsTheTableAndWritesAHeatmap) {
    const std::string heat = dir + "/heat.png";
    const auto r = runCli("diff '" + test + "' '" + ref + "' --heatmap '" + heat + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    for (const char* row : {"RMSE", "relMSE", "PSNR linear", "PSNR sRGB", "SSIM", "FLIP", "wrote"})
        EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
    const ImageU8 png = readPng(heat);
    EXPECT_EQ(png.width, 48);
    EXPECT_EQ(png.height, 32);
    // With a colour bar the image grows below.
    const auto bar = runCli("diff '" + test + "' '" + ref + "' --heatmap '" + heat + "' --colorbar --metric rmse");
    ASSERT_EQ(bar.status, 0) << bar.err;
    EXPECT_GT(readPng(heat).height, 32);
    // No temporary files left beside it.
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 3);
}

TEST_F(DiffCli, JsonMatchesTheLibrary) {
    const auto r = runCli("diff '" + test + "' '" + ref + "' --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const ImageMetrics m = compareImages(readExr(test), readExr(ref));
    EXPECT_NEAR(j["rmse"].get<double>(), m.rmse, 1e-9);
    EXPECT_NEAR(j["relmse"].get<double>(), m.relMse, 1e-9);
    EXPECT_NEAR(j["psnr_linear_db"].get<double>(), m.psnrLinear, 1e-6);
    EXPECT_NEAR(j["psnr_srgb_db"].get<double>(), m.psnrSrgb, 1e-6);
    EXPECT_NEAR(j["ssim"].get<double>(), m.ssim, 1e-9);
    EXPECT_NEAR(j["flip"].get<double>(), m.flip, 1e-9);
    EXPECT_GT(m.flip, 0.0);
    EXPECT_EQ(j["tonemap"], "aces");
    EXPECT_EQ(j["pixels"], 48 * 32);
}

TEST_F(DiffCli, IdenticalImagesPrintInfAndJsonNull) {
    const auto r = runCli("diff '" + ref + "' '" + ref + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("inf"), std::string::npos) << r.out;
    const auto j = runCli("diff '" + ref + "' '" + ref + "' --json");
    ASSERT_EQ(j.status, 0) << j.err;
    const auto doc = nlohmann::json::parse(j.out);
    EXPECT_TRUE(doc["psnr_linear_db"].is_null());
    EXPECT_TRUE(doc["psnr_srgb_db"].is_null());
    EXPECT_EQ(doc["rmse"].get<double>(), 0.0);
    EXPECT_EQ(doc["flip"].get<double>(), 0.0);
    EXPECT_EQ(doc["ssim"].get<double>(), 1.0);
}

TEST_F(DiffCli, PngInputsAreDecodedFromSrgb) {
    const std::string a = dir + "/a.png", b = dir + "/b.png";
    writePng(a, toLdrImage(pattern(48, 32, 1.0f), {}));
    writePng(b, toLdrImage(pattern(48, 32, 0.8f), {}));
    const auto same = runCli("diff '" + a + "' '" + a + "' --json");
    ASSERT_EQ(same.status, 0) << same.err;
    const auto s = nlohmann::json::parse(same.out);
    EXPECT_TRUE(s["psnr_srgb_db"].is_null());
    EXPECT_EQ(s["tonemap"], "linear");  // auto: a PNG is already display-referred
    const auto r = runCli("diff '" + a + "' '" + b + "' --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    // With the linear clamp, PSNR sRGB is PSNR of the PNGs' own 8-bit values.
    const ImageU8 pa = readPng(a), pb = readPng(b);
    double mse = 0.0;
    for (size_t i = 0; i < pa.rgba.size(); ++i)
        if (i % 4 != 3) mse += std::pow((double(pa.rgba[i]) - double(pb.rgba[i])) / 255.0, 2.0);
    mse /= double(pa.rgba.size() / 4 * 3);
    EXPECT_NEAR(j["psnr_srgb_db"].get<double>(), 10.0 * std::log10(1.0 / mse), 1e-3);
}

TEST_F(DiffCli, MaskLeavesPixelsOut) {
    // Differ in the left half only, and mask the left half: nothing left to see.
    ImageF t = pattern(48, 32, 1.0f);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 24; ++x) t.at(x, y)[0] += 0.5f;
    writeExr(test, t);
    ImageU8 mask;
    mask.width = 48;
    mask.height = 32;
    mask.rgba.assign(48 * 32 * 4, 0);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 24; ++x) mask.rgba[(size_t(y) * 48 + x) * 4] = 255;
    writePng(dir + "/mask.png", mask);
    const auto r = runCli("diff '" + test + "' '" + ref + "' --mask '" + dir + "/mask.png' --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["pixels"], 24 * 32);
    EXPECT_EQ(j["rmse"].get<double>(), 0.0);
}

TEST_F(DiffCli, ErrorsAreOneLineAndLeaveNoHeatmap) {
    const std::string heat = dir + "/heat.png";
    const std::string h = " --heatmap '" + heat + "'";
    expectOneLineError(runCli("diff '" + dir + "/missing.exr' '" + ref + "'" + h), "does not exist");
    expectOneLineError(runCli("diff '" + test + "' '" + dir + "/missing.png'" + h), "does not exist");
    writeExr(dir + "/small.exr", pattern(16, 16, 1.0f));
    expectOneLineError(runCli("diff '" + dir + "/small.exr' '" + ref + "'" + h), "is 16x16 but the reference");
    ImageF nan = pattern(48, 32, 1.0f);
    nan.at(4, 2)[1] = std::numeric_limits<float>::quiet_NaN();
    writeExr(dir + "/nan.exr", nan);
    expectOneLineError(runCli("diff '" + dir + "/nan.exr' '" + ref + "'" + h), "NaN at pixel (4, 2)");
    {
        std::FILE* f = std::fopen((dir + "/junk.exr").c_str(), "wb");
        std::fputs("not an exr\n", f);
        std::fclose(f);
    }
    expectOneLineError(runCli("diff '" + dir + "/junk.exr' '" + ref + "'" + h), "junk.exr");
    expectOneLineError(runCli("diff '" + test + "' '" + ref + "'" + h + " --metric mse"), "unknown metric 'mse'");
    expectOneLineError(runCli("diff '" + test + "' '" + ref + "'" + h + " --tonemap filmic"), "--tonemap");
    expectOneLineError(runCli("diff '" + test + "' '" + ref + "'" + h + " --ppd 0"), "--ppd");
    expectOneLineError(runCli("diff '" + test + "' '" + ref + "' --heatmap '" + dir + "/no/such/dir/h.png'"),
                       "does not exist");
    expectOneLineError(runCli("diff '" + test + "' '" + ref + "' --heatmap '" + dir + "/h.jpg'"), ".png");
    expectOneLineError(runCli("diff '" + test + "'"), "reference");
    EXPECT_FALSE(fileExists(heat));
}

// The shared Cycles references: adding bounces brings an image closer to the full solution, so
// every metric must rank `bounce1` closer to `full` than `direct` is.
TEST(DiffReferences, MoreBouncesAreCloserToTheFullSolution) {
    const std::string dir = std::string(GIS_SHARED_DIR) + "/assets/reference/refs/cornell_box";
    // A missing reference is a failure, not a skip: CI must not pass without the comparison.
    for (const char* pass : {"full", "direct", "bounce1"})
        ASSERT_TRUE(fileExists(dir + "/" + pass + ".exr")) << "missing Cycles reference " << dir << "/" << pass
                                                           << ".exr (../shared must be checked out)";
    const ImageF full = readExr(dir + "/full.exr");
    const ImageMetrics direct = compareImages(readExr(dir + "/direct.exr"), full);
    const ImageMetrics bounce1 = compareImages(readExr(dir + "/bounce1.exr"), full);
    EXPECT_LT(bounce1.rmse, direct.rmse);
    EXPECT_LT(bounce1.relMse, direct.relMse);
    EXPECT_GT(bounce1.psnrLinear, direct.psnrLinear);
    EXPECT_GT(bounce1.psnrSrgb, direct.psnrSrgb);
    EXPECT_GT(bounce1.ssim, direct.ssim);
    EXPECT_LT(bounce1.flip, direct.flip);
    EXPECT_TRUE(direct.flip > 0.0 && direct.flip < 1.0);
}

// tonemap.cpp mirrors shaders/tonemap.frag: the PNG the GPU writes equals the CPU tone mapping of
// the EXR of the same frame (within one 8-bit level: float rounding differs between the two).
TEST(TonemapMirror, CpuToneMappingMatchesTheGpuPass) {
    const std::string dir = tempDir("metrics_TonemapMirror");
    for (const char* tm : {"aces", "linear"}) {
        const std::string args = std::string("render --scene builtin:cornell --size 48x48 --backend osmesa") +
                                 " --exposure 1.5 --tonemap " + tm;
        const auto exr = runCli(args + " --out '" + dir + "/f.exr'");
        ASSERT_EQ(exr.status, 0) << exr.err;
        const auto png = runCli(args + " --out '" + dir + "/f.png'");
        ASSERT_EQ(png.status, 0) << png.err;
        DisplaySettings display;
        display.tonemap = std::string(tm) == "aces" ? Tonemapper::Aces : Tonemapper::Linear;
        display.exposureEV = 1.5f;
        const ImageU8 cpu = toLdrImage(readExr(dir + "/f.exr"), display);
        const ImageU8 gpu = readPng(dir + "/f.png");
        ASSERT_EQ(cpu.rgba.size(), gpu.rgba.size());
        int worst = 0, lit = 0;
        for (size_t i = 0; i < cpu.rgba.size(); ++i) {
            if (i % 4 == 3) continue;
            worst = std::max(worst, std::abs(int(cpu.rgba[i]) - int(gpu.rgba[i])));
            lit += gpu.rgba[i] > 20;
        }
        EXPECT_LE(worst, 1) << tm;
        EXPECT_GT(lit, 1000) << tm;  // the frame is not black
    }
}

}  // namespace
}  // namespace gis
