// VCT at a reduced trace resolution (vct.trace-scale 2 and 4): the upsampling keeps depth edges,
// the jittered frames converge to the full-resolution trace, and a static view settles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gi/method.h"
#include "render_test_util.h"
#include "vct_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 128;

RenderSettings settingsAt(int traceScale) {
    RenderSettings s;
    s.width = s.height = kSize;
    s.gi = "vct";
    setVct(s, "trace-scale", std::to_string(traceScale));
    return s;
}

// Upsampling keeps edges: on the rows through the quad's middle, the first reduced-resolution
// frame (every pixel but one per block upsampled, no history) matches the full-resolution trace
// everywhere farther than one traced texel from the depth step, to 5% of the step's contrast in
// indirect light. A blend across the step would put the wall's light on the quad (or the quad's
// darkness on the wall) up to the width of the upsampling footprint.
TEST(VctRealtime, UpsamplingKeepsDepthEdges) {
    const Scene scene = depthStepScene();
    // Marching cones: the same light for a pixel traced alone or with its block, so what differs is
    // the upsampling's. (With rays, vct.sky-rays, one traced pixel's rays differ from its
    // neighbours' by their noise, which frames average out: ReducedResolutionConvergesToFullResolution.)
    auto marchingAt = [](int traceScale) {
        RenderSettings s = settingsAt(traceScale);
        setVct(s, "sky-rays", "0");
        return s;
    };
    const VctImages full = renderVct(scene, marchingAt(1));
    const std::vector<PixelHit> hits = castPixels(scene, 0, kSize, kSize, nullptr);
    const int quad = hits[size_t(kSize / 2) * kSize + kSize / 2].region;
    auto at = [&](const ImageF& img, int x, int y) { return double(img.rgba[(size_t(y) * kSize + x) * 4]); };
    // The contrast: the wall just outside the quad against the quad just inside, full resolution.
    double wall = 0.0, front = 0.0;
    for (int x = 0; x < kSize; ++x) {
        const bool onQuad = hits[size_t(kSize / 2) * kSize + x].region == quad;
        (onQuad ? front : wall) = std::max(onQuad ? front : wall, at(full.diffuse, x, kSize / 2));
    }
    const double contrast = wall - front;
    ASSERT_GT(contrast, 0.0);
    ASSERT_GT(wall, 4.0 * front) << "the scene gives no contrast across the step to test";
    for (int scale : {2, 4}) {
        const VctImages reduced = renderVct(scene, marchingAt(scale), 1);
        double worst = 0.0;
        for (int y = kSize / 2 - 8; y <= kSize / 2 + 8; ++y)
            for (int x = 0; x < kSize; ++x) {
                bool nearEdge = false;  // a pixel of the other side within one traced texel on the row or column
                const int region = hits[size_t(y) * kSize + x].region;
                for (int d = -scale; d <= scale; ++d) {
                    const int xs = std::clamp(x + d, 0, kSize - 1), ys = std::clamp(y + d, 0, kSize - 1);
                    nearEdge |= hits[size_t(y) * kSize + xs].region != region;
                    nearEdge |= hits[size_t(ys) * kSize + x].region != region;
                }
                if (nearEdge) continue;
                worst = std::max(worst, std::abs(at(reduced.diffuse, x, y) - at(full.diffuse, x, y)) / contrast);
            }
        std::printf("VCT-REALTIME trace-scale %d, first frame: largest difference from full resolution beyond "
                    "one traced texel of the step %.4f of the contrast (wall %.4f, quad %.4f)\n",
                    scale, worst, wall, front);
        EXPECT_LT(worst, 0.05) << "trace-scale " << scale;
    }
}

// Mean over background-free pixels of |a - b| / max(b, floor), red green blue.
double meanRelativeDifference(const ImageF& a, const ImageF& b) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < b.rgba.size(); i += 4) {
        for (size_t c = 0; c < 3; ++c) {
            if (b.rgba[i + c] <= 0.0f) continue;
            sum += std::abs(double(a.rgba[i + c]) - double(b.rgba[i + c])) / std::max(double(b.rgba[i + c]), 1e-3);
            ++n;
        }
    }
    return n ? sum / n : 0.0;
}

// After framesToConverge frames of a static view every pixel has been traced once, exactly as the
// full-resolution trace traces it: the mean relative difference of indirect.diffuse and
// indirect.specular falls to under 1e-3 (fp16 rounding), from far above it on the first frame.
TEST(VctRealtime, ReducedResolutionConvergesToFullResolution) {
    const Scene scene = makeBuiltinScene("cornell");
    const VctImages full = renderVct(scene, settingsAt(1));
    for (int scale : {2, 4}) {
        const RenderSettings s = settingsAt(scale);
        const int frames = giMethod("vct").framesToConverge(s);
        EXPECT_EQ(frames, scale * scale);
        const VctImages first = renderVct(scene, s, 1);
        const VctImages converged = renderVct(scene, s, frames);
        const double before = meanRelativeDifference(first.diffuse, full.diffuse);
        const double after = meanRelativeDifference(converged.diffuse, full.diffuse);
        const double specular = meanRelativeDifference(converged.specular, full.specular);
        std::printf("VCT-REALTIME trace-scale %d: mean relative difference of indirect.diffuse from full "
                    "resolution %.5f after 1 frame, %.6f after %d (specular %.6f)\n",
                    scale, before, after, frames, specular);
        EXPECT_LT(after, 1e-3) << "trace-scale " << scale;
        EXPECT_LT(specular, 1e-3) << "trace-scale " << scale;
        EXPECT_GT(before, 10.0 * after + 1e-4) << "the first frame already matched: the test shows nothing";
    }
}

// A static view settles after framesToConverge frames; a camera move or a light edit unsettles it
// until the view has stood still that long again. At trace-scale 1 one frame settles it.
TEST(VctRealtime, StaticViewSettlesAndACameraMoveUnsettles) {
    context();
    Scene scene = makeBuiltinScene("cornell");
    scene.cameras.push_back(lookAtCamera({0.3f, 1.0f, 3.9f}, {0, 1, 0}));
    for (int scale : {1, 4}) {
        RenderSettings s = settingsAt(scale);
        setVct(s, "resolution", "32");
        const int frames = giMethod("vct").framesToConverge(s);
        Renderer r(scene, s);
        const VctPass& pass = vctPassOf(r);
        auto settlesAfter = [&] {
            int n = 0;
            while (!pass.settled() && n <= frames) {
                r.renderFrame();
                ++n;
            }
            return n;
        };
        EXPECT_FALSE(pass.settled()) << "settled before the first frame";
        EXPECT_EQ(settlesAfter(), frames) << "trace-scale " << scale;
        r.renderFrame();
        EXPECT_TRUE(pass.settled()) << "a static view unsettled by itself";
        r.setCamera(cameraMatrices(scene, int(scene.cameras.size()) - 1, 1.0f));
        EXPECT_FALSE(pass.settled()) << "a camera move left it settled";
        EXPECT_EQ(settlesAfter(), frames) << "trace-scale " << scale;
        r.lightsChanged();
        EXPECT_FALSE(pass.settled()) << "a light edit left it settled";
        EXPECT_EQ(settlesAfter(), frames) << "trace-scale " << scale;
    }
}

}  // namespace
}  // namespace gis::test
