// Probe GI (`--gi probes`): SH and octahedral math against closed forms, the probe grid, the
// furnace for every storage kind, convergence (updates stop, and restart after a light edit),
// extremes, and the README's measurements (GIS_PROBES_MEASURE=1 prints "PROBES-TABLE" lines).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "gi/method.h"
#include "gi/probes/probe_math.h"
#include "gi/probes/probes_pass.h"
#include "metrics.h"
#include "render_test_util.h"
#include "../vct/vct_test_util.h"

namespace gis::test {
namespace {

using namespace probes;

std::vector<glm::vec3> fibonacciSet(int n) {
    std::vector<glm::vec3> d;
    for (int k = 0; k < n; ++k) d.push_back(fibonacciDirection(k, n));
    return d;
}

TEST(ProbeMath, ShProjectionOfConstantAndClampedCosineMatchesClosedForms) {
    const auto dirs = fibonacciSet(8192);
    std::vector<glm::vec3> one(dirs.size(), glm::vec3(1.0f)), cosine;
    for (const auto& d : dirs) cosine.emplace_back(std::max(0.0f, d.z));
    // Constant 1: L00 = sqrt(4 pi), nothing else.
    const auto c = projectSh(dirs, one, 9);
    EXPECT_NEAR(c[0].x, 3.5449077, 1e-3);
    for (int k = 1; k < 9; ++k) EXPECT_NEAR(c[size_t(k)].x, 0.0, 1e-3) << k;
    // max(0, z): L00 = sqrt(pi)/2, L10 = sqrt(pi/3), L20 = sqrt(5 pi)/8, the rest 0.
    const auto z = projectSh(dirs, cosine, 9);
    const double expected[9] = {0.8862269, 0, 1.0233267, 0, 0, 0, 0.4954159, 0, 0};
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(z[size_t(k)].x, expected[k], 2e-3) << k;
    // Reconstruction: a constant sky L gives E / pi = L in every direction (L1 and L2).
    for (int coefficients : {4, 9}) {
        const auto s = projectSh(dirs, one, coefficients);
        for (const auto& n : fibonacciSet(64)) EXPECT_NEAR(shIrradianceOverPi(s, n).x, 1.0, 1e-3);
    }
    // The cosine-convolved L2 reconstruction of a clamped cosine, at the pole: pi (A0 L00 Y00 +
    // A1 L10 Y10 + A2 L20 Y20) / pi, the known 2/3 + ... value 0.8 (R&H's kernel, clamped-cosine light).
    const glm::vec3 e = shIrradianceOverPi(z, {0, 0, 1});
    const double analytic = (3.14159265 * 0.8862269 * 0.282095 + 2.0943951 * 1.0233267 * 0.488603 +
                             0.78539816 * 0.4954159 * 0.315392 * 2.0) / 3.14159265;
    EXPECT_NEAR(e.x, analytic, 2e-3);
}

TEST(ProbeMath, OctahedralMapRoundTripsAndReconstructsAConstantSky) {
    for (const auto& d : fibonacciSet(500)) {
        const glm::vec3 back = octDecode(octEncode(d));
        EXPECT_NEAR(glm::dot(back, d), 1.0, 1e-5);
    }
    const auto dirs = fibonacciSet(1024);
    const auto map = projectOctahedral(dirs, std::vector<glm::vec3>(dirs.size(), glm::vec3(0.5f)), kOctIrradianceSize);
    for (const auto& n : fibonacciSet(200)) EXPECT_NEAR(octSample(map, kOctIrradianceSize, n).x, 0.5, 1e-5);
}

TEST(ProbeMath, GridIsFittedToTheBoundsAndDegenerateGridsSaySo) {
    Aabb box;
    box.extend({0, 0, 0});
    box.extend({2, 1, 2});
    const ProbeGrid g = fitProbeGrid(box, 0.25f);  // cells of 0.5
    EXPECT_EQ(g.counts, glm::ivec3(4, 2, 4));
    EXPECT_NEAR(g.position(0).x, 0.25f, 1e-6);
    EXPECT_EQ(fitProbeGrid(box, 1.5f).count(), 1);   // spacing larger than the scene: one probe
    EXPECT_NEAR(fitProbeGrid(box, 1.5f).position(0).y, 0.5f, 1e-6);
    Aabb flat;
    flat.extend({0, 0, 0});
    flat.extend({1, 0, 1});
    EXPECT_EQ(fitProbeGrid(flat, 0.5f).counts, glm::ivec3(2, 1, 2));
    EXPECT_EQ(fitProbeGrid(Aabb{}, 0.1f).count(), 1);  // empty scene
    try {
        fitProbeGrid(box, 0.001f);
        FAIL() << "a grid of 8e9 probes was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("probes.spacing"), std::string::npos) << e.what();
    }
    EXPECT_THROW(fitProbeGrid(box, 0.0f), Error);
    EXPECT_THROW(fitProbeGrid(box, std::nanf("")), Error);
    // Bytes per probe, as the README states them.
    EXPECT_EQ(bytesPerProbe(Storage::Sh1), 64 + 1568 + 32);
    EXPECT_EQ(bytesPerProbe(Storage::Sh2), 144 + 1568 + 32);
    EXPECT_EQ(bytesPerProbe(Storage::Octahedral), 576 + 1568 + 32);
}

// A renderer on --gi probes and its pass.
struct ProbeRun {
    std::unique_ptr<Renderer> renderer;
    ProbesPass* pass = nullptr;
    ProbeRun(const Scene& scene, RenderSettings s) {
        context();
        s.gi = "probes";
        s.hdr32 = true;
        renderer = std::make_unique<Renderer>(scene, s);
        for (const auto& p : renderer->passes())
            if (auto* q = dynamic_cast<ProbesPass*>(p.get())) pass = q;
        if (!pass) throw Error("internal: no probes pass");
    }
    ImageF diffuse() const {
        const auto& s = renderer->settings();
        return readTextureFloat(renderer->frameTexture("indirect.diffuse"), s.width, s.height);
    }
    int renderUntilConverged(int cap) {
        int frames = 0;
        while (!pass->converged() && frames < cap) {
            renderer->renderFrame();
            ++frames;
        }
        return frames;
    }
};

RenderSettings small(int size = 32) {
    RenderSettings r;
    r.width = r.height = size;
    r.ambient = glm::vec3(0.0f);
    return r;
}

bool allFinite(const ImageF& img) {
    for (float v : img.rgba)
        if (!std::isfinite(v)) return false;
    return true;
}

double meanRgb(const ImageF& img) {
    double s = 0.0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) s += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
    return s / std::max<size_t>(1, img.rgba.size() / 4 * 3);
}

// Furnace: no geometry, a uniform sky L: the one probe must reconstruct E = pi L, i.e. E / pi = L,
// in every direction, for every storage kind (read back and evaluated as the shader does).
TEST(Probe, FurnaceEveryStorageReconstructsPiL) {
    Scene empty;
    finalizeScene(empty);
    const glm::vec3 sky(0.5f, 1.0f, 2.0f);
    for (const char* storage : {"sh1", "sh2", "octahedral"}) {
        RenderSettings s = small(16);
        s.background = sky;
        setParam(s, "probes.storage", storage);
        setParam(s, "probes.rays", "256");
        ProbeRun run(empty, s);
        run.renderer->renderFrame();
        ASSERT_EQ(run.pass->grid().count(), 1);
        const auto payload = run.pass->readIrradiance(0);
        double worst = 0.0;
        for (const auto& n : fibonacciSet(300)) {
            const glm::vec3 e = probeIrradianceOverPi(run.pass->rebuildSettings().storageKind(), payload, n);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(e[c] / sky[c] - 1.0));
        }
        std::printf("PROBES-TABLE furnace %s: worst relative error of E/(pi L) over 300 directions %.5f\n", storage, worst);
        EXPECT_LT(worst, 0.02) << storage;
    }
}

// A static Cornell box converges (the largest relative change of an update falls below the
// threshold), then stops updating; a light edit restarts the updates and it converges again.
TEST(Probe, ConvergesStopsAndRestartsAfterALightEdit) {
    Scene scene = makeBuiltinScene("cornell");
    RenderSettings s = small(32);
    applyPreset(s, "probes", "low");
    s.ambient = glm::vec3(0.0f);
    ProbeRun run(scene, s);
    const int cap = 100;
    const int frames = run.renderUntilConverged(cap);
    std::printf("PROBES-TABLE convergence cornell low: %d updates to a change below %.4f (last %.5f)\n", frames,
                run.pass->rebuildSettings().threshold, run.pass->lastChange());
    ASSERT_TRUE(run.pass->converged()) << "still changing by " << run.pass->lastChange() << " after " << cap;
    run.renderer->renderFrame();
    EXPECT_FALSE(run.pass->updatedLastFrame());
    const double before = meanRgb(run.diffuse());
    // Halve the lamp: the indirect light must follow to half.
    scene.lights[0].intensity *= 0.5f;
    run.renderer->lightsChanged();
    int follow = -1;
    std::vector<double> means;
    for (int f = 0; f < cap && !run.pass->converged(); ++f) {
        run.renderer->renderFrame();
        means.push_back(meanRgb(run.diffuse()));
    }
    ASSERT_TRUE(run.pass->converged());
    const double after = means.back();
    for (size_t f = 0; f < means.size(); ++f)
        if (std::abs(means[f] / after - 1.0) <= 0.05) {
            follow = int(f) + 1;
            break;
        }
    std::printf("PROBES-TABLE light edit (lamp x0.5): mean indirect %.5f -> %.5f (ratio %.3f), within 5%% after %d "
                "frame(s), converged after %zu\n",
                before, after, after / before, follow, means.size());
    EXPECT_NEAR(after / before, 0.5, 0.05);
    EXPECT_GE(follow, 1);
    EXPECT_LE(follow, 20);
}

TEST(Probe, ExtremesStayFinite) {
    const Scene cornell = makeBuiltinScene("cornell");
    {  // spacing larger than the scene: one probe
        RenderSettings s = small();
        setParam(s, "probes.spacing", "3");
        ProbeRun run(cornell, s);
        run.renderer->renderFrame();
        EXPECT_EQ(run.pass->grid().count(), 1);
        EXPECT_TRUE(allFinite(run.diffuse()));
        EXPECT_GT(meanRgb(run.diffuse()), 0.0);
    }
    // Scaled by 1e-3 and 1e3: the same indirect light (relative spacing, relative volumes).
    RenderSettings s = small();
    applyPreset(s, "probes", "low");
    s.ambient = glm::vec3(0.0f);
    ProbeRun one(cornell, s);
    one.renderUntilConverged(40);
    const double reference = meanRgb(one.diffuse());
    for (float scale : {1e-3f, 1e3f}) {
        ProbeRun run(scaledScene(cornell, scale), s);
        run.renderUntilConverged(40);
        const ImageF d = run.diffuse();
        ASSERT_TRUE(allFinite(d));
        std::printf("PROBES-TABLE scale %g: mean indirect.diffuse %.5f vs %.5f at x1\n", scale, meanRgb(d), reference);
        EXPECT_NEAR(meanRgb(d) / reference, 1.0, 0.05) << scale;
    }
}

// Every probe inside a solid block: with probes.inside=off all are switched off and the image is
// finite (black indirect); with relocate, those close enough to the surface move out.
TEST(Probe, ProbesInsideGeometryAreSwitchedOffOrRelocated) {
    Scene s;
    const int white = int(s.materials.size());
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    const float h = 1.0f;  // a closed cube of edge 2 around the origin, faces outward
    addQuad(s, {0, h, 0}, {0, 1, 0}, 2.0f, white);
    addQuad(s, {0, -h, 0}, {0, -1, 0}, 2.0f, white);
    addQuad(s, {h, 0, 0}, {1, 0, 0}, 2.0f, white);
    addQuad(s, {-h, 0, 0}, {-1, 0, 0}, 2.0f, white);
    addQuad(s, {0, 0, h}, {0, 0, 1}, 2.0f, white);
    addQuad(s, {0, 0, -h}, {0, 0, -1}, 2.0f, white);
    s.cameras.push_back(lookAtCamera({3, 2.5f, 4}, {0, 0, 0}, 40.0f));
    finalizeScene(s);
    for (const char* mode : {"off", "relocate"}) {
        RenderSettings r = small();
        r.background = glm::vec3(1.0f);
        setParam(r, "probes.spacing", "0.34");
        setParam(r, "probes.inside", mode);
        setParam(r, "probes.sdf-resolution", "32");
        ProbeRun run(s, r);
        run.renderer->renderFrame();
        const auto c = run.pass->stateCounts();
        std::printf("PROBES-TABLE all inside, %s: %d active, %d relocated, %d off of %d\n", mode, c.active,
                    c.relocated, c.off, run.pass->grid().count());
        EXPECT_EQ(c.active, 0) << mode;
        if (std::string(mode) == "off") EXPECT_EQ(c.off, run.pass->grid().count());
        EXPECT_TRUE(allFinite(run.diffuse()));
        EXPECT_TRUE(allFinite(run.renderer->readHdr()));
    }
}

}  // namespace
}  // namespace gis::test
