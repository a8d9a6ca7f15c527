// pathtrace.caustics=false, as Cycles' caustics switches: after a diffuse bounce no glossy light.
// On builtin:mirror with one bounce, the same seed draws the same random numbers either way, so
// pixels whose path never bounces diffusely before it ends (the spheres seen directly, the direct
// light everywhere) are bit-identical, and walls and ceiling lose the light the metal spheres
// reflect onto them from the lamp (their caustics).
#include <gtest/gtest.h>

#include "render_test_util.h"

namespace gis::test {
namespace {

TEST(PathTraceCaustics, SwitchRemovesGlossyLightAfterADiffuseBounceOnly) {
    context();
    const Scene scene = makeBuiltinScene("mirror");
    RenderSettings r;
    r.width = r.height = 48;
    r.gi = "pathtrace";
    r.samplesPerFrame = 64;
    setParam(r, "pathtrace.spp", "64");
    setParam(r, "pathtrace.bounces", "1");
    const ImageF on = renderHdr(scene, r);
    setParam(r, "pathtrace.caustics", "false");
    const ImageF off = renderHdr(scene, r);
    // Direct light alone (no bounce) cannot carry a caustic: identical.
    setParam(r, "pathtrace.bounces", "0");
    EXPECT_EQ(renderHdr(scene, r).rgba, [&] {
        RenderSettings d = r;
        setParam(d, "pathtrace.caustics", "true");
        return renderHdr(scene, d).rgba;
    }());
    // The mirror sphere's centre, seen directly: identical pixels.
    const glm::ivec2 sphere = projectToPixel(scene, r, glm::vec3(-0.4f, 0.35f, -0.3f));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(on.at(sphere.x, sphere.y)[c], off.at(sphere.x, sphere.y)[c]);
    // The light the spheres reflect from the lamp up onto walls and ceiling (their caustics) is
    // gone without caustics: the image holds less light.
    double withCaustic = 0.0, without = 0.0;
    for (size_t i = 0; i < on.rgba.size(); ++i)
        if (i % 4 != 3) withCaustic += on.rgba[i], without += off.rgba[i];
    std::printf("image sum: %.3f with caustics, %.3f without (%.2f%% caustic light)\n", withCaustic, without,
                100.0 * (withCaustic - without) / withCaustic);
    EXPECT_GT(withCaustic, without * 1.001);  // 0.30% measured at 48x48, 64 spp, one bounce
    // Never more light without caustics, pixel by pixel (the paths are the same or cut short).
    int brighter = 0;
    for (size_t i = 0; i < on.rgba.size(); ++i)
        if (i % 4 != 3 && off.rgba[i] > on.rgba[i] * (1.0f + 1e-5f) + 1e-7f) ++brighter;
    EXPECT_EQ(brighter, 0);
}

}  // namespace
}  // namespace gis::test
