// SSAO and its ground truth, ray-traced AO. Both output the AO term itself (--view ao / the
// ao-reference image): cosine-weighted visibility within a radius, 1 = open.
#include <cstdio>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/method.h"
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

TEST(Ssao, OpenPlaneIsUnoccludedEverywhereIncludingBorders) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 400.0f, 0);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 2, 3), glm::vec3(0, 0, -1), 60.0f));
    finalizeScene(s);
    const RenderSettings r = aoSettings("ssao");
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
    std::printf("open plane: lowest AO %.4f\n", lo);
    EXPECT_GE(lo, 0.98f);
}

TEST(Ssao, FootOfAWallMatchesTheAnalyticWedge) {
    const double d = 0.25 * kRadius;
    const double expected = wedgeAo(d / kRadius);  // 0.6575
    for (const char* method : {"ssao", "ao-reference"}) {
        const Scene s = floorScene(true);
        const RenderSettings r = aoSettings(method);
        const ImageF img = renderHdr(s, r);
        const glm::ivec2 p = projectToPixel(s, r, glm::vec3(float(d), 0.0f, 0.0f));
        const double ao = meanAround(img, p.x, p.y, 1);
        std::printf("%s at %.3f m from the wall: AO %.4f, analytic %.4f\n", method, d, ao, expected);
        EXPECT_NEAR(ao, expected, std::string(method) == "ssao" ? 0.05 : 0.02) << method;

        const Scene open = floorScene(false);  // the same point without the wall: open
        const ImageF img2 = renderHdr(open, r);
        EXPECT_NEAR(meanAround(img2, p.x, p.y, 1), 1.0, 0.02) << method;
    }
}

// A plate 1 m above the floor, radius 0.5: nothing within reach of either surface. Its top sees
// the open sky; the floor beside and under its silhouette must not be darkened (no halo).
TEST(Ssao, NoHaloAroundAFloatingPlate) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f), true));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 40.0f, 0);
    addQuad(s, glm::vec3(0, 1.0f, 0), glm::vec3(0, 1, 0), 1.0f, 0);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 2.5f, 2.5f), glm::vec3(0, 0.3f, 0), 50.0f));
    finalizeScene(s);
    const RenderSettings r = aoSettings("ssao");
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
    std::printf("floor next to the plate's silhouette: %d pixels, lowest AO %.4f (analytic 1)\n", counted, worst);
    EXPECT_GT(counted, 20);
    EXPECT_GE(worst, 0.95);
}

double rmse(const ImageF& a, const ImageF& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) sum += double(a.rgba[i] - b.rgba[i]) * (a.rgba[i] - b.rgba[i]);
    return std::sqrt(sum / double(a.rgba.size() / 4));
}

TEST(Ssao, ErrorAgainstRayTracedAoFallsFromLowToHighPreset) {
    const Scene s = makeBuiltinScene("cornell");
    RenderSettings ref = aoSettings("ao-reference", 64);
    setParam(ref, "--spp", std::to_string(512));
    ref.samplesPerFrame = 128;
    const ImageF truth = renderHdr(s, ref);
    double previous = 1e9;
    for (const char* preset : {"low", "medium", "high"}) {
        RenderSettings r = aoSettings("ssao", 64);
        applyPreset(r, "ssao", preset);
        const double e = rmse(renderHdr(s, r), truth);
        std::printf("SSAO %s: RMSE against ray-traced AO %.4f\n", preset, e);
        EXPECT_LT(e, previous) << preset;
        previous = e;
    }
}

// Temporal accumulation removes SSAO's *noise*: with the kernel rotation changing every frame and
// a still camera, 16 accumulated frames of a 16-direction SSAO (unblurred, so the noise shows)
// come closer to the noise-free SSAO (256 directions) than one frame does, and the change from one
// frame to the next (flicker) shrinks. Its *bias* against ray-traced AO (what the screen cannot
// see) is untouched: printed, not asserted.
TEST(Ssao, TemporalAccumulationRemovesNoiseAndFlicker) {
    const Scene s = makeBuiltinScene("cornell");
    RenderSettings converged = aoSettings("ssao", 64);
    setParam(converged, "ssao.samples", std::to_string(256));
    setParam(converged, "ssao.blur", (false) ? "true" : "false");
    const ImageF noiseFree = renderHdr(s, converged);
    RenderSettings r = aoSettings("ssao", 64);
    setParam(r, "ssao.blur", (false) ? "true" : "false");
    const ImageF single = renderHdr(s, r);
    setParam(r, "ssao.temporal", (true) ? "true" : "false");
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
    RenderSettings ref = aoSettings("ao-reference", 64);
    setParam(ref, "--spp", std::to_string(512));
    ref.samplesPerFrame = 128;
    const ImageF truth = renderHdr(s, ref);
    const double off = rmse(single, noiseFree), on = rmse(previous, noiseFree);
    std::printf("temporal: RMSE vs noise-free SSAO off %.4f, on (16 frames) %.4f; flicker frame 1 %.4f, frame 16 "
                "%.4f; vs ray-traced AO off %.4f, on %.4f\n",
                off, on, firstFlicker, lastFlicker, rmse(single, truth), rmse(previous, truth));
    EXPECT_LT(on, 0.8 * off);  // measured 0.71: 16 rotations of 16 directions are not the same 256 directions
    EXPECT_LT(lastFlicker, 0.5 * firstFlicker);
}

// Extremes: radius 1e-4 and 1e4, 1 and 256 directions, the scene scaled by 1e-3 and 1e3 - AO stays
// finite and in [0, 1].
TEST(Ssao, ExtremesStayFiniteAndInRange) {
    struct Case { float radius; int samples; float scale; };
    for (const Case& c : {Case{1e-4f, 16, 1.0f}, Case{1e4f, 16, 1.0f}, Case{0.5f, 1, 1.0f}, Case{0.5f, 256, 1.0f},
                          Case{0.5e-3f, 16, 1e-3f}, Case{0.5e3f, 16, 1e3f}}) {
        Scene s = makeBuiltinScene("cornell");
        const glm::mat4 m = glm::scale(glm::mat4(1.0f), glm::vec3(c.scale));
        for (DrawItem& d : s.draws) d.world = m * d.world;
        for (Camera& cam : s.cameras) {
            cam.cameraToWorld[3] = glm::vec4(glm::vec3(cam.cameraToWorld[3]) * c.scale, 1.0f);
            cam.znear *= c.scale;
            cam.zfar *= c.scale;
        }
        finalizeScene(s);
        RenderSettings r = aoSettings("ssao", 48);
        setParam(r, "--ao-radius", std::to_string(c.radius));
        setParam(r, "ssao.samples", std::to_string(c.samples));
        const ImageF img = renderHdr(s, r);
        for (size_t i = 0; i < img.rgba.size(); i += 4) {
            ASSERT_TRUE(std::isfinite(img.rgba[i])) << "radius " << c.radius << " samples " << c.samples;
            ASSERT_GE(img.rgba[i], 0.0f);
            ASSERT_LE(img.rgba[i], 1.0f);
        }
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
