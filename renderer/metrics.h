// Image error metrics on the CPU: a test image against a reference (the path tracer's, Cycles').
// Inputs are gis::ImageF, RGBA float, rows top to bottom; alpha is ignored everywhere.
//
// Conventions (docs/metrics.md says the same):
//  - RMSE      sqrt(mean over pixels and R, G, B of (t - r)^2), on linear radiance.
//  - relMSE    mean over pixels and R, G, B of (t - r)^2 / (r^2 + eps), eps = 1e-2, on linear
//              radiance (per channel, reference in the denominator).
//  - PSNR      10 log10(peak^2 / MSE) dB, MSE over R, G, B. Linear radiance: peak 1.0 (a fixed
//              yardstick, so PSNR is a function of RMSE alone and comparable across methods; the
//              reference's maximum would move with whatever emitter is in view). sRGB: both images
//              go through the same DisplaySettings (exposure, tone mapper, sRGB encode: tonemap.h,
//              mirroring shaders/tonemap.frag), peak 1.0. Identical images give +inf.
//  - SSIM      Wang et al. 2004 on the sRGB-encoded display images, per R, G, B channel and averaged
//              over the channels: Gaussian window 11x11, sigma 1.5, K1 = 0.01, K2 = 0.03, L = 1.
//              Near the borders the window is cut to the image and renormalised, so every pixel
//              has a value (Wang's code keeps only pixels whose whole window fits).
//  - FLIP      LDR-FLIP (Andersson et al. 2020) on the display images (tone mapped, linear [0, 1]),
//              pixels per degree 67 by default. Our own implementation; see metrics.cpp for the
//              pipeline and its (small) deviations. Mean of the per-pixel map, in [0, 1].
// Every mean skips the pixels an `ignore` mask marks (width*height bytes, nonzero = ignore); the
// SSIM and FLIP filters still read those pixels as neighbours.
//
// Bad input (empty images, different sizes, NaN or Inf in R, G or B, a mask of the wrong size or
// one that ignores every pixel) throws gis::Error with a one-line message.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image.h"
#include "tonemap.h"

namespace gis {

struct MetricOptions {
    DisplaySettings display;          // for psnrSrgb, ssim and flip
    double relMseEpsilon = 1e-2;
    double psnrPeak = 1.0;            // peak of linear radiance for psnrLinear
    double pixelsPerDegree = 67.0;    // FLIP viewing condition: 0.7 m from a 0.7 m wide 4K screen
    std::vector<uint8_t> ignore;      // empty, or width*height; nonzero = leave the pixel out
};

struct ImageMetrics {
    double rmse = 0.0;
    double relMse = 0.0;
    double psnrLinear = 0.0;   // dB, +inf when identical
    double psnrSrgb = 0.0;     // dB, +inf when identical after tone mapping
    double ssim = 1.0;
    double flip = 0.0;
    double meanTest = 0.0;       // mean linear radiance (R, G, B) of each image: "the light within N%"
    double meanReference = 0.0;
    int64_t pixels = 0;        // pixels the means cover (not ignored)
};

struct ComparisonMaps;

// Everything at once; `reference` is the ground truth. With `maps`, also hands back the per-pixel
// FLIP and 1 - SSIM maps it computed on the way (for heatmaps, without computing them again).
ImageMetrics compareImages(const ImageF& test, const ImageF& reference, const MetricOptions& options = {},
                           ComparisonMaps* maps = nullptr);

// --- Single metrics, on the values given (no tone mapping). `ignore` as in MetricOptions.
double meanSquaredError(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore = {});
double rmse(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore = {});
double relativeMse(const ImageF& test, const ImageF& reference, double epsilon = 1e-2,
                   const std::vector<uint8_t>& ignore = {});
double psnr(const ImageF& test, const ImageF& reference, double peak = 1.0, const std::vector<uint8_t>& ignore = {});
double psnrFromMse(double mse, double peak);   // +inf for mse == 0
double meanRadiance(const ImageF& image, const std::vector<uint8_t>& ignore = {});  // of R, G, B
// Inputs are display values in [0, 1] (sRGB-encoded for the convention above).
double ssim(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore = {});
// Inputs are display-referred linear RGB in [0, 1] (toneMapImage's output); values outside are clamped.
double flip(const ImageF& test, const ImageF& reference, double pixelsPerDegree = 67.0,
            const std::vector<uint8_t>& ignore = {});

// --- Per-pixel maps (for heatmaps). Every pixel gets a value; `ignore` does not change them.
struct ErrorMap {
    int width = 0, height = 0;
    std::vector<float> values;  // rows top to bottom
    float at(int x, int y) const { return values[size_t(y) * width + x]; }
};

struct ComparisonMaps {
    ErrorMap flip;       // errorMap(..., ErrorMetric::Flip, options)
    ErrorMap ssimError;  // errorMap(..., ErrorMetric::Ssim, options)
};

enum class ErrorMetric {
    Flip,    // LDR-FLIP of the display images, [0, 1]
    Rmse,    // sqrt(mean over R, G, B of (t - r)^2), linear radiance
    RelMse,  // mean over R, G, B of (t - r)^2 / (r^2 + eps), linear radiance
    Ssim,    // 1 - SSIM of the sRGB-encoded display images (mean over R, G, B), 0 = identical
};
ErrorMetric parseErrorMetric(const std::string& name);  // flip, rmse, relmse, ssim
const char* errorMetricName(ErrorMetric m);

ErrorMap errorMap(const ImageF& test, const ImageF& reference, ErrorMetric metric, const MetricOptions& options = {});
ErrorMap ssimMap(const ImageF& test, const ImageF& reference);  // SSIM itself (1 = identical), per pixel
ErrorMap flipMap(const ImageF& test, const ImageF& reference, double pixelsPerDegree = 67.0);

// --- False colour. The ramp runs from near-black through violet, red and orange to pale yellow with
// CIELAB lightness rising linearly (see metrics.cpp); value 0 -> first colour, >= maxValue -> last.
glm::vec3 heatmapColor(float t);  // t in [0, 1] -> sRGB-encoded colour in [0, 1]
// Pixels in `ignore` are drawn mid-grey. With `colorBar`, a strip showing the ramp from 0 (left)
// to maxValue (right) is added below the image. maxValue must be > 0.
ImageU8 heatmapImage(const ErrorMap& map, float maxValue, bool colorBar = false,
                     const std::vector<uint8_t>& ignore = {});
// The same strip over the image's bottom rows (a white line above it), for a view whose size is
// fixed (the viewer's panes).
void overlayColorBar(ImageU8& img);
// Written atomically (writePng); throws gis::Error naming the file.
void writeHeatmap(const std::string& path, const ErrorMap& map, float maxValue, bool colorBar = false,
                  const std::vector<uint8_t>& ignore = {});

// "inf" / "-inf" / "nan" or the number with `digits` significant digits.
std::string formatMetric(double value, int digits = 6);

// The checks every function above runs first; throws gis::Error.
void validateImagePair(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore = {});

namespace flipdetail {
// Linear sRGB (D65) -> CIELAB with the white of linear (1, 1, 1) as reference white.
glm::dvec3 linearRgbToLab(glm::dvec3 rgb);
// Hunt-adjusted HyAB distance between two linear RGB colours, and its mapping to [0, 1].
double huntHyab(glm::dvec3 rgbA, glm::dvec3 rgbB);
double colorErrorFromHyab(double hyab);
}  // namespace flipdetail

}  // namespace gis
