// Radiance does not depend on the unit of length: every registered method renders a scene scaled
// by 1e-6, 1e-3, 1e3 and 1e6 as it renders it at x1 (scaledScene moves camera, clip planes and
// lights with the geometry and scales point-light intensity by scale^2). One test per method on the
// point-lit and on the emitter-lit box (the cascaded methods also on the building), each at its low
// preset on 32x32; the tolerance is on the
// image mean and on every pixel's neighbourhood. At x1e-6 the rasterizer once lost the point
// light's highlight to an absolute clamp of d^2 and ssao 2% of its mean to an absolute radius floor.
#include <gtest/gtest.h>

#include <cmath>

#include "gi/method.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

struct Case {
    std::string method, scene;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.method << " on " << c.scene; }

std::vector<Case> cases() {
    std::vector<Case> all;
    for (const GiMethod& m : giMethods()) {
        if (m.name.rfind("test-", 0) == 0) continue;  // test-only methods registered by other tests
        all.push_back({m.name, "cornell"});
    }
    all.push_back({"pathtrace", "mirror"});  // specular paths: the case that was 12% dark at 1e-3
    for (const char* method : {"pathtrace", "none", "vct", "sdf", "probes", "hddagi"})
        all.push_back({method, "cornell-area"});  // emitter-lit: ReSTIR's sampling and the volume's emitter light
    // Cascades around the camera: their count follows the view, not the unit (at x1e-3 HDDAGI once
    // got one coarse volume for the building's four cascades).
    for (const char* method : {"sdf", "probes", "hddagi"}) all.push_back({method, "building"});
    return all;
}

double mean(const ImageF& img) {
    double sum = 0.0;
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) sum += img.rgba[i];
    return sum / double(img.rgba.size() / 4 * 3);
}

// Mean over 4x4 blocks, so a pixel's worth of edge shift does not count as a different image.
double worstBlock(const ImageF& a, const ImageF& b) {
    const ImageF da = downsample(a, 4), db = downsample(b, 4);
    double worst = 0.0, peak = 1e-6;
    for (size_t i = 0; i < da.rgba.size(); ++i)
        if (i % 4 != 3) {
            worst = std::max(worst, std::abs(double(da.rgba[i]) - db.rgba[i]));
            peak = std::max(peak, double(db.rgba[i]));
        }
    return worst / peak;
}

class ScaleInvariance : public ::testing::TestWithParam<Case> {};

TEST_P(ScaleInvariance, SameImageAtEveryScale) {
    const Case& c = GetParam();
    context();
    RenderSettings s;
    s.width = s.height = 32;
    s.hdr32 = true;
    applyPreset(s, c.method, "low");
    s.samplesPerFrame = 64;
    const Scene base = makeBuiltinScene(c.scene);
    const ImageF unit = renderHdr(scaledScene(base, 1.0f), s);
    const double m1 = mean(unit);
    ASSERT_GT(m1, 0.0) << "black at x1";
    for (float scale : {1e-6f, 1e-3f, 1e3f, 1e6f}) {
        const ImageF img = renderHdr(scaledScene(base, scale), s);
        for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v)) << "scale " << scale;
        const double m = mean(img), block = worstBlock(img, unit);
        std::printf("%s on %s at x%g: mean %.5f (x1 %.5f, %+.2f%%), worst 4x4 block %.2f%% of the peak\n",
                    c.method.c_str(), c.scene.c_str(), scale, m, m1, 100.0 * (m / m1 - 1.0), 100.0 * block);
        // On the building, probe GI's path test (a voxel walk from the pixel to each probe) turns
        // for a few of the 32x32 pixels where rounding moves a wall plane across a cell face:
        // +1.0% of the mean at x1e-3 with it, +0.3% without (measured 2026-12-07).
        const double tolerance = c.scene == "building" ? 0.02 : 0.01;
        EXPECT_NEAR(m, m1, tolerance * m1) << "scale " << scale;
        EXPECT_LT(block, 0.05) << "scale " << scale;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, ScaleInvariance, ::testing::ValuesIn(cases()), [](const auto& info) {
    std::string n = info.param.method + "_" + info.param.scene;
    for (char& ch : n)
        if (ch == '-') ch = '_';
    return n;
});

}  // namespace
}  // namespace gis::test
