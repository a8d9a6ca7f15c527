// Nothing re-runs that did not change (#24): once every pass of a static view is settled
// (Pass::settled), a frame executes none of them, its timers say cached and the image is the same
// bits; a camera move runs them again. And `render` converges: a temporal method renders its
// frames to converge unless --frames says otherwise, with or without --timings.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <set>

#include "cli_util.h"
#include "gi/method.h"
#include "image.h"
#include "render_test_util.h"
#include "renderer.h"
#include "scene/scene.h"

namespace gis::test {
namespace {

constexpr int kMaxFrames = 64;  // a method that needs more to settle is not checked here

RenderSettings methodSettings(const std::string& method) {
    RenderSettings s;
    s.width = s.height = 32;
    const GiMethod& m = giMethod(method);
    if (std::any_of(m.presets.begin(), m.presets.end(), [](const GiPreset& p) { return p.name == "low"; }))
        applyPreset(s, method, "low");
    s.gi = method;
    return s;
}

bool readsGBuffer(const Pass& pass) {
    const std::vector<std::string> in = pass.inputs();
    return std::find(in.begin(), in.end(), resource::kGbufferDepth) != in.end();
}

// Every method whose passes settle within kMaxFrames: the next frame skips every pass, reports
// each pass and step cached and gives the same bits; a camera move re-runs what depends on it.
TEST(Settled, AStaticViewRunsNothingAndKeepsTheImage) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    std::set<std::string> settled;
    for (const GiMethod& method : giMethods()) {
        SCOPED_TRACE(method.name);
        const RenderSettings s = methodSettings(method.name);
        Renderer r(scene, s);
        r.renderFrame();
        // Its frames to converge and its progressive samples, and a frame for the consumers.
        int longest = 0;
        for (const auto& pass : r.passes()) longest = std::max(longest, pass->progress().target);
        const int budget = std::min(kMaxFrames, (method.framesToConverge ? method.framesToConverge(s) : 1) + longest + 2);
        int frames = 1;
        for (; frames < budget && !r.settled(); ++frames) r.renderFrame();
        std::printf("%s: %s after %d frames\n", method.name.c_str(), r.settled() ? "settled" : "not settled", frames);
        if (!r.settled()) continue;
        settled.insert(method.name);
        const ImageF before = r.readHdr();
        r.renderFrame();
        for (size_t k = 0; k < r.passes().size(); ++k)
            EXPECT_TRUE(r.skippedLastFrame()[k]) << r.passes()[k]->name() << " ran in a static view";
        for (const PassTiming& t : r.timings(frames))  // only the settled frame is measured
            EXPECT_TRUE(t.cached) << t.pass << " is not reported cached";
        const ImageF after = r.readHdr();
        EXPECT_TRUE(before.rgba == after.rgba) << "a skipped frame changed the image";

        CameraMatrices moved = r.camera();
        moved.position += glm::vec3(0.1f, 0.0f, 0.0f);
        moved.view = glm::translate(moved.view, glm::vec3(-0.1f, 0.0f, 0.0f));
        moved.viewProj = moved.proj * moved.view;
        moved.invViewProj = glm::inverse(moved.viewProj);
        r.setCamera(moved);
        EXPECT_FALSE(r.settled());
        r.renderFrame();
        for (size_t k = 0; k < r.passes().size(); ++k) {
            const Pass& pass = *r.passes()[k];
            const std::vector<std::string> out = pass.outputs();
            const bool radiance = std::find(out.begin(), out.end(), resource::kRadiance) != out.end();
            if (radiance || readsGBuffer(pass)) {
                EXPECT_FALSE(r.skippedLastFrame()[k]) << pass.name() << " was skipped after a camera move";
            }
        }
        EXPECT_FALSE(before.rgba == r.readHdr().rgba) << "the camera move did not change the image";
    }
    // The methods this change made settle; others join as their passes implement settled().
    for (const char* name : {"none", "ssao", "pathtrace", "ao-reference"})
        EXPECT_TRUE(settled.count(name)) << name << " did not settle within " << kMaxFrames << " frames";
}

// The probe methods' reflection (probes/screen_reflection.h) averages its reflection-frames still
// frames once the probes have converged, counts them in the pass's progress and then settles like
// the rest; with reflection=environment it has no frames of its own to wait for.
int framesToSettle(const Scene& scene, const RenderSettings& s) {
    Renderer r(scene, s);
    int frames = 0;
    for (; frames < 400 && !(frames > 0 && r.settled()); ++frames) r.renderFrame();
    return r.settled() ? frames : -1;
}

TEST(Settled, ProbeReflectionsAverageTheirFramesThenSettle) {
    context();
    const Scene scene = makeBuiltinScene("mirror");
    for (const std::string method : {"probes", "hddagi", "sdf"}) {
        SCOPED_TRACE(method);
        RenderSettings s = methodSettings(method);
        setParam(s, method + ".reflection-frames", "6");
        Renderer r(scene, s);
        int frames = 0;
        for (; frames < 400 && !(frames > 0 && r.settled()); ++frames) r.renderFrame();
        ASSERT_TRUE(r.settled()) << "not settled after " << frames << " frames";
        bool averaged = false;
        for (const auto& pass : r.passes())
            for (const std::string& line : pass->stats()) averaged = averaged || line.find("6 of 6 frames averaged") != std::string::npos;
        EXPECT_TRUE(averaged) << "no pass says it averaged its 6 reflection frames";
        RenderSettings environment = s;
        setParam(environment, method + ".reflection", "environment");
        const int withoutRays = framesToSettle(scene, environment);
        std::printf("%s: settled after %d frames with reflection rays, %d without\n", method.c_str(), frames, withoutRays);
        EXPECT_GT(withoutRays, 0);
        // The mean starts with the probes' last update, which was blended before the reflection read
        // it; the field says it has converged one frame later.
        EXPECT_GT(frames, withoutRays) << "the reflection's frames were not waited for";
    }
}

// A pass whose input was re-produced this frame runs even when it says it is settled: the lighting
// pass re-runs while ReSTIR accumulates, however settled it is itself.
TEST(Settled, AConsumerOfAReproducedInputRuns) {
    context();
    const Scene scene = makeBuiltinScene("cornell-area");
    RenderSettings s = methodSettings("none");
    setParam(s, "emitters.accumulate", "4");
    Renderer r(scene, s);
    size_t lighting = 0, emitters = r.passes().size();
    for (size_t k = 0; k < r.passes().size(); ++k) {
        if (std::string(r.passes()[k]->name()) == "lighting") lighting = k;
        if (std::string(r.passes()[k]->name()) == "emitters") emitters = k;
    }
    ASSERT_LT(emitters, r.passes().size()) << "cornell-area has emitters: the ReSTIR pass should exist";
    r.renderFrame();
    r.renderFrame();  // the lighting pass is settled now, the emitters are not
    EXPECT_TRUE(r.passes()[lighting]->settled());
    EXPECT_FALSE(r.skippedLastFrame()[lighting]) << "lighting skipped while its emitter input changed";
    EXPECT_TRUE(r.skippedLastFrame()[0]) << "the shadow maps re-ran in a static view";
    for (int i = 0; i < 4; ++i) r.renderFrame();
    EXPECT_TRUE(r.settled()) << "the emitters' average is complete after 4 frames";
}

// Frame-cost measurements execute every pass every frame (bench, --rerun-settled).
TEST(Settled, RerunSettledExecutesEveryPass) {
    context();
    Renderer r(makeBuiltinScene("cornell"), methodSettings("none"));
    r.setSkipSettled(false);
    for (int i = 0; i < 3; ++i) r.renderFrame();
    for (size_t k = 0; k < r.passes().size(); ++k) EXPECT_FALSE(r.skippedLastFrame()[k]);
    for (const PassTiming& t : r.timings(1))
        if (t.pass != "shadows") {  // the shadow pass reuses its maps itself
            EXPECT_FALSE(t.cached) << t.pass;
        }
}

int framesToConverge(const std::string& method, const std::string& preset) {
    RenderSettings s;
    applyPreset(s, method, preset);
    return giMethod(method).framesToConverge(s);
}

// `render --gi sdf` writes its converged image: the same bits as --frames of its frames to converge.
TEST(Settled, RenderConvergesATemporalMethod) {
    const std::string dir = tempDir("settled_converge");
    const std::string base = "render --scene builtin:cornell --size 32x32 --gi sdf --preset low ";
    const int frames = framesToConverge("sdf", "low");
    ASSERT_GT(frames, 1) << "sdf accumulates over frames";
    const CliResult plain = runCli(base + "--out " + dir + "/plain.exr");
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_NE(plain.err.find(std::to_string(frames) + "/" + std::to_string(frames) + " frames"), std::string::npos)
        << plain.err;
    const CliResult given = runCli(base + "--frames " + std::to_string(frames) + " --out " + dir + "/given.exr");
    ASSERT_EQ(given.status, 0) << given.err;
    const CliResult one = runCli(base + "--frames 1 --out " + dir + "/one.exr");
    ASSERT_EQ(one.status, 0) << one.err;
    const ImageF a = readExr(dir + "/plain.exr"), b = readExr(dir + "/given.exr"), c = readExr(dir + "/one.exr");
    EXPECT_TRUE(a.rgba == b.rgba) << "render without --frames is not the frames-to-converge image";
    EXPECT_FALSE(a.rgba == c.rgba) << "one frame of sdf should differ from its converged image";
}

// --frames works without --timings: temporal SSAO's running mean differs after 1 and 3 frames.
TEST(Settled, FramesWorksWithoutTimings) {
    const std::string dir = tempDir("settled_frames");
    const std::string base = "render --scene builtin:cornell --size 32x32 --gi ssao --set ssao.temporal=true ";
    const CliResult three = runCli(base + "--frames 3 --out " + dir + "/three.exr");
    ASSERT_EQ(three.status, 0) << three.err;
    EXPECT_NE(three.err.find("3/3 frames"), std::string::npos) << three.err;
    const CliResult one = runCli(base + "--frames 1 --out " + dir + "/one.exr");
    ASSERT_EQ(one.status, 0) << one.err;
    EXPECT_FALSE(readExr(dir + "/three.exr").rgba == readExr(dir + "/one.exr").rgba);
    const CliResult zero = runCli(base + "--frames 0 --out " + dir + "/zero.exr");
    EXPECT_NE(zero.status, 0);
    EXPECT_NE(zero.err.find("--frames must be"), std::string::npos) << zero.err;
}

}  // namespace
}  // namespace gis::test
