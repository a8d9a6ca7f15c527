// Metrics on synthetic images with answers known in closed form (renderer/metrics.h).
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>

#include "metrics.h"
#include "scene/scene.h"
#include "tonemap.h"

namespace gis {
namespace {

ImageF solid(int w, int h, glm::vec3 c) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.resize(size_t(w) * h * 4);
    for (size_t p = 0; p < size_t(w) * h; ++p) {
        img.rgba[p * 4] = c.x;
        img.rgba[p * 4 + 1] = c.y;
        img.rgba[p * 4 + 2] = c.z;
        img.rgba[p * 4 + 3] = 1.0f;
    }
    return img;
}

ImageF generate(int w, int h, const std::function<glm::vec3(int, int)>& f) {
    ImageF img = solid(w, h, glm::vec3(0.0f));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 c = f(x, y);
            for (int k = 0; k < 3; ++k) img.at(x, y)[k] = c[k];
        }
    return img;
}

// Deterministic noise in [-1, 1].
struct Lcg {
    uint64_t s;
    float next() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return float((s >> 40) & 0xFFFFFF) / float(0xFFFFFF) * 2.0f - 1.0f;
    }
};

// Grey ramp with a few edges: something for the feature detectors to see.
ImageF structured(int w, int h) {
    return generate(w, h, [&](int x, int y) {
        float v = 0.2f + 0.5f * float(x) / float(w - 1);
        if ((x / 8 + y / 8) % 2) v *= 0.6f;
        return glm::vec3(v, 0.9f * v, 0.8f * v);
    });
}

ImageF withNoise(const ImageF& img, float amplitude, uint64_t seed) {
    ImageF out = img;
    Lcg rng{seed};
    for (size_t i = 0; i < out.rgba.size(); ++i)
        if (i % 4 != 3) out.rgba[i] = std::clamp(out.rgba[i] + amplitude * rng.next(), 0.0f, 1.0f);
    return out;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

// --- RMSE, relMSE, PSNR ---------------------------------------------------------------------

TEST(Metrics, IdenticalImagesHaveNoError) {
    const ImageF a = structured(40, 30);
    const ImageMetrics m = compareImages(a, a);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.relMse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnrLinear) && m.psnrLinear > 0);
    EXPECT_TRUE(std::isinf(m.psnrSrgb) && m.psnrSrgb > 0);
    EXPECT_DOUBLE_EQ(m.ssim, 1.0);
    EXPECT_EQ(m.flip, 0.0);
    EXPECT_EQ(m.pixels, 40 * 30);
    EXPECT_EQ(formatMetric(m.psnrLinear), "inf");
}

TEST(Metrics, AllBlackImagesAreIdenticalWithoutDividingByZero) {
    const ImageF black = solid(16, 16, glm::vec3(0.0f));
    const ImageMetrics m = compareImages(black, black);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.relMse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnrLinear));
    EXPECT_DOUBLE_EQ(m.ssim, 1.0);
    EXPECT_EQ(m.flip, 0.0);
}

TEST(Metrics, ConstantOffsetGivesKnownRmseAndPsnr) {
    const ImageF ref = solid(8, 8, glm::vec3(0.3f)), test = solid(8, 8, glm::vec3(0.4f));
    EXPECT_NEAR(rmse(test, ref), 0.1, 1e-7);
    EXPECT_NEAR(meanSquaredError(test, ref), 0.01, 1e-8);
    EXPECT_NEAR(psnr(test, ref), 20.0, 1e-5);                      // 10 log10(1 / 0.01)
    EXPECT_NEAR(psnr(test, ref, 2.0), 20.0 + 20.0 * std::log10(2.0), 1e-5);
    EXPECT_NEAR(compareImages(test, ref).psnrLinear, 20.0, 1e-5);  // default peak 1
    // Offset in one channel only: the mean runs over R, G and B.
    const ImageF oneChannel = solid(8, 8, glm::vec3(0.4f, 0.3f, 0.3f));
    EXPECT_NEAR(rmse(oneChannel, ref), std::sqrt(0.01 / 3.0), 1e-7);
    // Half the pixels off by 0.2: MSE 0.02.
    const ImageF half = generate(8, 8, [](int x, int) { return glm::vec3(x < 4 ? 0.5f : 0.3f); });
    EXPECT_NEAR(meanSquaredError(half, ref), 0.02, 1e-8);
    // Symmetric in test and reference.
    EXPECT_EQ(rmse(test, ref), rmse(ref, test));
}

TEST(Metrics, RelativeMseUsesTheReferenceAndEpsilon) {
    const ImageF ref = solid(4, 4, glm::vec3(0.5f)), test = solid(4, 4, glm::vec3(0.6f));
    EXPECT_NEAR(relativeMse(test, ref), 0.01 / (0.25 + 0.01), 1e-7);
    EXPECT_NEAR(relativeMse(test, ref, 1e-3), 0.01 / (0.25 + 1e-3), 1e-7);
    // The reference is the denominator: swapping changes the value.
    EXPECT_NEAR(relativeMse(ref, test), 0.01 / (0.36 + 0.01), 1e-7);
    // Black reference: epsilon alone, no division by zero.
    const ImageF black = solid(4, 4, glm::vec3(0.0f)), white = solid(4, 4, glm::vec3(1.0f));
    EXPECT_NEAR(relativeMse(white, black), 1.0 / 0.01, 1e-4);
    EXPECT_EQ(relativeMse(black, black), 0.0);
    // Relative: scaling both images scales nothing (for r^2 >> eps).
    const ImageF bigRef = solid(4, 4, glm::vec3(500.0f)), bigTest = solid(4, 4, glm::vec3(600.0f));
    EXPECT_NEAR(relativeMse(bigTest, bigRef), 0.04, 1e-6);
    EXPECT_NE(errorOf([&] { relativeMse(test, ref, 0.0); }), "(no error)");
}

TEST(Metrics, PsnrOfSrgbUsesTheDisplayTransform) {
    // Linear tone mapping, exposure 0: sRGB PSNR is plain PSNR of the encoded values.
    MetricOptions o;
    o.display.tonemap = Tonemapper::Linear;
    const ImageF ref = solid(8, 8, glm::vec3(srgbToLinear(0.5f))), test = solid(8, 8, glm::vec3(srgbToLinear(0.6f)));
    EXPECT_NEAR(compareImages(test, ref, o).psnrSrgb, 20.0, 1e-3);
    // Radiance far above 1 clamps to white on both sides: no visible difference.
    const ImageF hot = solid(8, 8, glm::vec3(5.0f)), hotter = solid(8, 8, glm::vec3(9.0f));
    EXPECT_TRUE(std::isinf(compareImages(hotter, hot, o).psnrSrgb));
    EXPECT_FALSE(std::isinf(compareImages(hotter, hot, o).psnrLinear));
    // Exposure -3 EV brings them back into range.
    o.display.exposureEV = -3.0f;
    EXPECT_FALSE(std::isinf(compareImages(hotter, hot, o).psnrSrgb));
}

TEST(Metrics, IgnoreMaskLeavesPixelsOutOfTheMeans) {
    const ImageF ref = solid(10, 10, glm::vec3(0.5f));
    ImageF test = ref;
    for (int k = 0; k < 3; ++k) test.at(2, 3)[k] = 0.9f;
    MetricOptions o;
    o.ignore.assign(100, 0);
    o.ignore[3 * 10 + 2] = 1;
    const ImageMetrics masked = compareImages(test, ref, o);
    EXPECT_EQ(masked.rmse, 0.0);
    EXPECT_EQ(masked.relMse, 0.0);
    EXPECT_TRUE(std::isinf(masked.psnrLinear));
    EXPECT_EQ(masked.pixels, 99);
    // The filtered metrics still see the pixel as a neighbour, but its own error is left out.
    const ImageMetrics full = compareImages(test, ref);
    EXPECT_GT(full.flip, masked.flip);
    EXPECT_LT(full.ssim, masked.ssim);
    EXPECT_NEAR(full.rmse, 0.4 / 10.0, 1e-6);  // sqrt(0.16 / 100)
}

// --- SSIM -----------------------------------------------------------------------------------

TEST(Ssim, ConstantImagesGiveTheLuminanceTerm) {
    // No variance anywhere: SSIM = (2ab + C1) / (a^2 + b^2 + C1), C1 = (0.01 * 1)^2.
    const double c1 = 1e-4;
    const ImageF a = solid(12, 9, glm::vec3(0.3f)), b = solid(12, 9, glm::vec3(0.5f));
    const double expected = (2 * 0.3 * 0.5 + c1) / (0.09 + 0.25 + c1);  // 0.88239
    EXPECT_NEAR(ssim(a, b), expected, 1e-6);
    const ErrorMap map = ssimMap(a, b);
    for (float v : map.values) EXPECT_NEAR(v, expected, 1e-6);
    EXPECT_DOUBLE_EQ(ssim(a, a), 1.0);
}

TEST(Ssim, ContrastChangeMatchesAHandComputedValue) {
    // 11x3 image of vertical stripes, columns alternating 0.2 (even x) and 0.8 (odd x); the test
    // image halves the contrast about 0.5 (0.35 / 0.65). At the centre column the 11-tap Gaussian
    // (sigma 1.5) fits exactly; rows are constant, so the cut vertical window does not matter.
    // With w(d) = exp(-d^2 / 4.5), d = -5..5, the odd columns (value 0.8) sit at even offsets:
    //   W8 = (1 + 2e^{-4/4.5} + 2e^{-16/4.5}) / sum w = 0.4999306,  W2 = 1 - W8 = 0.5000694
    //   mean_ref = 0.2 W2 + 0.8 W8, var_ref = W2 W8 (0.6)^2, var_test = var_ref / 4, cov = var_ref / 2
    //   SSIM = (2 m_t m_r + C1)(2 cov + C2) / ((m_t^2 + m_r^2 + C1)(var_t + var_r + C2)) = 0.8015873
    auto stripes = [](float lo, float hi) {
        return generate(11, 3, [=](int x, int) { return glm::vec3(x % 2 ? hi : lo); });
    };
    const ImageF ref = stripes(0.2f, 0.8f), test = stripes(0.35f, 0.65f);
    double w[11], sum = 0.0;
    for (int d = -5; d <= 5; ++d) sum += w[d + 5] = std::exp(-d * d / 4.5);
    const double w8 = (w[5] + w[3] + w[7] + w[1] + w[9]) / sum, w2 = 1.0 - w8;
    const double mr = 0.2 * w2 + 0.8 * w8, mt = 0.35 * w2 + 0.65 * w8;
    const double vr = w2 * w8 * 0.36, vt = vr / 4.0, cov = vr / 2.0;
    const double c1 = 1e-4, c2 = 9e-4;
    const double expected = (2 * mt * mr + c1) * (2 * cov + c2) / ((mt * mt + mr * mr + c1) * (vt + vr + c2));
    EXPECT_NEAR(expected, 0.8015873, 1e-6);
    const ErrorMap map = ssimMap(test, ref);
    for (int y = 0; y < 3; ++y) EXPECT_NEAR(map.at(5, y), expected, 1e-5) << "row " << y;
    // Symmetric, and below 1 for any contrast change.
    EXPECT_NEAR(ssimMap(ref, test).at(5, 1), expected, 1e-6);
    EXPECT_LT(ssim(test, ref), 1.0);
}

TEST(Ssim, FallsAsNoiseGrows) {
    const ImageF ref = structured(48, 48);
    double last = 1.0;
    for (float amp : {0.01f, 0.03f, 0.1f, 0.3f}) {
        const double s = ssim(withNoise(ref, amp, 7), ref);
        EXPECT_LT(s, last) << amp;
        last = s;
    }
}

// --- FLIP -----------------------------------------------------------------------------------

TEST(Flip, CielabOfTheSrgbPrimariesMatchesTheStandardValues) {
    // Published CIELAB (D65) coordinates of the sRGB primaries and white.
    auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 0.02; };
    EXPECT_TRUE(near(flipdetail::linearRgbToLab({1, 1, 1}), {100.0, 0.0, 0.0}));
    EXPECT_TRUE(near(flipdetail::linearRgbToLab({1, 0, 0}), {53.24, 80.09, 67.20}));
    EXPECT_TRUE(near(flipdetail::linearRgbToLab({0, 1, 0}), {87.73, -86.18, 83.18}));
    EXPECT_TRUE(near(flipdetail::linearRgbToLab({0, 0, 1}), {32.30, 79.19, -107.86}));
}

TEST(Flip, ColourErrorMapping) {
    // cmax = HyAB(Hunt(green), Hunt(blue))^0.7: the largest colour difference maps to exactly 1.
    const double greenBlue = flipdetail::huntHyab({0, 1, 0}, {0, 0, 1});
    EXPECT_NEAR(greenBlue, 203.297, 1e-2);  // |87.73 - 32.30| + |(-75.61, 72.98) - (25.58, -34.84)|
    EXPECT_NEAR(flipdetail::colorErrorFromHyab(greenBlue), 1.0, 1e-12);
    const double cmax = std::pow(greenBlue, 0.7);
    // The knee: pc * cmax (in HyAB^0.7) maps to pt = 0.95.
    EXPECT_NEAR(flipdetail::colorErrorFromHyab(std::pow(0.4 * cmax, 1.0 / 0.7)), 0.95, 1e-9);
    EXPECT_EQ(flipdetail::colorErrorFromHyab(0.0), 0.0);
    // Black against white: HyAB = 100 (L* 0 vs 100, no chroma), 100^0.7 = 25.12 above the knee:
    // 0.95 + (25.12 - 16.51) / (41.28 - 16.51) * 0.05 = 0.96738.
    EXPECT_NEAR(flipdetail::huntHyab({0, 0, 0}, {1, 1, 1}), 100.0, 1e-9);
    EXPECT_NEAR(flipdetail::colorErrorFromHyab(100.0), 0.967381, 1e-5);
}

TEST(Flip, IdenticalImagesGiveZero) {
    const ImageF a = structured(40, 40);
    const ErrorMap map = flipMap(a, a);
    for (float v : map.values) EXPECT_EQ(v, 0.0f);
    EXPECT_EQ(flip(a, a), 0.0);
}

TEST(Flip, UniformColoursGiveTheColourErrorAlone) {
    // Uniform images: the CSF filters keep the colour, the feature detectors see nothing, so every
    // pixel carries the colour error of the two colours.
    const ImageF black = solid(32, 24, glm::vec3(0.0f)), white = solid(32, 24, glm::vec3(1.0f));
    for (float v : flipMap(black, white).values) EXPECT_NEAR(v, 0.967381, 1e-5);
    const ImageF green = solid(16, 16, {0, 1, 0}), blue = solid(16, 16, {0, 0, 1});
    EXPECT_NEAR(flip(green, blue), 1.0, 1e-6);  // the paper's maximum colour difference
    // Grey 0.5 against 0.6 (linear): HyAB 5.769 -> 0.95 / (0.4 cmax) * 5.769^0.7 = 0.19622.
    EXPECT_NEAR(flip(solid(16, 16, glm::vec3(0.6f)), solid(16, 16, glm::vec3(0.5f))), 0.196218, 1e-5);
}

TEST(Flip, ErrorIsLocalAndStrongestAtEdges) {
    // Reference: a white 24x24 square on black; test: all black. Inside the square, far from its
    // edges, the error is black-vs-white (0.9674); at the edges the feature term pushes it higher;
    // more than the filter radii (10 px CSF, 9 px features at 67 ppd) outside, it is 0.
    const ImageF ref = generate(64, 64, [](int x, int y) {
        return glm::vec3(x >= 20 && x < 44 && y >= 20 && y < 44 ? 1.0f : 0.0f);
    });
    const ImageF test = solid(64, 64, glm::vec3(0.0f));
    const ErrorMap map = flipMap(test, ref);
    EXPECT_NEAR(map.at(32, 32), 0.967381, 2e-3);
    EXPECT_GT(map.at(20, 32), map.at(32, 32));
    EXPECT_GT(map.at(20, 32), 0.97);
    EXPECT_LE(map.at(20, 32), 1.0f);
    EXPECT_EQ(map.at(4, 4), 0.0f);
    EXPECT_EQ(map.at(60, 32), 0.0f);
    for (float v : map.values) EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
}

TEST(Flip, IsSymmetric) {
    // LDR-FLIP is symmetric by construction: HyAB and the feature term compare magnitudes with
    // absolute differences. (HDR-FLIP, which picks exposures from the reference, would not be.)
    const ImageF a = structured(40, 32), b = withNoise(a, 0.1f, 3);
    const ErrorMap ab = flipMap(a, b), ba = flipMap(b, a);
    for (size_t i = 0; i < ab.values.size(); ++i) ASSERT_EQ(ab.values[i], ba.values[i]) << i;
}

TEST(Flip, GrowsWithNoiseAmplitude) {
    const ImageF ref = structured(48, 48);
    double last = 0.0;
    for (float amp : {0.005f, 0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        const double f = flip(withNoise(ref, amp, 11), ref);
        EXPECT_GT(f, last) << amp;
        last = f;
    }
    EXPECT_LT(last, 1.0);
}

TEST(Flip, FineNoiseMattersLessFromFurtherAway) {
    // More pixels per degree = smaller pixels: the contrast sensitivity filters blur fine noise away.
    const ImageF ref = solid(48, 48, glm::vec3(0.4f)), test = withNoise(ref, 0.15f, 5);
    const double near = flip(test, ref, 20.0), standard = flip(test, ref, 67.0), far = flip(test, ref, 200.0);
    EXPECT_GT(near, standard);
    EXPECT_GT(standard, far);
}

// --- Input validation -----------------------------------------------------------------------

TEST(MetricsInput, BadInputIsOneClearLine) {
    const ImageF a = solid(8, 8, glm::vec3(0.5f)), small = solid(8, 4, glm::vec3(0.5f));
    EXPECT_EQ(errorOf([&] { compareImages(a, small); }), "test image is 8x8 but the reference image is 8x4");
    EXPECT_EQ(errorOf([&] { rmse(ImageF{}, a); }), "test image is empty (0x0)");
    ImageF nan = a;
    nan.at(3, 5)[1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(errorOf([&] { compareImages(a, nan); }), "reference image has NaN at pixel (3, 5), channel G");
    ImageF inf = a;
    inf.at(7, 0)[2] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(errorOf([&] { flip(inf, a); }), "test image has Inf at pixel (7, 0), channel B");
    ImageF nanAlpha = a;  // alpha is ignored, NaN or not
    nanAlpha.at(0, 0)[3] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(rmse(nanAlpha, a), 0.0);
    ImageF truncated = a;
    truncated.rgba.resize(10);
    EXPECT_NE(errorOf([&] { ssim(truncated, a); }).find("holds 10 floats"), std::string::npos);
    MetricOptions o;
    o.ignore.assign(10, 0);
    EXPECT_EQ(errorOf([&] { compareImages(a, a, o); }), "ignore mask has 10 entries for 8x8 pixels");
    o.ignore.assign(64, 1);
    EXPECT_EQ(errorOf([&] { compareImages(a, a, o); }), "ignore mask leaves out every pixel: nothing to compare");
    EXPECT_NE(errorOf([&] { flip(a, a, 0.0); }), "(no error)");
    EXPECT_NE(errorOf([&] { psnr(a, a, -1.0); }), "(no error)");
    EXPECT_EQ(errorOf([&] { parseErrorMetric("mse"); }), "unknown metric 'mse' (expected flip, rmse, relmse or ssim)");
    for (const char* name : {"flip", "rmse", "relmse", "ssim"})
        EXPECT_STREQ(errorMetricName(parseErrorMetric(name)), name);
}

TEST(MetricsInput, TinyImagesWork) {
    // Smaller than every filter: borders clamp (FLIP) or renormalise (SSIM).
    const ImageF a = solid(1, 1, glm::vec3(0.2f)), b = solid(1, 1, glm::vec3(0.3f));
    const ImageMetrics m = compareImages(a, b);
    EXPECT_NEAR(m.rmse, 0.1, 1e-6);
    EXPECT_GT(m.flip, 0.0);
    EXPECT_LT(m.ssim, 1.0);
    EXPECT_TRUE(std::isfinite(m.ssim) && std::isfinite(m.flip));
}

// --- Maps and heatmaps ----------------------------------------------------------------------

TEST(ErrorMaps, PerPixelValues) {
    const ImageF ref = solid(4, 2, glm::vec3(0.5f));
    ImageF test = ref;
    test.at(1, 1)[0] = 0.8f;  // one channel off by 0.3
    const ErrorMap r = errorMap(test, ref, ErrorMetric::Rmse);
    EXPECT_NEAR(r.at(1, 1), std::sqrt(0.09 / 3.0), 1e-6);
    EXPECT_EQ(r.at(0, 0), 0.0f);
    const ErrorMap rel = errorMap(test, ref, ErrorMetric::RelMse);
    EXPECT_NEAR(rel.at(1, 1), 0.09 / 0.26 / 3.0, 1e-6);
    const ErrorMap s = errorMap(ref, ref, ErrorMetric::Ssim);  // 1 - SSIM
    for (float v : s.values) EXPECT_NEAR(v, 0.0f, 1e-6);
    const ErrorMap f = errorMap(test, ref, ErrorMetric::Flip);
    EXPECT_EQ(f.width, 4);
    EXPECT_EQ(f.height, 2);
    EXPECT_GT(f.at(1, 1), 0.0f);
}

TEST(ErrorMaps, CompareImagesHandsBackTheMapsItComputed) {
    const ImageF ref = structured(24, 20), test = withNoise(ref, 0.1f, 9);
    MetricOptions o;
    o.display.exposureEV = 0.5f;
    ComparisonMaps maps;
    const ImageMetrics m = compareImages(test, ref, o, &maps);
    EXPECT_EQ(maps.flip.values, errorMap(test, ref, ErrorMetric::Flip, o).values);
    EXPECT_EQ(maps.ssimError.values, errorMap(test, ref, ErrorMetric::Ssim, o).values);
    double sum = 0.0;
    for (float v : maps.flip.values) sum += v;
    EXPECT_NEAR(m.flip, sum / double(maps.flip.values.size()), 1e-9);
}

TEST(Heatmap, RampLightnessRisesMonotonically) {
    double lastL = -1.0;
    for (int i = 0; i <= 64; ++i) {
        const glm::vec3 c = heatmapColor(float(i) / 64.0f);
        const glm::dvec3 lab =
            flipdetail::linearRgbToLab({srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)});
        EXPECT_GT(lab.x, lastL) << i;
        lastL = lab.x;
    }
    EXPECT_LT(flipdetail::linearRgbToLab(glm::dvec3(srgbToLinear(heatmapColor(0.0f).x))).x, 6.0);
    EXPECT_GT(lastL, 90.0);
    EXPECT_EQ(heatmapColor(-1.0f), heatmapColor(0.0f));
    EXPECT_EQ(heatmapColor(7.0f), heatmapColor(1.0f));
    EXPECT_EQ(heatmapColor(std::numeric_limits<float>::quiet_NaN()), heatmapColor(0.0f));
}

TEST(Heatmap, ImageLayoutColourBarAndMask) {
    ErrorMap map{32, 16, std::vector<float>(32 * 16, 0.0f)};
    map.values[5] = 2.0f;  // above the maximum: clamps to the top colour
    const ImageU8 plain = heatmapImage(map, 1.0f);
    EXPECT_EQ(plain.width, 32);
    EXPECT_EQ(plain.height, 16);
    const glm::vec3 top = heatmapColor(1.0f);
    EXPECT_EQ(plain.rgba[5 * 4], uint8_t(std::lround(top.x * 255.0f)));
    const ImageU8 withBar = heatmapImage(map, 1.0f, true);
    EXPECT_EQ(withBar.width, 32);
    EXPECT_GT(withBar.height, 16 + 8);
    std::vector<uint8_t> ignore(32 * 16, 0);
    ignore[0] = 1;
    const ImageU8 masked = heatmapImage(map, 1.0f, false, ignore);
    EXPECT_EQ(masked.rgba[0], 128);
    EXPECT_NE(errorOf([&] { heatmapImage(map, 0.0f); }), "(no error)");
    EXPECT_NE(errorOf([&] { heatmapImage(ErrorMap{}, 1.0f); }), "(no error)");
}

// Failures that happen after the temporary file exists, in a directory that does exist (a
// missing directory proves nothing: no file could appear there anyway): the write running into
// the file size limit (as on a full disk), and the rename onto a target that is a directory.
// Either way the error names the reason and the directory holds what it held before.
TEST(Heatmap, FailedWriteLeavesNoFile) {
    namespace fs = std::filesystem;
    const ErrorMap map{64, 64, std::vector<float>(64 * 64, 0.5f)};
    std::string pattern = (fs::temp_directory_path() / "gis_heatmap_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);  // private: a pid-named folder is predictable
    const fs::path dir = pattern;
    const std::string path = (dir / "heat.png").string();

    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const rlimit limit{64, 64};  // bytes: the PNG needs more
        ::setrlimit(RLIMIT_FSIZE, &limit);
        const std::string err = errorOf([&] { writeHeatmap(path, map, 1.0f); });
        ::_exit(err.find("File too large") != std::string::npos ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
    EXPECT_TRUE(fs::is_empty(dir)) << "a partial or temporary file was left in " << dir;

    fs::create_directory(path);  // the target is a directory: refused before anything is written
    EXPECT_NE(errorOf([&] { writeHeatmap(path, map, 1.0f); }).find("is a directory"), std::string::npos);
    EXPECT_TRUE(fs::is_directory(path));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "temporary file left";

    EXPECT_NE(errorOf([&] { writeHeatmap((dir / "no" / "heat.png").string(), map, 1.0f); }).find("does not exist"),
              std::string::npos);
    fs::remove_all(dir);
}

// --- Tone mapping (mirrors shaders/tonemap.frag; the CLI test compares it with the GPU) -------

TEST(Tonemap, TransferFunctionsAndAces) {
    EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);
    EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-6f);
    EXPECT_NEAR(linearToSrgb(2.0f), 1.0f, 1e-6f);
    EXPECT_EQ(linearToSrgb(-1.0f), 0.0f);
    for (int i = 0; i <= 255; ++i) EXPECT_NEAR(linearToSrgb(srgbToLinear(i / 255.0f)), i / 255.0f, 1e-5f);
    EXPECT_EQ(acesFitted(glm::vec3(0.0f)), glm::vec3(0.0f));
    EXPECT_GT(acesFitted(glm::vec3(100.0f)).x, 0.99f);
    const float mid = acesFitted(glm::vec3(0.18f)).y;
    EXPECT_TRUE(mid > 0.1f && mid < 0.3f) << mid;
    DisplaySettings linear{Tonemapper::Linear, 1.0f};
    EXPECT_EQ(toneMap({0.25f, 0.75f, -1.0f}, linear), glm::vec3(0.5f, 1.0f, 0.0f));
    EXPECT_EQ(toneMap({std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f}, linear), glm::vec3(0.0f));
}

}  // namespace
}  // namespace gis
