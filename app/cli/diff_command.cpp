// gisandbox diff TEST REFERENCE: error metrics of an image against a reference, and a heatmap.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "image.h"
#include "metrics.h"
#include "scene/atomic_file.h"
#include "tonemap.h"

namespace gis {

namespace {

bool hasExtension(const std::string& path, const std::string& ext) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e == ext;
}

void checkReadable(const std::string& path, const char* what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(std::string(what) + " '" + path + "' does not exist");
    if (!fs::is_regular_file(path, ec)) throw Error(std::string(what) + " '" + path + "' is not a file");
    if (!hasExtension(path, ".exr") && !hasExtension(path, ".png"))
        throw Error(std::string(what) + " '" + path + "' must end in .exr (linear) or .png (sRGB)");
}

// .exr: linear radiance as stored. .png: sRGB-encoded 8-bit, decoded to linear.
ImageF loadLinear(const std::string& path) {
    if (hasExtension(path, ".exr")) return readExr(path);
    return decodeSrgbImage(readPng(path));
}

}  // namespace

void addDiffOptions(CLI::App& cmd, DiffOptions& o) {
    cmd.add_option("test", o.test, "Image to judge: .exr (linear radiance) or .png (sRGB, decoded to linear)")
        ->required();
    cmd.add_option("reference", o.reference, "Reference image (ground truth), same size")->required();
    cmd.add_option("--heatmap", o.heatmap, "Write a false-colour PNG of the per-pixel error of --metric");
    cmd.add_option("--metric", o.metric, "Per-pixel error drawn by --heatmap: flip, rmse, relmse, ssim (1 - SSIM)")
        ->capture_default_str();
    cmd.add_option("--tonemap", o.tonemap,
                   "Display transform for PSNR sRGB, SSIM and FLIP: aces, linear (clamp), auto (linear if an "
                   "input is a PNG, else aces)")
        ->capture_default_str();
    cmd.add_option("--exposure", o.exposure, "Exposure in EV (scale 2^EV) before tone mapping")->capture_default_str();
    cmd.add_option("--ppd", o.ppd, "FLIP viewing condition in pixels per degree of visual angle")
        ->capture_default_str();
    cmd.add_option("--heatmap-max", o.heatmapMax,
                   "Error at the top of the heatmap's colour ramp (0: 1 for flip and ssim, the largest error for "
                   "rmse and relmse)")
        ->capture_default_str();
    cmd.add_option("--mask", o.mask, "PNG of the same size; pixels whose red channel is >= 128 are left out");
    cmd.add_flag("--colorbar", o.colorBar, "Add the colour ramp (0 at the left to --heatmap-max) below the heatmap");
    cmd.add_flag("--json", o.json, "Print JSON instead of a table");
}

namespace {

// Everything that can be checked before reading pixels is checked first, so a bad flag never
// costs a comparison and a failure never leaves a heatmap behind (writePng is atomic too).
void checkDiffOptions(const DiffOptions& o) {
    parseErrorMetric(o.metric);
    if (o.tonemap != "auto" && o.tonemap != "aces" && o.tonemap != "linear")
        throw Error("--tonemap '" + o.tonemap + "' must be aces, linear or auto");
    if (!std::isfinite(o.exposure) || std::abs(o.exposure) > 64.0f) throw Error("--exposure must be in [-64, 64] EV");
    if (!(o.ppd > 0.0) || !std::isfinite(o.ppd) || o.ppd > 10000.0) throw Error("--ppd must be in (0, 10000]");
    if (!(o.heatmapMax >= 0.0) || !std::isfinite(o.heatmapMax)) throw Error("--heatmap-max must be >= 0");
    if (!o.heatmap.empty()) {
        if (!hasExtension(o.heatmap, ".png")) throw Error("--heatmap '" + o.heatmap + "' must end in .png");
        const std::filesystem::path dir = std::filesystem::path(o.heatmap).parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir))
            throw Error("--heatmap: directory '" + dir.string() + "' does not exist");
    }
    checkReadable(o.test, "test image");
    checkReadable(o.reference, "reference image");
    if (!o.mask.empty()) {
        checkReadable(o.mask, "mask");
        if (!hasExtension(o.mask, ".png")) throw Error("--mask '" + o.mask + "' must be a .png");
    }
    // By device and inode, not by name: ./t.png, a symlink or a hard link to the input is the same
    // file, and the heatmap's rename would replace it.
    for (const auto& [input, what] : {std::pair<const std::string&, const char*>{o.test, "test image"},
                                      {o.reference, "reference image"},
                                      {o.mask, "mask"}})
        if (!o.heatmap.empty() && !input.empty() && sameFile(o.heatmap, input))
            throw Error("--heatmap '" + o.heatmap + "' is the " + what + " '" + input +
                        "': it would be overwritten; choose another path");
}

// The display transform the metrics compare under. A tone-mapped PNG against linear radiance:
// the errors would measure the tone curve, not the render (FLIP 0.49 where the two EXRs give
// 0.24). The EXR takes the display transform a PNG of it gets from `render` (aces unless
// --tonemap says otherwise), 8-bit, and the pair is compared as two PNGs.
struct DiffDisplay {
    std::string tonemap;   // its name
    float exposureEV = 0.0f;
};

DiffDisplay diffDisplay(const DiffOptions& o, ImageF& test, ImageF& reference) {
    const bool testPng = hasExtension(o.test, ".png"), referencePng = hasExtension(o.reference, ".png");
    if (testPng && referencePng)
        // Two PNGs are compared as they are: ours are ACES tone-mapped, a Cycles reference's PNG is
        // clipped linear ("Standard"), so their tone curves differ before any light does.
        std::fprintf(stderr,
                     "gisandbox: warning: comparing two PNGs as displayed: each is compared with the tone curve it "
                     "was written with (gisandbox's PNGs: ACES; the Cycles references': clipped linear); compare the "
                     "EXRs for radiance errors\n");
    if (testPng == referencePng) return {o.tonemap == "auto" ? (testPng ? "linear" : "aces") : o.tonemap, o.exposure};
    DisplaySettings toPng;
    const std::string curve = o.tonemap == "auto" ? "aces" : o.tonemap;
    toPng.tonemap = parseTonemapper(curve);
    toPng.exposureEV = o.exposure;
    ImageF& linear = testPng ? reference : test;
    linear = decodeSrgbImage(toLdrImage(linear, toPng));
    std::fprintf(stderr,
                 "gisandbox: warning: %s is a tone-mapped PNG and %s a linear EXR: the EXR is tone-mapped "
                 "(%s, %s EV) and quantized as a PNG before comparing; compare two EXRs for radiance errors\n",
                 (testPng ? o.test : o.reference).c_str(), (testPng ? o.reference : o.test).c_str(),
                 curve.c_str(), formatMetric(o.exposure, 4).c_str());
    return {"linear", 0.0f};
}

// --mask's pixels to leave out (red >= 128), one flag per pixel of the reference.
std::vector<uint8_t> readMask(const std::string& path, const ImageF& reference) {
    const ImageU8 mask = readPng(path);
    if (mask.width != reference.width || mask.height != reference.height)
        throw Error("mask '" + path + "' is " + std::to_string(mask.width) + "x" + std::to_string(mask.height) +
                    " but the reference is " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height));
    std::vector<uint8_t> ignore(size_t(mask.width) * mask.height);
    for (size_t p = 0; p < ignore.size(); ++p) ignore[p] = mask.rgba[p * 4] >= 128 ? 1 : 0;
    return ignore;
}

// Writes --heatmap; returns the error at the top of its colour ramp.
double writeDiffHeatmap(const DiffOptions& o, ErrorMetric metric, ComparisonMaps& maps, const ImageF& test,
                        const ImageF& reference, const MetricOptions& options) {
    const ErrorMap map = metric == ErrorMetric::Flip   ? std::move(maps.flip)
                         : metric == ErrorMetric::Ssim ? std::move(maps.ssimError)
                                                       : errorMap(test, reference, metric, options);
    double heatmapMax = o.heatmapMax;
    if (heatmapMax == 0.0) {
        if (metric == ErrorMetric::Flip || metric == ErrorMetric::Ssim) {
            heatmapMax = 1.0;
        } else {
            for (size_t p = 0; p < map.values.size(); ++p)
                if (options.ignore.empty() || !options.ignore[p]) heatmapMax = std::max(heatmapMax, double(map.values[p]));
            if (!(heatmapMax > 0.0)) heatmapMax = 1.0;  // no error at all: any scale draws it black
        }
    }
    writeHeatmap(o.heatmap, map, float(heatmapMax), o.colorBar, options.ignore);
    return heatmapMax;
}

// What a comparison found, as the table and the JSON report it.
struct DiffResult {
    const ImageF& test;
    const ImageF& reference;
    const MetricOptions& options;
    const DiffDisplay& display;
    ImageMetrics m;
    ErrorMetric metric;
    double heatmapMax;
};

void printDiffJson(const DiffOptions& o, const DiffResult& r) {
    const ImageMetrics& m = r.m;
    // Infinite PSNR (identical images) is written as null: JSON has no infinity.
    nlohmann::ordered_json j;
    j["test"] = o.test;
    j["reference"] = o.reference;
    j["width"] = r.reference.width;
    j["height"] = r.reference.height;
    j["pixels"] = m.pixels;
    j["tonemap"] = r.display.tonemap;
    j["exposure_ev"] = r.display.exposureEV;
    j["rmse"] = m.rmse;
    j["relmse"] = m.relMse;
    j["relmse_epsilon"] = r.options.relMseEpsilon;
    j["psnr_linear_db"] = std::isfinite(m.psnrLinear) ? nlohmann::ordered_json(m.psnrLinear) : nullptr;
    j["psnr_linear_peak"] = r.options.psnrPeak;
    j["psnr_srgb_db"] = std::isfinite(m.psnrSrgb) ? nlohmann::ordered_json(m.psnrSrgb) : nullptr;
    j["ssim"] = m.ssim;
    j["flip"] = m.flip;
    j["pixels_per_degree"] = o.ppd;
    j["mean_test"] = m.meanTest;
    j["mean_reference"] = m.meanReference;
    if (!o.heatmap.empty())
        j["heatmap"] = {{"path", o.heatmap}, {"metric", errorMetricName(r.metric)}, {"max", r.heatmapMax}};
    std::printf("%s\n", j.dump(2).c_str());
}

void printDiffTable(const DiffOptions& o, const DiffResult& r) {
    const ImageMetrics& m = r.m;
    const MetricOptions& options = r.options;
    std::printf("test        %s (%dx%d)\n", o.test.c_str(), r.test.width, r.test.height);
    std::printf("reference   %s (%dx%d)\n", o.reference.c_str(), r.reference.width, r.reference.height);
    std::printf("pixels      %lld compared", static_cast<long long>(m.pixels));
    if (!options.ignore.empty())
        std::printf(" (%lld masked)", static_cast<long long>(int64_t(options.ignore.size()) - m.pixels));
    std::printf("\ndisplay     %s, exposure %s EV (PSNR sRGB, SSIM, FLIP)\n\n", r.display.tonemap.c_str(),
                formatMetric(r.display.exposureEV, 4).c_str());
    std::printf("%-12s %12s\n", "metric", "value");
    std::printf("%-12s %12s\n", "RMSE", formatMetric(m.rmse).c_str());
    std::printf("%-12s %12s   eps %s\n", "relMSE", formatMetric(m.relMse).c_str(),
                formatMetric(options.relMseEpsilon).c_str());
    std::printf("%-12s %12s   dB, peak %s\n", "PSNR linear", formatMetric(m.psnrLinear, 5).c_str(),
                formatMetric(options.psnrPeak).c_str());
    std::printf("%-12s %12s   dB\n", "PSNR sRGB", formatMetric(m.psnrSrgb, 5).c_str());
    std::printf("%-12s %12s\n", "SSIM", formatMetric(m.ssim).c_str());
    std::printf("%-12s %12s   %s pixels/degree\n", "FLIP", formatMetric(m.flip).c_str(), formatMetric(o.ppd).c_str());
    std::printf("%-12s %12s   test %s, reference %s (linear radiance)\n", "mean ratio",
                m.meanReference > 0.0 ? formatMetric(m.meanTest / m.meanReference, 4).c_str() : "-",
                formatMetric(m.meanTest, 4).c_str(), formatMetric(m.meanReference, 4).c_str());
    if (!o.heatmap.empty())
        std::printf("\nwrote %s (%s, 0 .. %s)\n", o.heatmap.c_str(), errorMetricName(r.metric),
                    formatMetric(r.heatmapMax, 4).c_str());
}

}  // namespace

int runDiff(const DiffOptions& o) {
    checkDiffOptions(o);
    const ErrorMetric metric = parseErrorMetric(o.metric);
    ImageF test = loadLinear(o.test);
    ImageF reference = loadLinear(o.reference);
    const DiffDisplay display = diffDisplay(o, test, reference);
    MetricOptions options;
    options.display.tonemap = parseTonemapper(display.tonemap);
    options.display.exposureEV = display.exposureEV;
    options.pixelsPerDegree = o.ppd;
    if (!o.mask.empty()) options.ignore = readMask(o.mask, reference);
    try {
        validateImagePair(test, reference, options.ignore);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (test '" + o.test + "', reference '" + o.reference + "')");
    }
    ComparisonMaps maps;
    const ImageMetrics m = compareImages(test, reference, options, &maps);
    const double heatmapMax =
        o.heatmap.empty() ? o.heatmapMax : writeDiffHeatmap(o, metric, maps, test, reference, options);
    const DiffResult result{test, reference, options, display, m, metric, heatmapMax};
    if (o.json) printDiffJson(o, result);
    else printDiffTable(o, result);
    return 0;
}

}  // namespace gis
