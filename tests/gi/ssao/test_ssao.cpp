// SSAO and its ground truth, ray-traced AO. Both output the AO term itself (--view ao / the
// ao-reference image): cosine-weighted visibility within a radius, 1 = open. Every SSAO accuracy
// test runs for both kernels (ssao.kernel = hemisphere, gtao).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/method.h"
#include "gi_reference.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr float kRadius = 0.5f;

RenderSettings aoSettings(const std::string& method, int size = 96) {
    RenderSettings r;
    r.width = r.height = size;
    r.gi = method;
    r.view = "ao";
    setParam(r, "--ao-radius", std::to_string(kRadius));
    setParam(r, "--spp", std::to_string(256));
    r.samplesPerFrame = 64;
    return r;
}

// Cosine-weighted visibility at a floor point a distance d from the foot of an infinitely tall
// wall, rays of length r: a direction is blocked when its component towards the wall exceeds
// a = d / r. With Malley's method the directions project uniformly onto the unit disk, and the
// blocked ones onto the segment x > a, whose area is acos(a) - a sqrt(1 - a^2); so
// AO = 1 - (acos(a) - a sqrt(1 - a^2)) / pi. (a = 0: 0.5, the 90-degree wedge.)
double wedgeAo(double a) { return 1.0 - (std::acos(a) - a * std::sqrt(1.0 - a * a)) / 3.14159265358979; }

Scene floorScene(bool withWall) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f), true));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 40.0f, 0);
    if (withWall) addQuad(s, glm::vec3(0, 2.5f, 0), glm::vec3(1, 0, 0), 5.0f, 0);  // x = 0, facing +x
    s.cameras.push_back(lookAtCamera(glm::vec3(2.2f, 1.6f, 0.0f), glm::vec3(0.15f, 0.0f, 0.0f), 50.0f));
    finalizeScene(s);
    return s;
}

// The SSAO settings of `kernel` at its defaults.
RenderSettings ssaoSettings(const std::string& kernel, int size = 96) {
    RenderSettings r = aoSettings("ssao", size);
    setParam(r, "ssao.kernel", kernel);
    return r;
}

double rmse(const ImageF& a, const ImageF& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) sum += double(a.rgba[i] - b.rgba[i]) * (a.rgba[i] - b.rgba[i]);
    return std::sqrt(sum / double(a.rgba.size() / 4));
}

// Ray-traced AO of a scene, `spp` rays per pixel, rendered once per scene, size and spp.
const ImageF& rayTracedAo(const std::string& scene, int size, int spp = 512) {
    static std::map<std::tuple<std::string, int, int>, ImageF> cache;
    auto it = cache.find({scene, size, spp});
    if (it != cache.end()) return it->second;
    RenderSettings ref = aoSettings("ao-reference", size);
    setParam(ref, "--spp", std::to_string(spp));
    ref.samplesPerFrame = 128;
    const Scene s = scene.rfind("builtin:", 0) == 0 ? makeBuiltinScene(scene.substr(8)) : loadGltfFile(scene);
    return cache.emplace(std::make_tuple(scene, size, spp), renderHdr(s, ref)).first->second;
}

// The ssao presets of one kernel, low to high (whichever kernel the plain names belong to).
std::vector<std::string> kernelPresets(const std::string& kernel) {
    std::vector<std::string> names;
    for (const GiPreset& p : giMethod("ssao").presets)
        if (p.values.at("ssao.kernel").text == kernel) names.push_back(p.name);
    return names;
}

class SsaoKernels : public ::testing::TestWithParam<const char*> {};

// A 400 m grey plane at y = 0 seen from `eye`: nothing occludes it anywhere.
Scene openPlane(glm::vec3 eye, glm::vec3 target) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 400.0f, 0);
    s.cameras.push_back(lookAtCamera(eye, target, 60.0f));
    finalizeScene(s);
    return s;
}

TEST_P(SsaoKernels, OpenPlaneIsUnoccludedEverywhereIncludingBorders) {
    const Scene s = openPlane(glm::vec3(0, 2, 3), glm::vec3(0, 0, -1));
    const RenderSettings r = ssaoSettings(GetParam());
    const ImageF img = renderHdr(s, r);
    float lo = 1.0f;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            if (img.at(x, y)[3] > 0.0f && img.at(x, y)[0] > 0.0f) lo = std::min(lo, img.at(x, y)[0]);
    // Every row that sees the floor, border rows and columns included.
    for (int y : {r.height - 1, r.height / 2}) {
        EXPECT_NEAR(img.at(0, y)[0], 1.0f, 0.02f) << "left border, row " << y;
        EXPECT_NEAR(img.at(r.width - 1, y)[0], 1.0f, 0.02f) << "right border, row " << y;
        EXPECT_NEAR(img.at(r.width / 2, y)[0], 1.0f, 0.02f) << "centre, row " << y;
    }
    std::printf("%s, open plane: lowest AO %.4f\n", GetParam(), lo);
    EXPECT_GE(lo, 0.98f);
}

// The same plane seen from 2 cm above it, out to the horizon: depth round-off at grazing angles
// must not shadow the plane, and nothing may turn NaN.
TEST_P(SsaoKernels, PlaneAtGrazingAnglesStaysOpenAndFinite) {
    const Scene s = openPlane(glm::vec3(0, 0.02f, 0), glm::vec3(0, 0.0f, -10.0f));
    const RenderSettings r = ssaoSettings(GetParam());
    const ImageF img = renderHdr(s, r);
    ASSERT_TRUE(allFinite(img));
    const std::vector<PixelHit> hits = castPixels(s, 0, r.width, r.height, nullptr);
    float lo = 1.0f;
    int floorPixels = 0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            if (hits[size_t(y) * r.width + x].region >= 0) {  // the plane, not the sky (AO 0 there)
                lo = std::min(lo, img.at(x, y)[0]);
                ++floorPixels;
            }
    std::printf("%s, plane seen from 2 cm: %d pixels, lowest AO %.4f\n", GetParam(), floorPixels, lo);
    EXPECT_GT(floorPixels, r.width * r.height / 4);
    EXPECT_GE(lo, 0.98f);
}

TEST_P(SsaoKernels, FootOfAWallMatchesTheAnalyticWedge) {
    const std::string kernel = GetParam();
    const double d = 0.25 * kRadius;
    const double expected = wedgeAo(d / kRadius);  // 0.6575
    const Scene s = floorScene(true);
    const RenderSettings r = ssaoSettings(kernel);
    const glm::ivec2 p = projectToPixel(s, r, glm::vec3(float(d), 0.0f, 0.0f));
    const double ao = meanAround(renderHdr(s, r), p.x, p.y, 1);
    std::printf("%s at %.3f m from the wall: AO %.4f, analytic %.4f\n", kernel.c_str(), d, ao, expected);
    // Measured: hemisphere 0.704 (its thickness guess), GTAO 0.723 at 4 slices x 4 steps: its
    // horizon is exact per slice in theory, but 4 steps per side rarely land on the highest wall
    // point within the radius, and the 4x4 blur, centred half a pixel off, averages in pixels
    // farther from the wall (a symmetric 5x5 blur gave 0.697, tried and not kept: it cost 56%
    // more blur taps and moved the Cornell RMSE by 0.0004).
    EXPECT_NEAR(ao, expected, kernel == "gtao" ? 0.07 : 0.05);
    const Scene open = floorScene(false);  // the same point without the wall: open
    EXPECT_NEAR(meanAround(renderHdr(open, r), p.x, p.y, 1), 1.0, 0.02);
}

TEST(AoReference, FootOfAWallMatchesTheAnalyticWedge) {
    const double d = 0.25 * kRadius;
    const double expected = wedgeAo(d / kRadius);
    const RenderSettings r = aoSettings("ao-reference");
    const Scene s = floorScene(true);
    const glm::ivec2 p = projectToPixel(s, r, glm::vec3(float(d), 0.0f, 0.0f));
    const double ao = meanAround(renderHdr(s, r), p.x, p.y, 1);
    std::printf("ray-traced AO at %.3f m from the wall: %.4f, analytic %.4f\n", d, ao, expected);
    EXPECT_NEAR(ao, expected, 0.02);
    EXPECT_NEAR(meanAround(renderHdr(floorScene(false), r), p.x, p.y, 1), 1.0, 0.02);
}

// A plate 1 m above the floor, radius 0.5: nothing within reach of either surface. Its top sees
// the open sky; the floor beside and under its silhouette must not be darkened (no halo).
TEST_P(SsaoKernels, NoHaloAroundAFloatingPlate) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f), true));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 40.0f, 0);
    addQuad(s, glm::vec3(0, 1.0f, 0), glm::vec3(0, 1, 0), 1.0f, 0);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 2.5f, 2.5f), glm::vec3(0, 0.3f, 0), 50.0f));
    finalizeScene(s);
    const RenderSettings r = ssaoSettings(GetParam());
    const ImageF img = renderHdr(s, r);
    const glm::ivec2 top = projectToPixel(s, r, glm::vec3(0, 1.0f, 0));
    EXPECT_NEAR(meanAround(img, top.x, top.y, 2), 1.0, 0.02) << "plate top";
    const std::vector<PixelHit> hits = castPixels(s, 0, r.width, r.height, nullptr);
    const std::vector<bool> interior = interiorPixels(hits, r.width, r.height, 1, 0);
    double worst = 1.0;
    int counted = 0;
    for (int y = 3; y < r.height - 3; ++y)
        for (int x = 3; x < r.width - 3; ++x) {
            const size_t i = size_t(y) * r.width + x;
            if (hits[i].region != 0 || !interior[i]) continue;  // floor pixels, not at an edge
            bool nearPlate = false;  // within 3 px of the plate's silhouette
            for (int j = -3; j <= 3; ++j)
                for (int k = -3; k <= 3; ++k) nearPlate |= hits[size_t(y + j) * r.width + x + k].region == 8;
            if (!nearPlate) continue;
            worst = std::min(worst, double(img.at(x, y)[0]));
            ++counted;
        }
    std::printf("%s, floor next to the plate's silhouette: %d pixels, lowest AO %.4f (analytic 1)\n", GetParam(),
                counted, worst);
    EXPECT_GT(counted, 20);
    EXPECT_GE(worst, 0.95);
}

TEST_P(SsaoKernels, ErrorAgainstRayTracedAoFallsFromLowToHighPreset) {
    const Scene s = makeBuiltinScene("cornell");
    const ImageF& truth = rayTracedAo("builtin:cornell", 64);
    const std::vector<std::string> presets = kernelPresets(GetParam());
    ASSERT_EQ(presets.size(), 3u);
    double previous = 1e9;
    for (const std::string& preset : presets) {
        RenderSettings r = aoSettings("ssao", 64);
        applyPreset(r, "ssao", preset);
        const double e = rmse(renderHdr(s, r), truth);
        std::printf("SSAO %s: RMSE against ray-traced AO %.4f\n", preset.c_str(), e);
        EXPECT_LT(e, previous) << preset;
        previous = e;
    }
}

// The bar GTAO was made to clear: GTAO at each preset is no less accurate against
// ray-traced AO on the Cornell box than the hemisphere kernel's medium preset. At 128x128: the
// low preset works at half resolution, and 32x32 (half of 64) is too coarse to say anything.
TEST(Ssao, GtaoPresetsAreAtLeastAsAccurateAsTheMediumHemisphere) {
    const int size = 128;
    const Scene s = makeBuiltinScene("cornell");
    const ImageF& truth = rayTracedAo("builtin:cornell", size, 256);
    auto error = [&](const std::string& preset) {
        RenderSettings r = aoSettings("ssao", size);
        applyPreset(r, "ssao", preset);
        return rmse(renderHdr(s, r), truth);
    };
    const double medium = error(kernelPresets("hemisphere")[1]);
    for (const std::string& preset : kernelPresets("gtao")) {
        const double e = error(preset);
        std::printf("%s: RMSE %.4f against the hemisphere medium's %.4f\n", preset.c_str(), e, medium);
        EXPECT_LE(e, medium) << preset;
    }
}

// Temporal accumulation removes SSAO's *noise*: with the kernel rotation changing every frame and
// a still camera, 16 accumulated frames of an unblurred SSAO (so the noise shows) come closer to
// the noise-free SSAO (256 directions, 64 slices) than one frame does, and the change from one
// frame to the next (flicker) shrinks. Its *bias* against ray-traced AO (what the screen cannot
// see) is untouched: printed, not asserted.
TEST_P(SsaoKernels, TemporalAccumulationRemovesNoiseAndFlicker) {
    const std::string kernel = GetParam();
    const Scene s = makeBuiltinScene("cornell");
    RenderSettings converged = ssaoSettings(kernel, 64);
    setParam(converged, kernel == "gtao" ? "ssao.slices" : "ssao.samples", kernel == "gtao" ? "64" : "256");
    setParam(converged, "ssao.blur", "false");
    const ImageF noiseFree = renderHdr(s, converged);
    RenderSettings r = ssaoSettings(kernel, 64);
    setParam(r, "ssao.blur", "false");
    const ImageF single = renderHdr(s, r);
    setParam(r, "ssao.temporal", "true");
    r.hdr32 = true;
    Renderer renderer(s, r);
    ImageF previous;
    double firstFlicker = 0.0, lastFlicker = 0.0;
    for (int frame = 0; frame < 17; ++frame) {
        renderer.renderFrame();
        ImageF img = renderer.readHdr();
        if (frame == 1) firstFlicker = rmse(img, previous);
        if (frame == 16) lastFlicker = rmse(img, previous);
        previous = std::move(img);
    }
    const ImageF& truth = rayTracedAo("builtin:cornell", 64);
    const double off = rmse(single, noiseFree), on = rmse(previous, noiseFree);
    std::printf("%s temporal: RMSE vs noise-free SSAO off %.4f, on (16 frames) %.4f; flicker frame 1 %.4f, frame 16 "
                "%.4f; vs ray-traced AO off %.4f, on %.4f\n",
                kernel.c_str(), off, on, firstFlicker, lastFlicker, rmse(single, truth), rmse(previous, truth));
    EXPECT_LT(on, 0.8 * off);  // hemisphere measured 0.71: 16 rotations of 16 directions are not 256 directions
    EXPECT_LT(lastFlicker, 0.5 * firstFlicker);
}

// Extremes: radius 1e-4 and 1e4, 1 and 256 directions or 1 and 64 slices - AO stays finite and in [0, 1].
TEST_P(SsaoKernels, ExtremesStayFiniteAndInRange) {
    const std::string kernel = GetParam();
    const std::string countKey = kernel == "gtao" ? "ssao.slices" : "ssao.samples";
    struct Case { float radius; int count; };
    const int most = kernel == "gtao" ? 64 : 256;
    const Scene s = makeBuiltinScene("cornell");
    for (const Case& c : {Case{1e-4f, 16}, Case{1e4f, 16}, Case{0.5f, 1}, Case{0.5f, most}}) {
        RenderSettings r = ssaoSettings(kernel, 48);
        setParam(r, "--ao-radius", std::to_string(c.radius));
        setParam(r, countKey, std::to_string(c.count));
        const ImageF img = renderHdr(s, r);
        for (size_t i = 0; i < img.rgba.size(); i += 4) {
            ASSERT_TRUE(std::isfinite(img.rgba[i])) << "radius " << c.radius << " count " << c.count;
            ASSERT_GE(img.rgba[i], 0.0f);
            ASSERT_LE(img.rgba[i], 1.0f);
        }
    }
}

// AO does not depend on the unit of length: the Cornell box scaled by 1e-3 and 1e3 (camera, clip
// planes and radius with it) gives the AO of x1, pixel for pixel up to depth round-off.
TEST_P(SsaoKernels, SameAoWhenTheSceneIsScaledBy1e3Or1eMinus3) {
    const Scene base = makeBuiltinScene("cornell");
    RenderSettings r = ssaoSettings(GetParam(), 48);
    const ImageF unit = renderHdr(base, r);
    for (float scale : {1e-3f, 1e3f}) {
        setParam(r, "--ao-radius", std::to_string(kRadius * scale));
        const ImageF img = renderHdr(scaledScene(base, scale), r);
        ASSERT_TRUE(allFinite(img)) << "scale " << scale;
        const double e = rmse(img, unit);
        std::printf("%s, Cornell box x%g: RMSE against x1 %.5f\n", GetParam(), scale, e);
        EXPECT_LT(e, 0.01) << "scale " << scale;
    }
}

INSTANTIATE_TEST_SUITE_P(Kernels, SsaoKernels, ::testing::Values("hemisphere", "gtao"));

// GIS_MEASURE=ssao: the README's SSAO table. For each scene at 256x256, every preset of both
// kernels: RMSE of the AO against ray-traced AO (512 rays per pixel) and milliseconds (the ssao
// pass's GPU time and the frame's wall time with glFinish, medians of 12 frames after 3 of
// warm-up; --gi none's wall time for the added cost). Rounds interleave the variants so load from
// other processes spreads over all of them; the table keeps each variant's fastest round.
TEST(SsaoMeasure, KernelsAndPresetsAt256) {
    if (!measuring("ssao")) GTEST_SKIP() << "set GIS_MEASURE=ssao to measure the kernels";
    const int size = 256, rounds = 3, frames = 12, warmup = 3;
    const std::string pointScene =
        std::string(GIS_SHARED_DIR) + "/assets/reference/scenes/cornell_point/cornell_point.gltf";
    for (const std::string& sceneName : {std::string("builtin:cornell"), pointScene}) {
        const Scene s = sceneName == pointScene ? loadGltfFile(pointScene) : makeBuiltinScene("cornell");
        const ImageF& truth = rayTracedAo(sceneName, size);
        std::vector<std::string> variants{"none"};
        for (const GiPreset& p : giMethod("ssao").presets) variants.push_back(p.name);
        std::map<std::string, std::pair<double, double>> best;  // variant -> (pass ms, wall ms)
        std::map<std::string, double> error;
        for (int round = 0; round < rounds; ++round)
            for (const std::string& v : variants) {
                RenderSettings r = aoSettings("none", size);
                r.view = "final";  // the whole frame, as Godot's figure is
                if (v != "none") applyPreset(r, "ssao", v);
                Renderer renderer(s, r);
                renderer.setSkipSettled(false);  // the cost of frames that run (a static view skips them)
                std::vector<double> wall;
                for (int f = 0; f < frames + warmup; ++f) {
                    const auto t0 = std::chrono::steady_clock::now();
                    renderer.renderFrame();
                    glFinish();
                    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                }
                double passMs = 0.0;
                for (const PassTiming& t : renderer.timings(warmup))
                    if (t.pass == "ssao") passMs = t.medianMs;
                const double wallMs = medianAfter(wall, warmup);
                auto it = best.find(v);
                if (it == best.end() || wallMs < it->second.second) best[v] = {passMs, wallMs};
                if (v != "none" && round == 0) {
                    r.view = "ao";
                    error[v] = rmse(renderHdr(s, r), truth);
                }
            }
        for (const std::string& v : variants)
            std::printf("SSAO-TABLE | %s | %s | %s | %.4f | %.1f | %.1f | +%.1f |\n",
                        sceneName == pointScene ? "cornell_point" : "cornell", v.c_str(),
                        v == "none" ? "" : giMethod("ssao").preset(v).description.c_str(),
                        v == "none" ? 0.0 : error[v], best[v].first, best[v].second,
                        best[v].second - best["none"].second);
    }
}

// The ray-traced AO against Cycles' AO pass (0.5 m, cosine-weighted, background 0).
class AoMatchesCycles : public ::testing::TestWithParam<const char*> {};

TEST_P(AoMatchesCycles, MeanRelativeErrorWithinTwoPercent) {
    const std::string name = GetParam();
    const std::string dir = std::string(GIS_SHARED_DIR) + "/assets/reference";
    const Scene s = loadGltfFile(dir + "/scenes/" + name + "/" + name + ".gltf");
    const int size = 64;
    const ImageF ref = downsample(readExr(dir + "/refs/" + name + "/ao.exr"), 256 / size);
    RenderSettings r = aoSettings("ao-reference", size);
    setParam(r, "--spp", std::to_string(512));
    r.samplesPerFrame = 128;
    const ImageF img = renderHdr(s, r);
    const std::vector<PixelHit> hits = castPixels(s, 0, size, size, nullptr);
    const std::vector<bool> keep = interiorPixels(hits, size, size, 1, 0);
    double ours = 0.0, cycles = 0.0;
    std::map<int, std::pair<double, double>> regions;
    std::map<int, int> counts;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            ours += img.at(x, y)[0];
            cycles += ref.at(x, y)[0];
            const size_t i = size_t(y) * size + x;
            if (!keep[i]) continue;
            regions[hits[i].region].first += img.at(x, y)[0];
            regions[hits[i].region].second += ref.at(x, y)[0];
            ++counts[hits[i].region];
        }
    const double err = std::abs(ours - cycles) / cycles;
    std::printf("%s AO: image mean ours %.4f cycles %.4f error %.2f%%\n", name.c_str(), ours / (size * size),
                cycles / (size * size), 100.0 * err);
    EXPECT_LT(err, 0.02);
    for (const auto& [region, sums] : regions) {
        if (counts[region] < 20) continue;
        const double e = std::abs(sums.first - sums.second) / sums.second;
        std::printf("  region %2d/%d %4d px: ours %.4f cycles %.4f error %.2f%%\n", region / 8, region % 8,
                    counts[region], sums.first / counts[region], sums.second / counts[region], 100.0 * e);
        EXPECT_LT(e, 0.02) << "region " << region;
    }
}

INSTANTIATE_TEST_SUITE_P(CornellBoxes, AoMatchesCycles, ::testing::Values("cornell_box", "cornell_point"));

}  // namespace
}  // namespace gis::test
