// The closed room lit by its emissive panel (builtin:room?lamp=panel), where bounce light is most
// of the image: issue #23's energy check. Each GI method at its defaults, the emitter a light of the
// direct pass, must bring the room's mean radiance within 85-115% of the path tracer's (64
// bounces). The pixels that see the panel are left out (emitterPixels): they are its emission, the
// same in every method. renderer/emitters/README.md has the measured table
// (EmitterTables.DISABLED_PanelRoomEnergy, 256 spp, and the `gi` mode's rows).
#include <cstdio>

#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 64;

RenderSettings panelRoomSettings(const std::string& gi) {
    RenderSettings r;
    r.width = r.height = kSize;
    r.gi = gi;
    setParam(r, "emitters.mode", "lights");
    return r;
}

// The path tracer's mean of the room (64 bounces) and the pixels that see the panel.
struct Truth {
    std::vector<bool> panel;
    double mean = 0.0;
};

Truth pathTraced(const Scene& scene) {
    Truth t;
    RenderSettings pt = panelRoomSettings("pathtrace");
    t.panel = emitterPixels(scene, pt);
    pt.samplesPerFrame = 16;
    setParam(pt, "pathtrace.spp", "64");
    setParam(pt, "pathtrace.bounces", "64");
    t.mean = meanRgbExcept(renderHdr(scene, pt), t.panel);
    return t;
}

TEST(EmitterPanelRoom, EveryMethodBringsTheRoomWithinFifteenPercentOfThePathTracer) {
    const Scene scene = makeBuiltinScene("room?lamp=panel");
    const Truth truth = pathTraced(scene);
    ASSERT_GT(truth.mean, 0.0);
    for (const char* gi : {"vct", "sdf", "probes", "hddagi"}) {
        const ImageF img = renderHdr(scene, panelRoomSettings(gi));
        ASSERT_TRUE(allFinite(img)) << gi;
        const double mean = meanRgbExcept(img, truth.panel), ratio = mean / truth.mean;
        std::printf("panel room: %-7s mean %.4f, path tracer %.4f, ratio %.3f\n", gi, mean, truth.mean, ratio);
        EXPECT_GE(ratio, 0.85) << gi;
        EXPECT_LE(ratio, 1.15) << gi;
    }
}

// What the check above would catch: direct light alone (no method's bounces) is far short.
TEST(EmitterPanelRoom, DirectLightAloneFallsShort) {
    const Scene scene = makeBuiltinScene("room?lamp=panel");
    const Truth truth = pathTraced(scene);
    RenderSettings none = panelRoomSettings("none");
    none.ambient = glm::vec3(0.0f);
    EXPECT_LT(meanRgbExcept(renderHdr(scene, none), truth.panel) / truth.mean, 0.7);
}

}  // namespace
}  // namespace gis::test
