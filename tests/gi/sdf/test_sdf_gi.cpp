// SDF GI (`--gi sdf`) through the renderer: the Cornell box's indirect energy per wall against the
// path tracer, colour bleeding, caching (the field is rebuilt only when geometry changes),
// temporal convergence and reprojection, extremes, debug views, the thin-wall leak and the
// README's measurements ("SDF-TABLE" lines).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/method.h"
#include "gi/sdf/sdf_pass.h"
#include "volume/volume_cascades.h"
#include "gl/gl.h"
#include "metrics.h"
#include "render_test_util.h"
#include "../vct/vct_test_util.h"
#include "gi_reference.h"
#include "march_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 96;
constexpr int kSpp = 64;

constexpr ReferenceSpec kSpec{kSize, kSpp, true};

RenderSettings base(const std::string& gi) { return referenceSettings(gi, kSpec); }

void setSdf(RenderSettings& s, const std::string& key, const std::string& text) { setParam(s, "sdf." + key, text); }

struct SdfImages {
    ImageF frame, diffuse, specular, ao, indirect;  // indirect: diffuse albedo x indirect.diffuse
    int fieldBuilds = 0, radianceBuilds = 0;
    std::map<std::string, double> stepMs;           // median GPU ms per step over the frames after the first
};

ImageF indirectTerm(const Renderer& r, const ImageF& diffuse, int w, int h) {
    const ImageF baseColor = readTextureFloat(r.frameTexture("gbuffer.baseColor"), w, h);
    const ImageF material = readTextureFloat(r.frameTexture("gbuffer.material"), w, h);
    ImageF out = diffuse;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                out.at(x, y)[c] = srgbToLinear(baseColor.at(x, y)[c]) * (1.0f - material.at(x, y)[0]) * diffuse.at(x, y)[c];
    return out;
}

const SdfGiPass& sdfPass(const Renderer& r) {
    for (const auto& p : r.passes())
        if (auto* s = dynamic_cast<const SdfGiPass*>(p.get())) return *s;
    throw Error("internal: no SDF pass");
}

SdfImages read(const Renderer& r) {
    const int w = r.settings().width, h = r.settings().height;
    SdfImages out;
    out.frame = r.readHdr();
    out.diffuse = readTextureFloat(r.frameTexture("indirect.diffuse"), w, h);
    out.specular = readTextureFloat(r.frameTexture("indirect.specular"), w, h);
    out.ao = readTextureFloat(r.frameTexture("ao"), w, h);
    out.indirect = indirectTerm(r, out.diffuse, w, h);
    out.fieldBuilds = sdfPass(r).fieldBuilds();
    out.radianceBuilds = sdfPass(r).radianceBuilds();
    for (const PassTiming& t : r.timings(1))
        if (t.step && t.pass.rfind("sdf/", 0) == 0) out.stepMs[t.pass.substr(4)] = t.medianMs > 0 ? t.medianMs : t.firstMs;
    return out;
}

// Renders `frames` frames of a static view; 0: until converged (SDFGI's probes: until the field
// says so, at most the method's framesToConverge; per-pixel rays: framesToConverge).
void renderFrames(Renderer& r, int frames = 0) {
    const bool untilConverged = frames <= 0;
    if (untilConverged) frames = giMethod("sdf").framesToConverge(r.settings());
    for (int f = 0; f < frames; ++f) {
        r.renderFrame();
        const probes::ProbeField* field = sdfPass(r).probeField();
        if (untilConverged && field && field->converged()) break;
    }
}

SdfImages renderSdf(const Scene& scene, RenderSettings s, int frames = 0) {
    context();
    s.gi = "sdf";
    Renderer r(scene, s);
    renderFrames(r, frames);
    return read(r);
}

// The converged images with each of `values` of a live parameter, from one converged field: the
// parameter set live and one frame rendered for each value after the first (what the panel does).
std::vector<SdfImages> renderSdfLive(const Scene& scene, RenderSettings s, const std::string& key,
                                     const std::vector<std::string>& values) {
    context();
    s.gi = "sdf";
    setSdf(s, key, values.front());
    Renderer r(scene, s);
    renderFrames(r);
    std::vector<SdfImages> out{read(r)};
    for (size_t i = 1; i < values.size(); ++i) {
        setSdf(s, key, values[i]);
        r.setLiveSettings(s);
        r.renderFrame();
        out.push_back(read(r));
    }
    return out;
}

// The Cornell references at this file's size and sample count (tests/gi/gi_reference.h).
const GiReference& reference(const std::string& name) { return giReference(name, kSpec); }

double interiorRmse(const ImageF& a, const ImageF& b, const GiReference& r) { return test::interiorRmse(a, b, r.interior()); }

// The band (80-120% on the walls and floor), with the near-field occlusion on (sdf.ao=1) and off
// (the default; switched live on the converged field: the same bits as a fresh render). With
// probes a quarter of the room apart the default's back wall and floor read just above 120% (the
// occlusion had hidden it by darkening the room's edges); an eighth apart, the default since issue
// #39, they are within it (README, "sdf.ao against the truth").
TEST(SdfGi, CornellIndirectEnergyPerWallAgainstPathTracer) {
    const GiReference& ref = reference("cornell");
    const ImageF pt = subtract(ref.ptFull(), ref.ptDirect());
    const std::vector<SdfImages> byAo = renderSdfLive(makeBuiltinScene("cornell"), base("sdf"), "ao", {"1", "0"});
    for (const char* ao : {"1", "0"}) {
        const SdfImages& v = byAo[ao[0] == '1' ? 0 : 1];
        const ImageF indirect = subtract(v.frame, ref.direct());
        ASSERT_TRUE(allFinite(indirect));
        int inBand = 0;
        for (const auto& [name, region] : kCornellFaces) {
            const double ours = ref.regionMean(indirect, region), theirs = ref.regionMean(pt, region);
            const double ratio = ours / theirs;
            const bool ok = ratio >= 0.8 && ratio <= 1.2;
            std::printf("SDF-TABLE energy cornell ao=%s %-10s sdf %.5f pathtrace (16 bounces) %.5f ratio %.0f%% %s\n",
                        ao, name.c_str(), ours, theirs, 100.0 * ratio, ok ? "(in 80-120%)" : "(OUTSIDE 80-120%)");
            if (name == "ceiling") continue;
            inBand += ok;
            EXPECT_GE(ratio, 0.8) << name << " ao=" << ao;
            EXPECT_LE(ratio, 1.2) << name << " ao=" << ao;
        }
        std::printf("SDF-TABLE energy ao=%s: %d of 4 (walls, floor) within 80-120%%\n", ao, inBand);
        std::printf("SDF-TABLE psnr cornell medium ao=%s: %.2f dB sRGB vs the 16-bounce path tracer\n", ao,
                    compareImages(v.frame, ref.ptFull()).psnrSrgb);
    }
}

// Cascades forced onto the Cornell box (its front half then lies in finer cascades, the rest is
// handed over to the coarsest) keep every wall's indirect energy against the path tracer in the
// same 80-120% band as one volume, and change the image little: the hand-over neither loses nor
// doubles light.
TEST(SdfGi, ForcedCascadesKeepTheCornellEnergy) {
    const GiReference& ref = reference("cornell");
    const ImageF pt = subtract(ref.ptFull(), ref.ptDirect());
    RenderSettings s = base("sdf");
    setSdf(s, "resolution", "32");
    const SdfImages one = renderSdf(makeBuiltinScene("cornell"), s);
    setSdf(s, "cascades", "3");
    const SdfImages three = renderSdf(makeBuiltinScene("cornell"), s);
    const ImageF a = subtract(one.frame, ref.direct()), b = subtract(three.frame, ref.direct());
    ASSERT_TRUE(allFinite(b));
    for (const auto& [name, region] : kCornellFaces) {
        const double mOne = ref.regionMean(a, region), mThree = ref.regionMean(b, region), mPt = ref.regionMean(pt, region);
        std::printf("SDF-TABLE cascades cornell %-10s one volume %.0f%%, three cascades %.0f%% of the path tracer\n",
                    name.c_str(), 100.0 * mOne / mPt, 100.0 * mThree / mPt);
        if (name == "ceiling") continue;
        EXPECT_GE(mThree / mPt, 0.8) << name;
        EXPECT_LE(mThree / mPt, 1.2) << name;
    }
    const double rel = interiorRmse(b, a, ref) / ref.regionMean(a, 0);
    std::printf("SDF-TABLE cascades cornell: indirect RMSE three cascades vs one = %.3f of the floor's mean\n", rel);
    EXPECT_LT(rel, 0.05);  // the comment's "change the image little", asserted
}

TEST(SdfGi, ColourBleedsFromTheWallsOntoTheFloor) {
    const GiReference& ref = reference("cornell");
    const SdfImages v = renderSdf(makeBuiltinScene("cornell"), base("sdf"));
    const GiReference::FloorBleeding b = ref.floorBleeding(v.indirect);
    std::printf("SDF-TABLE bleeding floor red/green: near red wall %.3f, near green wall %.3f\n", b.nearRed, b.nearGreen);
    EXPECT_GT(b.nearRed, b.nearGreen);
}

// The field is view-independent: camera moves and light edits never rebuild it; a light edit
// re-lights the voxels; a geometry change rebuilds both. And --timings lists every step.
TEST(SdfGi, FieldIsRebuiltOnlyWhenGeometryChanges) {
    context();
    RenderSettings s = base("sdf");
    setSdf(s, "resolution", "32");
    const Scene scene = makeBuiltinScene("cornell");  // the renderer keeps a reference to it
    Renderer r(scene, s);
    r.renderFrame();
    CameraMatrices c = r.camera();
    for (int i = 0; i < 3; ++i) {
        c.view = glm::translate(c.view, glm::vec3(0.05f, 0.0f, 0.0f));
        c.viewProj = c.proj * c.view;
        c.invViewProj = glm::inverse(c.viewProj);
        c.position = glm::vec3(glm::inverse(c.view)[3]);
        r.setCamera(c);
        r.renderFrame();
    }
    EXPECT_EQ(sdfPass(r).fieldBuilds(), 1);
    EXPECT_EQ(sdfPass(r).radianceBuilds(), 1);
    r.lightsChanged();
    r.renderFrame();
    EXPECT_EQ(sdfPass(r).fieldBuilds(), 1);
    EXPECT_EQ(sdfPass(r).radianceBuilds(), 2);
    r.invalidate(ChangeGeometry);
    r.renderFrame();
    EXPECT_EQ(sdfPass(r).fieldBuilds(), 2);
    EXPECT_EQ(sdfPass(r).radianceBuilds(), 3);
    std::map<std::string, int> steps;
    for (const PassTiming& t : r.timings(0))
        if (t.step) steps[t.pass] = 1;
    // One cascade (the Cornell box): steps without a cascade prefix, a row per flood pass.
    EXPECT_EQ(sdfPass(r).cascadeCount(), 1);
    std::vector<std::string> expected = {"sdf/voxelize", "sdf/seed", "sdf/resolve", "sdf/inject", "sdf/probe classify",
                                         "sdf/probe trace", "sdf/probe blend irradiance", "sdf/trace", "sdf/filter"};
    const std::vector<int> jumps = jfaSteps(32, JfaVariant::JfaPlusTwo);
    for (size_t k = 0; k < jumps.size(); ++k)
        expected.push_back("sdf/jfa." + std::to_string(k + 1) + "." + std::to_string(jumps[k]));
    for (const std::string& step : expected) EXPECT_TRUE(steps.count(step)) << step;
}

// A camera that stands where `position` is and looks along -z, with `base`'s projection.
CameraMatrices cameraAt(const CameraMatrices& base, const glm::vec3& position) {
    CameraMatrices c = base;
    c.view = glm::lookAt(position, position + glm::vec3(0.0f, -0.2f, -1.0f), glm::vec3(0, 1, 0));
    c.viewProj = c.proj * c.view;
    c.invViewProj = glm::inverse(c.viewProj);
    c.position = position;
    return c;
}

bool statsSay(const SdfGiPass& pass, int cascade, const std::string& what) {
    const std::string head = "cascade " + std::to_string(cascade) + ":";
    for (const std::string& line : pass.stats())
        if (line.rfind(head, 0) == 0) return line.find(what) != std::string::npos;
    return false;
}

// The atrium gets several cascades. A camera move within the snap rebuilds none of them (the stats
// say "cached"); a move of 1.5 snaps of the finest cascade rebuilds exactly the cascades whose
// position changed - the finest, not the coarsest. Every step has its row per cascade, the images
// stay finite.
TEST(SdfGi, CascadesFollowTheCameraAndRebuildOnlyWhatMoved) {
    context();
    const Scene scene = makeBuiltinScene("atrium");
    RenderSettings s = base("sdf");
    s.width = s.height = 48;
    setSdf(s, "resolution", "32");
    setSdf(s, "rays", "1");
    Renderer r(scene, s);
    const SdfGiPass& pass = sdfPass(r);
    const CascadeLayout& layout = pass.layout();
    const int count = pass.cascadeCount();
    ASSERT_GT(count, 1);
    // In the courtyard, a fifth of the way up.
    const glm::vec3 start = scene.bounds.center() + glm::vec3(0.0f, -0.3f * scene.bounds.extent().y, 0.0f);
    const CameraMatrices initial = r.camera();
    r.setCamera(cameraAt(initial, start));
    r.renderFrame();
    for (int i = 0; i < count; ++i) EXPECT_EQ(pass.fieldBuilds(i), 1) << i;
    const float snap0 = float(layout.snapCells()) * layout.cellSize(0);

    // Wall clock of a frame, glFinish included.
    auto timedFrame = [&r] {
        const auto begin = std::chrono::steady_clock::now();
        r.renderFrame();
        glFinish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    };
    r.setCamera(cameraAt(initial, start + glm::vec3(0.6f * snap0, 0.0f, -0.4f * snap0)));
    const double cachedMs = timedFrame();
    for (int i = 0; i < count; ++i) {
        EXPECT_EQ(pass.fieldBuilds(i), 1) << i;
        EXPECT_EQ(pass.radianceBuilds(i), 1) << i;
        EXPECT_TRUE(statsSay(pass, i, "last frame cached")) << i;
    }

    const glm::vec3 far = start + glm::vec3(1.5f * snap0, 0.0f, 0.0f);
    std::vector<bool> moves;
    for (int i = 0; i < count; ++i) moves.push_back(layout.mustMove(pass.cascadeOffset(i), layout.centredOffset(i, far)));
    ASSERT_TRUE(moves.front());
    ASSERT_FALSE(moves.back());
    r.setCamera(cameraAt(initial, far));
    const double movedMs = timedFrame();
    for (int i = 0; i < count; ++i) {
        EXPECT_EQ(pass.fieldBuilds(i), moves[size_t(i)] ? 2 : 1) << i;
        EXPECT_TRUE(statsSay(pass, i, moves[size_t(i)] ? "last frame rebuilt" : "last frame cached")) << i;
    }
    const SdfImages img = read(r);
    EXPECT_TRUE(allFinite(img.frame) && allFinite(img.diffuse) && allFinite(img.specular) && allFinite(img.ao));
    double mean = 0.0;
    for (size_t k = 0; k < img.diffuse.rgba.size(); k += 4) mean += img.diffuse.rgba[k + 1];
    EXPECT_GT(mean, 0.0) << "no indirect light at all";
    std::map<std::string, int> steps;
    for (const PassTiming& t : r.timings(0))
        if (t.step) steps[t.pass] = 1;
    for (int i = 0; i < count; ++i)
        for (const char* step : {"voxelize", "seed", "jfa.1.16", "jfa.7.1", "resolve", "inject"})
            EXPECT_TRUE(steps.count("sdf/c" + std::to_string(i) + "." + step)) << i << " " << step;
    for (const std::string& line : pass.stats()) std::printf("SDF-TABLE atrium stats: %s\n", line.c_str());
    // What the move cost: the frame's wall clock (with the new voxelizer's program link) and the
    // GPU time of each step in it (the README's table).
    std::printf("SDF-TABLE atrium frames: %.1f ms wall within the snap, %.1f ms when cascade 0 moved\n", cachedMs,
                movedMs);
    for (const auto& [step, timer] : pass.steps.steps)
        if (!timer->samples.empty())
            std::printf("SDF-TABLE atrium step %s: %.2f ms in its last run (%zu runs)\n", step.c_str(),
                        timer->samples.back(), timer->samples.size());
}

// SDFGI: a probe grid per cascade. The probes move with their cascade (a cascade that moved has a
// moved grid, the others keep theirs), every frame's probe rays stay within sdf.probe-ray-budget (counted
// on the GPU), and the gathered light is there.
TEST(SdfGi, ProbesFollowTheirCascadesWithinTheRayBudget) {
    context();
    const Scene scene = makeBuiltinScene("atrium");
    RenderSettings s = base("sdf");
    s.width = s.height = 48;
    setSdf(s, "resolution", "32");
    setSdf(s, "probe-rays", "32");
    setSdf(s, "probe-ray-budget", "1024");
    Renderer r(scene, s);
    const SdfGiPass& pass = sdfPass(r);
    ASSERT_NE(pass.probeField(), nullptr);
    const probes::ProbeField& field = *pass.probeField();
    const CascadeLayout& layout = pass.layout();
    const int count = pass.cascadeCount();
    ASSERT_GT(count, 1);
    ASSERT_EQ(int(field.grids().size()), count);
    const glm::vec3 start = scene.bounds.center() + glm::vec3(0.0f, -0.3f * scene.bounds.extent().y, 0.0f);
    const CameraMatrices initial = r.camera();
    r.setCamera(cameraAt(initial, start));
    for (int f = 0; f < 3; ++f) {
        r.renderFrame();
        EXPECT_LE(field.lastBatch(), 1024 / 32);
        if (f > 0) {
            EXPECT_LE(field.lastBatchRays(), 1024u) << f;
        }
    }
    const std::vector<probes::ProbeGrid> before = field.grids();
    const glm::vec3 far = start + glm::vec3(1.5f * float(layout.snapCells()) * layout.cellSize(0), 0.0f, 0.0f);
    std::vector<bool> moves;
    for (int i = 0; i < count; ++i) moves.push_back(layout.mustMove(pass.cascadeOffset(i), layout.centredOffset(i, far)));
    ASSERT_TRUE(moves.front());
    r.setCamera(cameraAt(initial, far));
    r.renderFrame();
    r.renderFrame();
    EXPECT_LE(field.lastBatchRays(), 1024u);
    for (int i = 0; i < count; ++i) {
        const bool moved = field.grids()[size_t(i)].first != before[size_t(i)].first;
        EXPECT_EQ(moved, bool(moves[size_t(i)])) << "cascade " << i;
        EXPECT_EQ(field.grids()[size_t(i)].counts, before[size_t(i)].counts) << "cascade " << i;
    }
    const SdfImages img = read(r);
    ASSERT_TRUE(allFinite(img.diffuse));
    double mean = 0.0;
    for (size_t k = 0; k < img.diffuse.rgba.size(); k += 4) mean += img.diffuse.rgba[k + 1];
    EXPECT_GT(mean, 0.0) << "no gathered light";
}

// A static view settles once the probes have converged (the renderer may then skip the pass); a
// camera move unsettles it. The per-pixel ray variant settles after its frames to converge.
TEST(SdfGi, AStaticViewSettlesOnceConverged) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    for (const char* diffuse : {"probes", "rays"}) {
        RenderSettings s = base("sdf");
        s.width = s.height = 32;
        setSdf(s, "resolution", "32");
        setSdf(s, "diffuse", diffuse);
        Renderer r(scene, s);
        const SdfGiPass& pass = sdfPass(r);
        int frames = 0;
        while (!pass.settled() && frames < 400) {
            r.renderFrame();
            ++frames;
        }
        std::printf("SDF-TABLE settled (%s) after %d frames\n", diffuse, frames);
        EXPECT_TRUE(pass.settled()) << diffuse;
        EXPECT_GT(frames, 1) << diffuse;
        r.setCamera(cameraAt(r.camera(), glm::vec3(0.0f, 1.0f, 3.0f)));
        EXPECT_FALSE(pass.settled()) << diffuse;
    }
}

// The per-pixel rays settle after the frames to converge of the live sdf.temporal, not of the one
// the pass was built with (a live edit restarts the history).
TEST(SdfGi, RaysSettleAfterTheLiveTemporalsFrames) {
    context();
    RenderSettings s = base("sdf");
    s.width = s.height = 32;
    setSdf(s, "resolution", "32");
    setSdf(s, "diffuse", "rays");
    RenderSettings live = s;
    setSdf(live, "temporal", "0.5");
    const int frames = giMethod("sdf").framesToConverge(live);
    ASSERT_LT(frames, giMethod("sdf").framesToConverge(s)) << "the live edit does not change the frames to converge";
    const Scene scene = makeBuiltinScene("cornell");
    Renderer r(scene, s);
    r.renderFrame();
    r.setLiveSettings(live);
    const SdfGiPass& pass = sdfPass(r);
    int n = 0;
    while (!pass.settled() && n <= 2 * frames) {
        r.renderFrame();
        ++n;
    }
    EXPECT_EQ(n, frames);
}

// SDFGI's gather at a reduced trace resolution (sdf.trace-scale 2 and 4, sdf.filter-radius 0: the
// 2x2 joint bilateral upsample) against the per-pixel gather (trace-scale 1), converged probes.
constexpr int kGatherSize = 64;
RenderSettings gatherEvery(int pixels) {
    RenderSettings s = base("sdf");
    s.width = s.height = kGatherSize;
    setSdf(s, "resolution", "32");
    setSdf(s, "probe-rays", "64");
    setSdf(s, "trace-scale", std::to_string(pixels));
    setSdf(s, "filter-radius", "0");
    return s;
}

// Upsampling keeps edges: on the rows through the quad's middle (a quad 1 m in front of a lit
// wall), at every pixel, right up to the depth step, the upsampled gather lies within the range of
// the per-pixel gather over the same side's pixels that its footprint (one traced texel each way)
// covers, to 5% of the step's contrast in indirect light. A blend across the step would bring the
// other side's light there, outside that range: so no light crosses the step at all, let alone
// more than one traced texel. (Not the per-pixel value itself: the gather jumps where a cell of
// probes switches to another set, and interpolation smooths such a jump.)
TEST(SdfGi, UpsampledGatherKeepsDepthEdges) {
    const Scene scene = depthStepScene();
    auto settings = [](int pixels) {  // the wall's light is the emitter's, seen through the GI; a black sky
        RenderSettings s = gatherEvery(pixels);
        setParam(s, "emitters.mode", "gi");
        s.background = glm::vec3(0.0f);
        return s;
    };
    const SdfImages full = renderSdf(scene, settings(1));
    const int n = kGatherSize;
    const std::vector<PixelHit> hits = castPixels(scene, 0, n, n, nullptr);
    auto region = [&](int x, int y) { return hits[size_t(std::clamp(y, 0, n - 1)) * n + size_t(std::clamp(x, 0, n - 1))].region; };
    const int quad = region(n / 2, n / 2);
    auto at = [](const ImageF& img, int x, int y) { return double(img.at(x, y)[0]); };
    double sum[2] = {0.0, 0.0};  // the mean of each side on the middle row: wall, quad
    int count[2] = {0, 0};
    for (int x = 0; x < n; ++x) {
        const int side = region(x, n / 2) == quad ? 1 : 0;
        sum[side] += at(full.diffuse, x, n / 2);
        ++count[side];
    }
    const double wall = sum[0] / std::max(count[0], 1), front = sum[1] / std::max(count[1], 1);
    // Which side is brighter does not matter here: the probes between the quad and the wall see the
    // emitter, and their light reaches the quad's front too (the probe gather's leak, the same at every
    // trace scale).
    const double contrast = std::abs(wall - front);
    ASSERT_GT(std::max(wall, front), 2.0 * std::min(wall, front)) << "the scene gives no contrast across the step to test";
    for (int pixels : {2, 4}) {
        const SdfImages reduced = renderSdf(scene, settings(pixels));
        double worst = 0.0;
        for (int y = n / 2 - 8; y <= n / 2 + 8; ++y)
            for (int x = 0; x < n; ++x) {
                // The per-pixel gather's range on this side within the upsampling's footprint.
                double lo = 1e30, hi = -1e30;
                for (int dy = -pixels; dy <= pixels; ++dy)
                    for (int dx = -pixels; dx <= pixels; ++dx) {
                        const int xs = std::clamp(x + dx, 0, n - 1), ys = std::clamp(y + dy, 0, n - 1);
                        if (region(xs, ys) != region(x, y)) continue;
                        lo = std::min(lo, at(full.diffuse, xs, ys));
                        hi = std::max(hi, at(full.diffuse, xs, ys));
                    }
                const double v = at(reduced.diffuse, x, y);
                worst = std::max(worst, std::max({lo - v, v - hi, 0.0}) / contrast);
            }
        std::printf("SDF-TABLE trace-scale %d: largest excess of the upsampled gather over the per-pixel gather's "
                    "range on its side: %.4f of the contrast (wall %.4f, quad %.4f)\n",
                    pixels, worst, wall, front);
        EXPECT_LT(worst, 0.05) << "trace-scale " << pixels;
    }
}

// Mean over the pixels with light of |a - b| / b, red green blue.
double meanRelativeDifference(const ImageF& a, const ImageF& b) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < b.rgba.size(); i += 4)
        for (size_t c = 0; c < 3; ++c)
            if (b.rgba[i + c] > 1e-3f) {
                sum += std::abs(double(a.rgba[i + c]) - double(b.rgba[i + c])) / double(b.rgba[i + c]);
                ++n;
            }
    return n ? sum / n : 0.0;
}

// The probes' light is smooth, so the upsampled gather is the per-pixel one within 4.5% on average
// over the Cornell box (what it loses: the gather's variation inside a traced block, which grows
// with the probes' density: 2.6% with probes a quarter of the room apart, 4.0% an eighth). The
// near-field occlusion is printed, not held to it: per pixel it carries the 32^3 field's stripes
// along the boxes' faces, which one sample per block does not resolve.
TEST(SdfGi, UpsampledGatherStaysCloseToThePerPixelGather) {
    const Scene scene = makeBuiltinScene("cornell");
    auto settings = [](int pixels) {
        RenderSettings s = gatherEvery(pixels);
        s.width = s.height = kSize;
        return s;
    };
    const SdfImages full = renderSdf(scene, settings(1));
    for (int pixels : {4}) {
        const SdfImages reduced = renderSdf(scene, settings(pixels));
        const double diffuse = meanRelativeDifference(reduced.diffuse, full.diffuse);
        const double ao = meanRelativeDifference(reduced.ao, full.ao);
        std::printf("SDF-TABLE trace-scale %d: mean relative difference from the per-pixel gather: indirect.diffuse "
                    "%.4f, ao %.4f\n", pixels, diffuse, ao);
        EXPECT_LT(diffuse, 0.045) << "trace-scale " << pixels;
    }
}

// A static camera converges: the mean frame-to-frame change of indirect.diffuse falls below 1%
// of its mean within framesToConverge frames.
TEST(SdfGi, TemporalAccumulationConverges) {
    context();
    RenderSettings s = base("sdf");
    s.gi = "sdf";
    setSdf(s, "diffuse", "rays");
    const Scene scene = makeBuiltinScene("cornell");
    Renderer r(scene, s);
    const int frames = giMethod("sdf").framesToConverge(s);
    ImageF previous;
    double change = 1.0;
    for (int f = 0; f < frames; ++f) {
        r.renderFrame();
        const ImageF d = readTextureFloat(r.frameTexture("indirect.diffuse"), kSize, kSize);
        if (f > 0) {
            double diff = 0.0, mean = 0.0;
            for (size_t i = 0; i < d.rgba.size(); ++i) {
                if (i % 4 == 3) continue;
                diff += std::abs(d.rgba[i] - previous.rgba[i]);
                mean += d.rgba[i];
            }
            change = diff / std::max(mean, 1e-30);
            std::printf("SDF-TABLE temporal frame %2d: mean change %.4f of the mean\n", f, change);
        }
        previous = d;
    }
    EXPECT_LT(change, 0.01) << "after " << frames << " frames";
}

// Moving the camera keeps the history where the surface was seen before (no smear): after a
// converged view and a small move, one frame is closer to the converged image at the new camera
// than one frame rendered there from scratch.
TEST(SdfGi, ReprojectionDoesNotSmearOnCameraMoves) {
    context();
    RenderSettings s = base("sdf");
    setSdf(s, "diffuse", "rays");
    const Scene scene = makeBuiltinScene("cornell");
    const int frames = giMethod("sdf").framesToConverge(s);
    Renderer moved(scene, s);
    for (int f = 0; f < frames; ++f) moved.renderFrame();
    CameraMatrices c = moved.camera();
    c.view = glm::rotate(glm::mat4(1.0f), glm::radians(4.0f), glm::vec3(0, 1, 0)) * c.view;
    c.viewProj = c.proj * c.view;
    c.invViewProj = glm::inverse(c.viewProj);
    c.position = glm::vec3(glm::inverse(c.view)[3]);
    moved.setCamera(c);
    moved.renderFrame();
    Renderer fresh(scene, s), converged(scene, s);
    fresh.setCamera(c);
    fresh.renderFrame();
    converged.setCamera(c);
    for (int f = 0; f < frames; ++f) converged.renderFrame();
    const ImageF target = readTextureFloat(converged.frameTexture("indirect.diffuse"), kSize, kSize);
    const ImageF a = readTextureFloat(moved.frameTexture("indirect.diffuse"), kSize, kSize);
    const ImageF b = readTextureFloat(fresh.frameTexture("indirect.diffuse"), kSize, kSize);
    const double errMoved = compareImages(a, target).rmse, errFresh = compareImages(b, target).rmse;
    std::printf("SDF-TABLE reprojection: RMSE to converged after a 4-degree turn %.5f, from scratch %.5f\n", errMoved,
                errFresh);
    EXPECT_LT(errMoved, errFresh);
}

// The leak number against the ray offset on builtin:leak's thinnest wall (0.005 m): dark-room mean
// / lit-room mean of the indirect term (the default's bound is the method contract's,
// tests/gi/test_method_contract.cpp).
TEST(SdfGi, ThinWallLeakIsMeasured) {
    const Scene scene = makeBuiltinScene("leak?thickness=0.005");
    for (float offset : {1.5f, 3.0f}) {
        RenderSettings s = base("sdf");
        setSdf(s, "offset", std::to_string(offset));
        const SdfImages img = renderSdf(scene, s);
        ASSERT_TRUE(allFinite(img.indirect));
        double lit = 0.0;
        const double leak = darkOverLitRoom(img.indirect, &lit);
        std::printf("SDF-TABLE leak 64^3 offset %.1f: dark room / lit room = %.4f\n", offset, leak);
        EXPECT_GT(lit, 0.0);
        EXPECT_LT(leak, 0.5);
    }
}

// Issue #39 at building scale: builtin:building's closed room (camera 2) has no opening, so any light
// there leaked through its 20 cm walls and roof, thinner than a cell of every cascade but the finest.
// The leak number is its mean radiance over the sunlit corridor's (camera 0); the path tracer's is
// 0. Per-pixel rays (sdf.diffuse=rays), this method's own gather: a hit reads the voxel light half a
// cell towards the ray, never the wall's far face, and a slab voxel shows the face the ray meets
// (shaders/gi/sdf/sdf_trace.comp). The probe gather (the default) is the probe field's.
TEST(SdfGi, BuildingClosedRoomLeaksLittle) {
    const Scene scene = makeBuiltinScene("building");
    double mean[2] = {0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        RenderSettings s = base("sdf");
        s.width = s.height = 64;
        s.camera = i == 0 ? 0 : 2;
        setSdf(s, "diffuse", "rays");
        const SdfImages img = renderSdf(scene, s);
        ASSERT_TRUE(allFinite(img.frame));
        mean[i] = meanRadiance(img.frame);
    }
    const double leak = mean[1] / mean[0];
    std::printf("SDF-TABLE building diffuse=rays: closed room / corridor = %.4f (corridor %.4f)\n", leak, mean[0]);
    EXPECT_GT(mean[0], 0.0);
    EXPECT_LT(leak, 0.05);
}

// Rays from anywhere in builtin:building's closed room, in every direction, through the cascades
// the closed-room camera places (the far end of the room lies in the coarsest, whose cells are
// three times the walls' thickness): every one hits, and no hit lies beyond the room's walls by
// more than a cell of the cascade it was found in (the field's level set is within half a cell of
// the surface, and a march stops within the hit threshold, half a cell, on either side of it). A
// hit further out is lit by the room on the other side: a leak. The refinement of a grazing hit on
// the floor stepped through the wall standing on it, into the hall and outside.
TEST(SdfGi, RaysFromTheBuildingsClosedRoomHitItsWalls) {
    context();
    RenderSettings s = base("sdf");
    s.width = s.height = 32;
    s.camera = 2;
    const Scene building = makeBuiltinScene("building");
    Renderer r(building, s);
    r.renderFrame();
    const DistanceField& field = sdfPass(r).field();
    ASSERT_EQ(field.layers(), 4);
    // The room's inside and its walls' outer faces (renderer/scene/builtin_gi_scenes.cpp).
    const glm::vec3 inLo(4.2f, 0.02f, -5.5f), inHi(16.0f, 3.0f, 2.3f), outLo(4.0f, -0.2f, -5.7f), outHi(16.2f, 3.2f, 2.5f);
    std::mt19937 gen(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 o = inLo + 0.05f + (inHi - inLo - 0.1f) * glm::vec3(u(gen), u(gen), u(gen));
        const float cosTheta = 2.0f * u(gen) - 1.0f, phi = 6.2831853f * u(gen), sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
        rays.push_back({glm::vec4(o, 200.0f), glm::vec4(sinTheta * std::cos(phi), cosTheta, sinTheta * std::sin(phi), 0.0f)});
    }
    const std::vector<Hit> hits = march(field, rays);
    int beyond = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
        ASSERT_TRUE(hits[i].hit) << "ray " << i;
        const glm::vec3 past = glm::max(outLo - hits[i].position, hits[i].position - outHi);
        const float tolerance = field.volume(hits[i].cascade).cellSize();
        if (std::max({past.x, past.y, past.z}) > tolerance) {
            if (++beyond <= 5) ADD_FAILURE() << "ray " << i << " hit beyond the walls, cascade " << hits[i].cascade;
        }
    }
    std::printf("SDF-TABLE building closed room: %d of %zu rays hit beyond its walls\n", beyond, rays.size());
    EXPECT_EQ(beyond, 0);
}

// The corridor of builtin:building (64x64, issue #39) with SDFGI's probes a quarter of each cascade
// apart (the default until issue #39; an eighth now, where few pixels lack a probe): the 3 m
// corridor in the finest cascade's 5.4 m holds hardly a probe, and the path test finds none of the
// 8 around most of its pixels in sight (they stand in or behind its 20 cm walls). The gather gave
// those no indirect light at all (a third of the surface pixels, whole blocks of wall and ceiling
// black); they take their own rays instead. Those rays see direct light alone (sdf.bounces = 1):
// a pixel whose rays meet only unlit faces stays dark. Such pixels (the floor by the doorways,
// 39 of 3974) were fewer while a hit on the ceiling mixed in the mean of the roof's sunlit top; 90
// since a hit shows each slab's face towards the ray (shaders/volume/sdf_hit_light.glsl).
TEST(SdfGi, PixelsThatSeeNoProbeTakeTheirOwnRays) {
    constexpr int kSide = 64;
    const Scene building = makeBuiltinScene("building");
    RenderSettings s = base("sdf");
    s.width = s.height = kSide;
    s.camera = 0;
    setSdf(s, "probe-spacing", "0.25");
    const SdfImages img = renderSdf(building, s);
    ASSERT_TRUE(allFinite(img.frame));
    const std::vector<PixelHit> hits = castPixels(building, s.camera, kSide, kSide, nullptr);
    int surface = 0, unlit = 0;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x) {
            if (hits[size_t(y) * kSide + x].region < 0) continue;  // the sky through a window
            const float* d = img.diffuse.at(x, y);
            ++surface;
            unlit += d[0] + d[1] + d[2] <= 0.0f ? 1 : 0;
        }
    std::printf("SDF-TABLE building corridor, probes a quarter of a cascade apart: %d of %d surface pixels without "
                "indirect light\n", unlit, surface);
    EXPECT_GT(surface, kSide * kSide / 2);
    EXPECT_LT(unlit, surface / 25);
}

// The atrium lit by its sky alone (64x64): at the far wing's coarse cascade the arches and the
// opposite roofline grow by up to a cell in the field, and a ray within `sdf.hit-threshold` cells
// of it stops there, so the loggias see the sky through a narrower band (README, "What the hit
// threshold trades at building scale"). The threshold holds for the probes' rays too: with the
// probes gathered (the default) a lower one lets more sky in, already within the first 24 frames.
TEST(SdfGi, TheProbesRaysTakeTheHitThreshold) {
    Scene atrium = makeBuiltinScene("atrium");
    atrium.lights.clear();
    double mean[2] = {0.0, 0.0};
    const char* thresholds[2] = {"1", "0.1"};
    for (int i = 0; i < 2; ++i) {
        RenderSettings s = base("sdf");
        s.width = s.height = 64;
        s.background = glm::vec3(0.35f, 0.45f, 0.6f);
        setParam(s, "emitters.environment", "false");  // the sky's own light through the probes' rays
        setSdf(s, "hit-threshold", thresholds[i]);
        const SdfImages img = renderSdf(atrium, s, 24);
        ASSERT_TRUE(allFinite(img.diffuse));
        mean[i] = meanRadiance(img.indirect);
        std::printf("SDF-TABLE atrium under its sky alone, sdf.hit-threshold=%s: indirect %.4f\n", thresholds[i], mean[i]);
    }
    EXPECT_GT(mean[0], 0.0);
    EXPECT_GT(mean[1], 1.05 * mean[0]);
}

// An open floor under a uniform sky of radiance 1 and no light: every ray misses and reads the
// sky, so indirect.diffuse is 1 over the floor (the furnace idea for the contract's E / pi).
TEST(SdfGi, OpenFloorSeesTheSky) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.5f)));
    addQuad(s, glm::vec3(0.0f), glm::vec3(0, 1, 0), 2.0f, 0);
    s.cameras.push_back(lookAtCamera({0, 1.5f, 1.5f}, {0, 0, 0}));
    finalizeScene(s);
    RenderSettings r = base("sdf");
    r.background = glm::vec3(1.0f);
    setParam(r, "emitters.environment", "false");  // the sky through the method's rays, not the direct pass
    const SdfImages v = renderSdf(s, r);
    const float* centre = v.diffuse.at(kSize / 2, kSize / 2);
    std::printf("SDF-TABLE open floor under a sky of 1: indirect.diffuse %.4f %.4f %.4f, ao %.4f\n", centre[0],
                centre[1], centre[2], v.ao.at(kSize / 2, kSize / 2)[0]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], 1.0f, 0.02f);
    EXPECT_NEAR(v.ao.at(kSize / 2, kSize / 2)[0], 1.0f, 0.02f);
}

TEST(SdfGi, DebugViews) {
    RenderSettings s = base("sdf");
    setSdf(s, "resolution", "32");
    const Scene scene = makeBuiltinScene("cornell");
    s.view = "sdf.slice";
    setSdf(s, "slice-axis", "z");
    const SdfImages slice = renderSdf(scene, s, 1);
    // Inside the room the distance is positive (blue-white), outside the walls negative (red).
    int blue = 0, red = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float* p = slice.frame.at(x, y);
            blue += p[2] > p[0] + 0.05f;
            red += p[0] > p[2] + 0.05f;
        }
    EXPECT_GT(blue, kSize * kSize / 4);
    EXPECT_GT(red, 0);
    // The SDFGI probes, as spheres: lit where probes are.
    s.view = "sdf.probes.spheres";
    const SdfImages spheres = renderSdf(scene, s, 1);
    double lit = 0.0;
    for (size_t i = 0; i < spheres.frame.rgba.size(); i += 4) lit += spheres.frame.rgba[i + 1];
    EXPECT_GT(lit, 0.0);
    // The per-pixel diffuse rays' views (sdf.diffuse=rays).
    setSdf(s, "diffuse", "rays");
    s.view = "sdf.steps";
    const SdfImages steps = renderSdf(scene, s, 1);
    double total = 0.0;
    for (size_t i = 0; i < steps.frame.rgba.size(); i += 4) total += steps.frame.rgba[i] + steps.frame.rgba[i + 2];
    EXPECT_GT(total, 0.0);
    s.view = "sdf.normals";
    const SdfImages normals = renderSdf(scene, s, 1);
    EXPECT_TRUE(allFinite(normals.frame));
}

// Error against the path tracer's one-bounce indirect falls with rays per pixel (sdf.diffuse=rays,
// one frame, no temporal or spatial filtering: the noise) and with the field's resolution
// (converged: the bias).
TEST(SdfGi, ErrorFallsWithRaysAndResolution) {
    const GiReference& ref = reference("cornell");
    const ImageF pt = subtract(ref.ptOneBounce(), ref.ptDirect());
    const Scene scene = makeBuiltinScene("cornell");
    double previous = 1e30;
    for (int rays : {1, 4, 16}) {
        RenderSettings r = base("sdf");
        setSdf(r, "resolution", "32");
        setSdf(r, "diffuse", "rays");
        setSdf(r, "rays", std::to_string(rays));
        setSdf(r, "temporal", "0");
        setSdf(r, "filter-radius", "0");
        const double e = interiorRmse(subtract(renderSdf(scene, r, 1).frame, ref.direct()), pt, ref);
        std::printf("SDF-TABLE error 32^3 %2d rays, one frame unfiltered: indirect RMSE %.5f\n", rays, e);
        EXPECT_LT(e, previous) << rays << " rays";
        previous = e;
    }
    previous = 1e30;
    for (int res : {16, 32, 64}) {
        RenderSettings r = base("sdf");
        setSdf(r, "resolution", std::to_string(res));
        setSdf(r, "diffuse", "rays");
        const double e = interiorRmse(subtract(renderSdf(scene, r).frame, ref.direct()), pt, ref);
        std::printf("SDF-TABLE error %d^3 converged: indirect RMSE %.5f\n", res, e);
        EXPECT_LT(e, previous) << res << "^3";
        previous = e;
    }
}

// The README's table (GIS_MEASURE=sdf: the high preset is 128^3 and slow on llvmpipe): PSNR
// against the path tracer per preset, error against rays and resolution, timings per step.
TEST(SdfGi, MeasurePresets) {
    if (!measuring("sdf")) GTEST_SKIP() << "set GIS_MEASURE=sdf to measure";
    const GiReference& ref = reference("cornell");
    const ImageF pt = subtract(ref.ptOneBounce(), ref.ptDirect());
    for (const char* preset : {"low", "medium", "high"}) {
        RenderSettings r = base("sdf");
        applyPreset(r, "sdf", preset);
        r.width = r.height = kSize;
        r.ambient = glm::vec3(0.0f);
        r.hdr32 = true;
        const SdfImages v = renderSdf(makeBuiltinScene("cornell"), r);
        std::printf("SDF-TABLE preset %-6s psnr %.2f dB sRGB vs 1-bounce, %.2f dB vs 16-bounce;", preset,
                    compareImages(v.frame, ref.ptOneBounce()).psnrSrgb, compareImages(v.frame, ref.ptFull()).psnrSrgb);
        for (const auto& [step, ms] : v.stepMs) std::printf(" %s %.1f ms", step.c_str(), ms);
        std::printf("\n");
    }
    for (int bounces : {1, 2}) {
        RenderSettings r = base("sdf");
        setSdf(r, "bounces", std::to_string(bounces));
        const SdfImages v = renderSdf(makeBuiltinScene("cornell"), r);
        const ImageF ours = subtract(v.frame, ref.direct()), full = subtract(ref.ptFull(), ref.ptDirect());
        std::printf("SDF-TABLE bounces %d: psnr %.2f dB vs 16-bounce;", bounces, compareImages(v.frame, ref.ptFull()).psnrSrgb);
        for (const auto& [name, region] : kCornellFaces)
            std::printf(" %s %.0f%%", name.c_str(), 100.0 * ref.regionMean(ours, region) / ref.regionMean(full, region));
        std::printf(" of the 16-bounce indirect\n");
    }
}

}  // namespace
}  // namespace gis::test
