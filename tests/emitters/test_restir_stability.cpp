// ReSTIR's reuse stays bounded (issue 37): a sample reused in time and space never carries more
// than its own domain's estimate, so no pixel grows over frames, at any unit of length. The 1/Z
// weights this module used before amplified a sample by sum M / Z whenever fewer reservoirs could
// produce it than it was weighed with, and the history fed that back every frame: white patches on
// the DamagedHelmet's visor after ~16 frames, 65504 on a mirror sphere's box scaled by 1e-3.
#include <algorithm>

#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr float kEmitterRadiance = 15.0f;

// The Cornell box with a mirror sphere and a rough metal sphere (builtin:mirror), lit only by a
// textured emitter under its ceiling: a checker of two colours, so the emitter's radiance varies
// over its surface as a texture's does.
Scene glossyEmitterScene() {
    Scene s = makeBuiltinScene("mirror");
    s.lights.clear();
    Image checker;
    checker.name = "checker";
    checker.width = checker.height = 4;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const bool a = (x + y) % 2 == 0;
            for (uint8_t c : {uint8_t(255), uint8_t(a ? 255 : 60), uint8_t(a ? 255 : 20), uint8_t(255)})
                checker.rgba8.push_back(c);
        }
    s.images.push_back(checker);
    Material lamp = lambert(glm::vec3(0.0f));
    lamp.name = "TexturedLamp";
    lamp.emissive = glm::vec3(kEmitterRadiance);
    lamp.emissiveTexture = int(s.images.size()) - 1;
    s.materials.push_back(lamp);
    addQuad(s, glm::vec3(0, 1.98f, 0), glm::vec3(0, -1, 0), 0.6f, int(s.materials.size()) - 1);
    finalizeScene(s);
    return s;
}

RenderSettings directOnly(int size) {
    RenderSettings r;
    r.width = r.height = size;
    r.hdr32 = true;
    r.ambient = glm::vec3(0.0f);
    r.gi = "none";
    r.view = "direct";  // the emitters' light alone: not their own pixels, whose edges the two filter differently
    setParam(r, "emitters.mode", "lights");
    return r;
}

// The pixels where the mirror shows the emitter itself (direct light above a quarter of its
// radiance in either image), grown by one pixel: the emitter's edge again, which the rasterizer
// samples at the pixel's centre and the path tracer over its area, as for the emitter's own pixels.
std::vector<bool> reflectedEmitter(const ImageF& a, const ImageF& b) {
    std::vector<bool> bright(size_t(a.width) * a.height);
    for (size_t i = 0; i < bright.size(); ++i)
        for (int c = 0; c < 3; ++c) bright[i] = bright[i] || std::max(a.rgba[i * 4 + c], b.rgba[i * 4 + c]) > 0.25f * kEmitterRadiance;
    return grownByOnePixel(bright, a.width, a.height);
}

double meanRgb(const ImageF& img) {
    return meanRgbExcept(img, std::vector<bool>(size_t(img.width) * img.height, false));
}

float maxRgb(const ImageF& img) {
    float m = 0.0f;
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) m = std::max(m, img.rgba[i]);
    return m;
}

// The default reuse on mirrors: the running mean of every pixel stays under the largest emitter
// radiance (direct light is at most the radiance of what is seen times the directional albedo,
// at most one here), at three units of length; the image's mean is the path tracer's direct light.
// The rasterizer samples each pixel's centre and the path tracer its area, so ReSTIR renders at
// twice the size and is averaged down (2x2) before the means are compared. (The issue asked for
// 1,000 frames; the suite affords 128 at x1 and 48 at each other scale on llvmpipe. Run by hand
// at 256 and 96 frames the means were -1.4%, -1.2% and -1.2%.)
TEST(RestirStability, MirrorsStayBoundedAndUnbiasedAtEveryScale) {
    const Scene base = glossyEmitterScene();
    RenderSettings pt = directOnly(32);
    pt.gi = "pathtrace";
    pt.samplesPerFrame = 16;
    setParam(pt, "pathtrace.spp", "512");
    setParam(pt, "pathtrace.bounces", "0");
    const ImageF reference = renderHdr(base, pt);
    ASSERT_GT(meanRgb(reference), 0.0);
    for (float scale : {1.0f, 1e-3f, 1e3f}) {
        RenderSettings s = directOnly(64);
        setParam(s, "emitters.accumulate", scale == 1.0f ? "128" : "48");
        const ImageF img = renderHdr(scaledScene(base, scale), s);
        ASSERT_TRUE(allFinite(img)) << "scale " << scale;
        const ImageF small = downsample(img, 2);
        const std::vector<bool> skip = reflectedEmitter(small, reference);
        EXPECT_LT(std::count(skip.begin(), skip.end(), true), int(skip.size()) / 50) << "scale " << scale;
        const double mean = meanRgbExcept(small, skip), truth = meanRgbExcept(reference, skip);
        std::printf("x%g: mean %.5f (path tracer %.5f, %+.2f%%), brightest pixel %.3f\n", scale, mean, truth,
                    100.0 * (mean / truth - 1.0), maxRgb(img));
        EXPECT_LE(maxRgb(img), kEmitterRadiance) << "scale " << scale;
        EXPECT_NEAR(mean, truth, 0.02 * truth) << "scale " << scale;
    }
}

// The case users met first: the DamagedHelmet at its Cycles reference's framing, 256x256 (the
// divergence did not show at 128x128). The mean after 24 frames is the mean after 8 (the old
// weights: RMSE against Cycles 0.46 after 8 frames, 364 after 16). The issue asked for 256 frames;
// 24 is what the suite affords at this size on llvmpipe.
TEST(RestirStability, DamagedHelmetAfter24FramesIsTheImageAfter8) {
    const std::string path = std::string(GIS_SHARED_DIR) + "/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf";
    Scene scene = loadGltfFile(path);
    Camera camera = lookAtCamera(glm::vec3(0, 0, 3.2f), glm::vec3(0), 40.0f);
    scene.cameras.insert(scene.cameras.begin(), camera);
    RenderSettings s = directOnly(256);
    s.view = "final";  // the image a user sees: the sky's radiance 1 and the emitters' direct light
    s.background = glm::vec3(1.0f);
    setParam(s, "emitters.accumulate", "24");
    context();
    Renderer renderer(scene, s);
    double after8 = 0;
    for (int frame = 1; frame <= 24; ++frame) {
        renderer.renderFrame();
        if (frame == 8) after8 = meanRgb(renderer.readHdr());
    }
    const ImageF last = renderer.readHdr();
    ASSERT_TRUE(allFinite(last));
    const double after24 = meanRgb(last);
    std::printf("mean after 8 frames %.5f, after 24 %.5f (%+.3f%%)\n", after8, after24,
                100.0 * (after24 / after8 - 1.0));
    EXPECT_NEAR(after24, after8, 0.01 * after8);
}

}  // namespace
}  // namespace gis::test
