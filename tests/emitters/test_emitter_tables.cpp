// The measured tables of renderer/emitters/README.md, on the reference Cornell box lit by its
// emitter (shared/assets/reference/scenes/cornell_box, Cycles' refs/cornell_box, 256x256). Slow on
// llvmpipe, so not in the default run:
//   build/tests/gis_emitter_tests --gtest_also_run_disabled_tests --gtest_filter='*Table*'
// Each prints its rows and one `NAME-TABLE` line per row for the README.
#include <cstdio>
#include <map>

#include "gi/method.h"
#include "metrics.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 256;

std::string sharedPath(const std::string& rel) { return std::string(GIS_SHARED_DIR) + "/assets/reference/" + rel; }

RenderSettings cornellSettings(const std::string& gi, const std::string& mode) {
    RenderSettings r;
    r.width = r.height = kSize;
    r.gi = gi;
    setParam(r, "emitters.mode", mode);
    return r;
}

// --gi none with the emitter as a light: each face's mean direct light against Cycles' direct pass.
TEST(EmitterTables, DISABLED_CornellBoxDirectLightPerFace) {
    const Scene scene = loadScene(sharedPath("scenes/cornell_box/cornell_box.gltf"));
    const ImageF ref = readExr(sharedPath("refs/cornell_box/direct.exr"));
    RenderSettings r = cornellSettings("none", "lights");
    r.ambient = glm::vec3(0.0f);
    const ImageF img = renderHdr(scene, r);
    const std::vector<PixelHit> hits = castPixels(scene, 0, kSize, kSize, nullptr);
    const std::vector<bool> keep = interiorPixels(hits, kSize, kSize, 1, 0);
    std::map<int, int> pixels;
    for (size_t i = 0; i < hits.size(); ++i)
        if (hits[i].region >= 0 && keep[i]) ++pixels[hits[i].region];
    double worst = 0.0;
    int compared = 0;
    for (const auto& [region, n] : pixels) {
        if (n < 30) continue;
        const double ours = regionMean(img, hits, keep, region), cycles = regionMean(ref, hits, keep, region);
        if (cycles < 1e-3) continue;  // unlit
        const double err = (ours - cycles) / cycles;
        worst = std::max(worst, std::abs(err));
        ++compared;
        std::printf("CORNELL-DIRECT-TABLE | %d/%d | %d | %.5f | %.5f | %+.2f%% |\n", region / 8, region % 8, n, ours,
                    cycles, 100.0 * err);
    }
    std::printf("CORNELL-DIRECT-TABLE | worst | | | | %.2f%% |\n", 100.0 * worst);
    EXPECT_GE(compared, 6);
    EXPECT_LT(worst, 0.03);  // the goal
}

// The emitter's outline in Cycles' image: its pixels (radiance above 1; the lit walls stay below
// 0.5) and their 8 neighbours. Cycles averages each pixel over its square, so the pixels the
// 15-radiance emitter's edge crosses hold its share of them; a rasterizer sampling pixel centres
// gave them all or nothing of it (the G-buffer's emission is box-filtered since, so the column now
// measures what is left there). Found from the reference alone: the same pixels for every method.
MetricOptions emitterOutlineLeftOut(const ImageF& ref) {
    MetricOptions o;
    o.ignore.assign(size_t(ref.width) * ref.height, 0);
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            if (ref.at(x, y)[0] + ref.at(x, y)[1] + ref.at(x, y)[2] <= 3.0f) continue;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx >= 0 && ny >= 0 && nx < ref.width && ny < ref.height)
                        o.ignore[size_t(ny) * ref.width + nx] = 1;
                }
        }
    return o;
}

// One method's PSNR (sRGB) against Cycles' full image with the emitters only in the GI and as
// lights, and with them as lights with the emitter's outline left out: "| gi | lights | lights - gi
// | lights, outline out |".
void printPsnrRow(const char* table, const char* gi, const std::string& preset) {
    const Scene scene = loadScene(sharedPath("scenes/cornell_box/cornell_box.gltf"));
    const ImageF ref = readExr(sharedPath("refs/cornell_box/full.exr"));
    double psnr[2] = {}, outlineOut = 0.0;
    for (int m = 0; m < 2; ++m) {
        RenderSettings r = cornellSettings(gi, m == 0 ? "gi" : "lights");
        if (!preset.empty()) applyPreset(r, gi, preset);
        const ImageF img = renderHdr(scene, r);
        psnr[m] = compareImages(img, ref).psnrSrgb;
        if (m == 1) outlineOut = compareImages(img, ref, emitterOutlineLeftOut(ref)).psnrSrgb;
    }
    std::printf("%s | %s | %.2f | %.2f | %+.2f | %.2f |\n", table, gi, psnr[0], psnr[1], psnr[1] - psnr[0], outlineOut);
}

// Every method at its default settings.
TEST(EmitterTables, DISABLED_CornellBoxPsnrLightsVsGi) {
    for (const char* gi : {"none", "ssao", "vct", "sdf", "probes"}) printPsnrRow("CORNELL-PSNR-TABLE", gi, "");
}

// The same at the voxel methods' high presets (the goals: probes >= 30, vct >= 26, sdf >= 24 dB).
TEST(EmitterTables, DISABLED_CornellBoxPsnrHighPresets) {
    for (const char* gi : {"vct", "sdf", "probes"}) printPsnrRow("CORNELL-PSNR-HIGH-TABLE", gi, "high");
}

// The closed room lit by its emissive panel, where bounce light is most of the image: each
// method's mean radiance over the path tracer's (64 bounces, 256 spp), 64x64 (the goal:
// 85-115%).
TEST(EmitterTables, DISABLED_PanelRoomEnergy) {
    const Scene scene = makeBuiltinScene("room?lamp=panel");
    RenderSettings pt = cornellSettings("pathtrace", "lights");
    pt.width = pt.height = 64;
    const std::vector<bool> panel = emitterPixels(scene, pt);  // its own radiance, the same in every method
    auto mean = [&](const ImageF& img) { return meanRgbExcept(img, panel); };
    pt.samplesPerFrame = 16;
    setParam(pt, "pathtrace.spp", "256");
    setParam(pt, "pathtrace.bounces", "64");
    const double truth = mean(renderHdr(scene, pt));
    for (const char* mode : {"lights", "gi"})
        for (const char* gi : {"none", "vct", "sdf", "probes", "hddagi"}) {
            RenderSettings r = cornellSettings(gi, mode);
            r.width = r.height = 64;
            const double m = mean(renderHdr(scene, r));
            std::printf("PANEL-ROOM-TABLE | %s | %s | %.4f | %.4f | %.2f |\n", mode, gi, m, truth, m / truth);
        }
    // vct at its default sums three bounces; its feedback (off by default: the bounces cost) all of them.
    RenderSettings feedback = cornellSettings("vct", "lights");
    feedback.width = feedback.height = 64;
    setParam(feedback, "vct.feedback", "true");
    const double m = mean(renderHdr(scene, feedback));
    std::printf("PANEL-ROOM-TABLE | lights | vct, vct.feedback=true | %.4f | %.4f | %.2f |\n", m, truth, m / truth);
}

// ReSTIR's GPU time per frame at 256x256 (median of 16 frames after 4), biased and unbiased.
TEST(EmitterTables, DISABLED_RestirCostPerFrame) {
    const Scene scene = loadScene(sharedPath("scenes/cornell_box/cornell_box.gltf"));
    context();
    for (const char* unbiased : {"false", "true"}) {
        RenderSettings r = cornellSettings("none", "lights");
        setParam(r, "emitters.unbiased", unbiased);
        setParam(r, "emitters.accumulate", "0");
        Renderer renderer(scene, r);
        for (int i = 0; i < 20; ++i) renderer.renderFrame();
        for (const PassTiming& t : renderer.timings(4))
            if (t.pass.rfind("emitters", 0) == 0)
                std::printf("RESTIR-COST-TABLE | unbiased=%s | %s | %.2f ms |\n", unbiased, t.pass.c_str(), t.medianMs);
    }
}

// A small emitter of the same power lights the room as the default one does: each method's mean
// radiance with builtin:cornell-area?emitter-size=0.04 over its mean with the default 0.5 m quad
// (128x128, default settings, --emitters lights and gi; the goal: within 10%).
TEST(EmitterTables, DISABLED_SmallEmitterOfEqualPower) {
    const Scene big = makeBuiltinScene("cornell-area"), small = makeBuiltinScene("cornell-area?emitter-size=0.04");
    RenderSettings size = cornellSettings("none", "lights");
    size.width = size.height = 128;
    // Both emitters' pixels left out of both images: their visible radiance differs by (0.5/0.04)^2
    // by design, and the same pixels are averaged in both.
    std::vector<bool> emitters = emitterPixels(big, size);
    const std::vector<bool> smallOnes = emitterPixels(small, size);
    for (size_t p = 0; p < emitters.size(); ++p) emitters[p] = emitters[p] || smallOnes[p];
    for (const char* mode : {"lights", "gi"})
        for (const char* gi : {"none", "vct", "sdf", "probes", "hddagi"}) {
            RenderSettings r = cornellSettings(gi, mode);
            r.width = r.height = 128;
            const double a = meanRgbExcept(renderHdr(big, r), emitters), b = meanRgbExcept(renderHdr(small, r), emitters);
            std::printf("EMITTER-SIZE-TABLE | %s | %s | %.4f | %.4f | %.3f |\n", mode, gi, a, b, b / a);
        }
}

}  // namespace
}  // namespace gis::test
