// The sandbox's GL side headless (EGL or OSMesa): the panel's actions change what the panes show
// through the same ViewSession the window uses; split/grid composites; heatmaps against the
// reference; debug displays; light edits; screenshots; resizing; no GL objects leaked over 1000
// switches; and the CPU BRDF table against the lighting pass.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "brdf_cpu.h"
#include "cli_util.h"
#include "metrics.h"
#include "cli/panel_action.h"
#include "cli/settings_io.h"
#include "view/view_session.h"
#include "view_test_util.h"

namespace gis::test {
namespace {

using namespace gis::view;
namespace fs = std::filesystem;

struct Sandbox {
    ViewState state;
    std::unique_ptr<ViewSession> session;
    explicit Sandbox(const std::string& scene = "builtin:cornell") {
        viewContext();
        session = std::make_unique<ViewSession>();
        EXPECT_TRUE(session->openScene(state, scene)) << session->lastError();
    }
    void act(const std::string& line) { applyPanelAction(state, parsePanelAction(splitWords(line))); }
    // Frames until every pane has converged (progressive methods, heatmaps).
    void settle(int w, int h, int maxFrames = 400) {
        for (int i = 0; i < maxFrames; ++i) {
            session->relight(state);  // as the window does before every frame
            session->renderFrame(state, w, h);
            if (session->settled()) return;
        }
        ADD_FAILURE() << "did not settle in " << maxFrames << " frames";
    }
    ImageU8 view(int w, int h) {
        settle(w, h);
        return session->composite(state, false);
    }
};

// A settled view renders nothing: once the pane's renderer is settled, session frames show the
// last image without a renderer frame; a camera move renders again (#24).
TEST(Session, AStaticViewRendersNoFrame) {
    Sandbox sb;
    sb.act("method 0 ssao");
    const int w = 40, h = 32;
    for (int i = 0; i < 40 && !(sb.session->pane(0).renderer && sb.session->pane(0).renderer->settled()); ++i)
        sb.session->renderFrame(sb.state, w, h);
    ASSERT_TRUE(sb.session->pane(0).renderer->settled());
    const int rendered = sb.session->framesRendered();
    const ImageU8 before = sb.session->readPane(0);
    for (int i = 0; i < 5; ++i) sb.session->renderFrame(sb.state, w, h);
    EXPECT_EQ(sb.session->framesRendered(), rendered) << "a static, settled view rendered again";
    EXPECT_EQ(meanAbsDiff(before, sb.session->readPane(0)), 0.0);
    sb.act("camera orbit 10 0");
    sb.session->renderFrame(sb.state, w, h);
    EXPECT_EQ(sb.session->framesRendered(), rendered + 1);
    EXPECT_GT(meanAbsDiff(before, sb.session->readPane(0)), 0.0);
}

// While the camera moves and full frames are over the frame budget, the pane renders at the scale
// that fits it (shown and read back at the pane's size); when it stops, the full-scale frame is
// back: the same pixels a session that never moved renders there (#24, #42). The reduced renderer
// is readied while the view rests, so the first move does not build it (vct voxelizes there).
TEST(Session, AMovingCameraRendersAtALowerScaleAndRefines) {
    EXPECT_EQ(budgetScale(20.0, 33.0), 1.0f);
    EXPECT_EQ(budgetScale(60.0, 33.0), 0.5f);
    EXPECT_EQ(budgetScale(200.0, 33.0), 0.25f);
    EXPECT_EQ(budgetScale(1000.0, 33.0), 0.125f);
    EXPECT_EQ(budgetScale(1e9, 33.0), 0.125f) << "an eighth per side at the least";
    EXPECT_EQ(budgetScale(200.0, 0.0), 1.0f) << "no budget: always full scale";
    EXPECT_EQ(defaultFrameBudgetMs("llvmpipe (LLVM 15.0.6, 256 bits)"), kCpuFrameBudgetMs);
    EXPECT_EQ(defaultFrameBudgetMs("NVIDIA H100 80GB HBM3/PCIe/SSE2"), kGpuFrameBudgetMs);
    Sandbox sb;
    sb.session->setDefaultFrameBudget(1e-9);  // every full frame is over it
    const int w = 64, h = 48;
    sb.session->renderFrame(sb.state, w, h);  // no full frame measured yet: full scale
    EXPECT_EQ(sb.session->pane(0).shownSize, sb.session->paneSize());
    const int builds = sb.session->rebuilds(), rendered = sb.session->framesRendered();
    const PaneView& pane = sb.session->pane(0);
    glFinish();  // its timer results are there for the next frame to collect
    // At rest, over the budget: the reduced renderer is readied (built and given its first frame)
    // once the full frame is measured, which is this frame or the next (when its timer arrives).
    sb.session->renderFrame(sb.state, w, h);
    ASSERT_GT(pane.fullFrameMs, 0.0) << "no GPU time collected";
    sb.session->renderFrame(sb.state, w, h);
    EXPECT_EQ(sb.session->rebuilds(), builds + 1) << "the reduced renderer is built before the first move";
    EXPECT_EQ(sb.session->framesRendered(), rendered + 1) << "and given its first frame, once";
    EXPECT_EQ(pane.scale, 1.0f) << "the full frame stays on show";
    sb.act("camera orbit 5 0");
    sb.session->renderFrame(sb.state, w, h);  // moving: an eighth of the pixels per side
    EXPECT_EQ(pane.scale, 0.125f);
    EXPECT_EQ(pane.shownSize, glm::ivec2(8, 6));
    EXPECT_EQ(sb.session->rebuilds(), builds + 1) << "the first move builds nothing";
    EXPECT_FALSE(sb.session->settled()) << "a reduced frame waits for its refinement";
    const ImageU8 moving = sb.session->readPane(0);
    EXPECT_EQ(moving.width, w);
    EXPECT_EQ(moving.height, h);
    sb.session->renderFrame(sb.state, w, h);  // stopped, the reduced view settled: full scale again
    EXPECT_EQ(pane.scale, 1.0f);
    EXPECT_EQ(pane.shownSize, sb.session->paneSize());
    Sandbox still;
    still.state.camera = sb.state.camera;
    still.session->renderFrame(still.state, w, h);
    EXPECT_EQ(meanAbsDiff(sb.session->readPane(0), still.session->readPane(0)), 0.0);
    EXPECT_GT(meanAbsDiff(moving, still.session->readPane(0)), 0.0) << "the moving frame was not reduced";
}

// A method that converges over frames, over the budget, converges at the reduced scale first; once
// that view has settled the pane climbs back: full-scale frames refine behind the reduced image,
// which stays on show until the full one has settled, the same image as without a budget. The
// state's budget overrides the machine's (#42).
TEST(Session, AConvergingPaneOverTheBudgetSettlesReducedThenClimbsToFullScale) {
    Sandbox sb;
    sb.act("method 0 pathtrace");
    sb.act("preset 0 medium");
    sb.act("frame-budget 0.000001");
    EXPECT_EQ(sb.session->frameBudgetMs(sb.state), double(1e-6f));
    const int w = 64, h = 48;
    sb.session->renderFrame(sb.state, w, h);  // measures a full frame
    glFinish();
    const PaneView& pane = sb.session->pane(0);
    bool reduced = false, refining = false;
    for (int i = 0; i < 400 && !sb.session->settled(); ++i) {
        sb.session->renderFrame(sb.state, w, h);
        reduced |= pane.scale == 0.125f && pane.status.find("converging") != std::string::npos;
        if (pane.status.find("refining at full scale") != std::string::npos) {
            EXPECT_TRUE(reduced) << "refined before the reduced view settled";
            EXPECT_EQ(pane.scale, 0.125f) << "the settled reduced image is what shows while refining";
            refining = true;
        }
    }
    ASSERT_TRUE(sb.session->settled());
    EXPECT_TRUE(reduced);
    EXPECT_TRUE(refining);
    EXPECT_EQ(pane.scale, 1.0f);
    Sandbox unbudgeted;
    unbudgeted.act("method 0 pathtrace");
    unbudgeted.act("preset 0 medium");
    EXPECT_EQ(meanAbsDiff(sb.session->readPane(0), unbudgeted.view(w, h)), 0.0);
    EXPECT_THROW(sb.act("frame-budget -1"), Error);
}

// A deferred method's debug views are drawn from what its passes hold: switching a pane's display
// to one and back rebuilds nothing, and the probes go on converging where they were (#42 item 11:
// the switch restarted the probe updates).
TEST(Session, SwitchingToADebugViewKeepsTheProbesConverging) {
    // Twelve updates a probe: enough to see them go on past the switch, and the convergence the
    // test compares against costs an eighth of the default's.
    Sandbox sb;
    sb.act("method 0 probes");
    sb.act("set 0 probes.max-updates 12");
    const int w = 32, h = 24;
    for (int i = 0; i < 5; ++i) sb.session->renderFrame(sb.state, w, h);
    const int done = sb.session->pane(0).renderer->samplesDone();
    ASSERT_GT(done, 1);
    const ImageU8 lit = sb.session->readPane(0);
    const int builds = sb.session->rebuilds();
    sb.act("display 0 probes.spheres");
    sb.session->renderFrame(sb.state, w, h);
    EXPECT_EQ(sb.session->rebuilds(), builds) << "the display switch built a new renderer";
    EXPECT_GT(sb.session->pane(0).renderer->samplesDone(), done) << "the probe updates started over";
    EXPECT_GT(meanAbsDiff(lit, sb.session->readPane(0)), 1.0) << "the debug view is not on show";
    sb.act("display 0 lit");
    sb.settle(w, h);
    EXPECT_EQ(sb.session->rebuilds(), builds);
    Sandbox fresh;
    fresh.act("method 0 probes");
    fresh.act("set 0 probes.max-updates 12");
    EXPECT_EQ(meanAbsDiff(fresh.view(w, h), sb.session->readPane(0)), 0.0) << "back to lit: not the converged image";
}

// Two panes' heatmap figures line up: the same four decimals whatever their size (#42 item 11:
// one pane read 0.123, the other 0.0456).
TEST(Session, PaneMetricsShowFourDecimals) {
    EXPECT_EQ(formatPaneMetric(0.123), "0.1230");
    EXPECT_EQ(formatPaneMetric(0.0456), "0.0456");
    EXPECT_EQ(formatPaneMetric(std::numeric_limits<double>::infinity()), "inf");
}

TEST(Session, PanelActionsChangeTheRenderedImage) {
    Sandbox s;
    const ImageU8 base = s.view(48, 48);
    EXPECT_TRUE(s.session->lastError().empty()) << s.session->lastError();
    const int builds = s.session->rebuilds();

    // The pane shows exactly what a Renderer with the pane's settings renders.
    {
        Renderer r(s.session->scene(), paneSettings(s.state, 0, {48, 48}));
        r.renderFrame();
        EXPECT_EQ(meanAbsDiff(r.readLdr(), base), 0.0);
    }

    s.act("exposure 1");
    EXPECT_GT(meanAbsDiff(s.view(48, 48), base), 1.0);
    s.act("exposure 0");
    s.act("tonemap linear");
    EXPECT_GT(meanAbsDiff(s.view(48, 48), base), 0.5);
    s.act("tonemap aces");
    EXPECT_EQ(s.session->rebuilds(), builds) << "display settings are live too";

    s.act("method 0 pathtrace");
    s.act("preset 0 low");
    const ImageU8 traced = s.view(48, 48);
    EXPECT_GT(s.session->rebuilds(), builds) << "a method switch rebuilds";
    EXPECT_GT(meanAbsDiff(traced, base), 2.0) << "the path tracer looks like the rasterizer";
    EXPECT_TRUE(s.session->pane(0).renderer->converged());
    EXPECT_EQ(s.session->pane(0).renderer->samplesDone(), 4);

    // A camera move restarts the accumulation, without a rebuild.
    const int tracedBuilds = s.session->rebuilds();
    s.act("camera orbit 15 5");
    s.session->renderFrame(s.state, 48, 48);
    EXPECT_EQ(s.session->pane(0).renderer->samplesDone(), 1) << "restarted";
    EXPECT_EQ(s.session->rebuilds(), tracedBuilds);
    const ImageU8 moved = s.view(48, 48);
    EXPECT_GT(meanAbsDiff(moved, traced), 2.0);
    // So does a BRDF switch.
    s.act("specular 0 none");
    s.session->renderFrame(s.state, 48, 48);
    EXPECT_EQ(s.session->pane(0).renderer->samplesDone(), 1);
}

// The Cornell box is ideal Lambert (specular factor 0): the BRDF switch is tried on a glossy red
// box lit by a directional light added through the panel.
TEST(Session, BrdfSwitchChangesTheImageWithoutARebuild) {
    Sandbox s(std::string(GIS_SHARED_DIR) + "/assets/gltf/Box/glTF-Binary/Box.glb");
    s.act("light add directional");
    s.act("camera orbit 30 -20");
    const ImageU8 base = s.view(48, 48);
    ASSERT_TRUE(s.session->lastError().empty()) << s.session->lastError();
    const int builds = s.session->rebuilds();
    s.act("specular 0 none");
    const ImageU8 noSpecular = s.view(48, 48);
    EXPECT_GT(meanAbsDiff(noSpecular, base), 0.05) << "the specular BRDF switch changed nothing";
    EXPECT_EQ(s.session->rebuilds(), builds) << "a BRDF switch must not rebuild the renderer";
    {
        Renderer r(s.session->scene(), paneSettings(s.state, 0, {48, 48}));
        r.setCamera(viewCameraMatrices(s.state, s.session->scene(), 1.0f));
        r.renderFrame();
        EXPECT_EQ(meanAbsDiff(r.readLdr(), noSpecular), 0.0) << "the pane is what a Renderer gives";
    }
    s.act("specular 0 ggx");
    EXPECT_EQ(meanAbsDiff(s.view(48, 48), base), 0.0) << "switching back gives the same image";
    s.act("diffuse 0 lambert");
    EXPECT_EQ(meanAbsDiff(s.view(48, 48), base), 0.0);
}

TEST(Session, SplitAndGridComposeThePanes) {
    Sandbox s;
    s.act("mode split");
    s.act("method 1 pathtrace");
    s.act("preset 1 low");
    s.act("divider 0.25");
    s.settle(64, 40);
    ASSERT_EQ(s.session->visiblePanes(), 2);
    const ImageU8 left = s.session->readPane(0), right = s.session->readPane(1);
    const ImageU8 split = s.session->composite(s.state, false);
    ASSERT_EQ(split.width, 64);
    auto px = [](const ImageU8& img, int x, int y) { return &img.rgba[(size_t(y) * img.width + x) * 4]; };
    int fromLeft = 0, fromRight = 0;
    for (int y = 0; y < 40; ++y) {
        fromLeft += std::equal(px(split, 5, y), px(split, 5, y) + 3, px(left, 5, y));
        fromRight += std::equal(px(split, 40, y), px(split, 40, y) + 3, px(right, 40, y));
    }
    EXPECT_EQ(fromLeft, 40) << "left of the divider is the left pane";
    EXPECT_EQ(fromRight, 40) << "right of it, the right pane";
    EXPECT_GT(meanAbsDiff(left, right), 2.0);

    s.act("mode grid");
    s.act("specular 2 none");
    s.act("display 3 normal");
    s.settle(64, 40);
    ASSERT_EQ(s.session->visiblePanes(), 4);
    EXPECT_EQ(s.session->paneSize(), glm::ivec2(32, 20));
    const ImageU8 grid = s.session->composite(s.state, true);
    EXPECT_EQ(grid.width, 64);
    EXPECT_EQ(grid.height, 40);
    EXPECT_GT(meanAbsDiff(s.session->readPane(3), s.session->readPane(0)), 5.0);
}

TEST(Session, GBufferDisplaysShowTheirChannels) {
    Sandbox s;
    const ImageU8 lit = s.view(40, 40);
    std::vector<ImageU8> images;
    for (const char* d : {"depth", "normal", "basecolor", "material", "emissive"}) {
        s.act(std::string("display 0 ") + d);
        images.push_back(s.view(40, 40));
        EXPECT_GT(meanAbsDiff(images.back(), lit), 1.0) << d;
    }
    for (size_t i = 0; i < images.size(); ++i)
        for (size_t j = i + 1; j < images.size(); ++j) EXPECT_GT(meanAbsDiff(images[i], images[j]), 1.0) << i << " " << j;
    // The base colour display shows the Cornell walls' albedo: red on the left, green on the right.
    const ImageU8& base = images[2];
    const uint8_t* leftWall = &base.rgba[(20 * 40 + 3) * 4];
    const uint8_t* rightWall = &base.rgba[(20 * 40 + 36) * 4];
    EXPECT_GT(leftWall[0], leftWall[1] + 50);
    EXPECT_GT(rightWall[1], rightWall[0] + 50);
    // The lighting's term views without a dot ("direct", "emission") are displays too; a typo is not.
    s.act("display 0 direct");
    const ImageU8 directTerm = s.view(40, 40);
    s.act("display 0 emission");
    EXPECT_GT(meanAbsDiff(directTerm, s.view(40, 40)), 1.0) << "the direct term looks like the (black) emission";
    EXPECT_THROW(s.act("display 0 lti"), Error);
    // Direct only removes the ambient term of --gi none.
    s.act("display 0 lit");
    s.act("direct-only 0 on");
    const ImageU8 direct = s.view(40, 40);
    double litSum = 0, directSum = 0;
    for (size_t i = 0; i < lit.rgba.size(); i += 4) litSum += lit.rgba[i + 1], directSum += direct.rgba[i + 1];
    EXPECT_LT(directSum, litSum);
}

TEST(Session, HeatmapAgainstTheReference) {
    Sandbox s;
    s.act("reference-spp 8");
    s.act("mode split");
    s.act("display 0 heatmap");
    // The right pane path-traces with the reference's own samples: no error at all.
    s.act("method 1 pathtrace");
    s.act("preset 1 low");
    s.act("display 1 heatmap");
    s.act("reference-spp 4");
    s.settle(32, 32);
    const PaneView& raster = s.session->pane(0);
    const PaneView& traced = s.session->pane(1);
    ASSERT_TRUE(raster.heatmapReady);
    ASSERT_TRUE(traced.heatmapReady);
    EXPECT_EQ(traced.metricName, "FLIP");
    EXPECT_EQ(traced.metricValue, 0.0) << "same samples, same seed: identical to the reference";
    EXPECT_GT(raster.metricValue, 0.05) << "--gi none misses all indirect light";
    const ImageU8 heat = s.session->readPane(0);
    const ImageU8 zero = s.session->readPane(1);
    EXPECT_GT(meanAbsDiff(heat, zero), 5.0);
    // The colour bar across the pane's bottom rows: the ramp from 0 (left) to heatmapMax (right).
    EXPECT_EQ(raster.heatmapMax, 1.0) << "FLIP's range";
    for (const ImageU8* pane : {&heat, &zero})
        for (int x : {0, pane->width - 1}) {
            const glm::vec3 expected = heatmapColor(x == 0 ? 0.0f : 1.0f) * 255.0f;
            const uint8_t* px = &pane->rgba[(size_t(pane->height - 1) * pane->width + x) * 4];
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(px[k], expected[k], 2.0) << "x " << x << " channel " << k;
        }
    // The reference is cached: switching the metric recomputes the map, not the reference.
    const int builds = s.session->rebuilds();
    s.act("metric rmse");
    s.settle(32, 32);
    EXPECT_EQ(s.session->rebuilds(), builds);
    EXPECT_EQ(s.session->pane(0).metricName, "RMSE");
    EXPECT_GT(s.session->pane(0).metricValue, 0.0);
    // A camera move invalidates it.
    s.act("camera orbit 5 0");
    s.session->renderFrame(s.state, 32, 32);
    EXPECT_FALSE(s.session->pane(0).heatmapReady);
    s.settle(32, 32);
    EXPECT_TRUE(s.session->pane(0).heatmapReady);
}

// The pixel inspector reads the pane's radiance at the pixel asked for and, once the heatmap's reference has converged, the reference's radiance there.
TEST(Session, PixelInspectorReadsThePaneAndTheReference) {
    Sandbox s;
    s.act("reference-spp 4");
    s.act("method 0 none");
    s.settle(32, 32);
    EXPECT_FALSE(s.session->inspectPixel(s.state, 0, {32, 0}).has_value()) << "outside the pane";
    const ImageF hdr = s.session->pane(0).renderer->readHdr();
    for (glm::ivec2 p : {glm::ivec2(3, 5), glm::ivec2(16, 16), glm::ivec2(30, 27)}) {
        const auto r = s.session->inspectPixel(s.state, 0, p);
        ASSERT_TRUE(r.has_value());
        EXPECT_EQ(r->radiance, glm::make_vec3(hdr.at(p.x, p.y)));
        EXPECT_FALSE(r->hasReference) << "no heatmap, no reference";
    }
    s.act("display 0 heatmap");
    s.settle(32, 32);
    const auto withRef = s.session->inspectPixel(s.state, 0, {16, 16});
    ASSERT_TRUE(withRef.has_value());
    EXPECT_TRUE(withRef->hasReference);
    EXPECT_GT(withRef->reference.g, 0.0f);
    EXPECT_NE(withRef->reference, withRef->radiance) << "--gi none misses the indirect light the reference has";
}

// A toon pane cannot be compared with the path tracer: it keeps its image and says why, in the
// viewer's words (not the command line's flags).
TEST(Session, HeatmapOfANonPhysicalBrdfKeepsTheImage) {
    Sandbox s;
    s.act("specular 0 toon");
    const ImageU8 lit = s.view(32, 32);
    s.act("display 0 heatmap");
    const ImageU8 shown = s.view(32, 32);
    EXPECT_EQ(meanAbsDiff(shown, lit), 0.0) << "the lit image stays";
    const PaneView& p = s.session->pane(0);
    EXPECT_FALSE(p.heatmapReady);
    EXPECT_NE(p.status.find("physically based BRDFs only"), std::string::npos) << p.status;
    EXPECT_EQ(p.status.find("--"), std::string::npos) << "no command-line flags in the viewer: " << p.status;
    EXPECT_TRUE(s.session->lastError().empty()) << s.session->lastError();
}

TEST(Session, LightEditsChangeTheImage) {
    Sandbox s;
    const ImageU8 base = s.view(32, 32);
    s.act("light 0 intensity 0");
    const ImageU8 dark = s.view(32, 32);
    EXPECT_GT(meanAbsDiff(base, dark), 5.0);
    s.act("light 0 off");
    s.act("light 0 intensity 1");
    EXPECT_EQ(meanAbsDiff(s.view(32, 32), dark), 0.0) << "a disabled light lights nothing";
    s.act("lights reset");
    EXPECT_EQ(meanAbsDiff(s.view(32, 32), base), 0.0);
}

// A lightmap pane after a light edit: the last bake stays on show and its status says it is
// stale while the next bake runs; once that is done the mark is gone (#41). With every light baked
// (lightmap.mode=all) the frame is the lightmap alone: the old image until the new bake is done.
TEST(Session, ALightEditMarksTheLightmapStaleUntilItIsBakedAgain) {
    Sandbox s;
    for (const char* line : {"method 0 lightmap", "set 0 lightmap.texels 1024", "set 0 lightmap.samples 8",
                             "set 0 lightmap.cache false", "set 0 lightmap.mode all"})
        s.act(line);
    const ImageU8 base = s.view(32, 32);
    EXPECT_EQ(s.session->pane(0).status.find("stale"), std::string::npos) << s.session->pane(0).status;
    s.act("light 0 intensity 0.25");
    s.session->relight(s.state);
    s.session->renderFrame(s.state, 32, 32);
    EXPECT_NE(s.session->pane(0).status.find("stale"), std::string::npos) << s.session->pane(0).status;
    EXPECT_EQ(meanAbsDiff(s.session->composite(s.state, false), base), 0.0) << "the last bake is shown";
    const ImageU8 dimmer = s.view(32, 32);
    EXPECT_EQ(s.session->pane(0).status.find("stale"), std::string::npos) << s.session->pane(0).status;
    EXPECT_GT(meanAbsDiff(dimmer, base), 5.0);
}

// --lighting auto gives an unlit model the default sun and sky unless an environment map lights
// it. A map set after the scene opened (the panel, a script, --environment over a settings file)
// takes the sun away as one set before would, and clearing it brings the sun back (#26).
TEST(Session, AnEnvironmentMapSetLaterReplacesAutosDefaultSun) {
    const std::string box = std::string(GIS_SHARED_DIR) + "/assets/gltf/Box/glTF-Binary/Box.glb";
    const std::string sky = std::string(GIS_SOURCE_DIR) + "/assets/environments/sky_sun.hdr";
    Sandbox later(box);
    ASSERT_EQ(later.session->sceneLights().size(), 1u) << "auto adds the default sun to an unlit model";
    const ImageU8 sunlit = later.view(32, 32);
    later.act("environment " + sky);
    const ImageU8 mapLit = later.view(32, 32);
    EXPECT_GT(meanAbsDiff(sunlit, mapLit), 1.0);
    EXPECT_TRUE(later.session->sceneLights().empty());
    EXPECT_TRUE(later.state.lights.empty()) << "the panel's light list follows";

    Sandbox first;  // the map chosen before the scene opens
    first.act("environment " + sky);
    ASSERT_TRUE(first.session->openScene(first.state, box)) << first.session->lastError();
    EXPECT_TRUE(first.session->sceneLights().empty());
    EXPECT_EQ(meanAbsDiff(first.view(32, 32), mapLit), 0.0);

    later.act("environment off");
    EXPECT_EQ(meanAbsDiff(later.view(32, 32), sunlit), 0.0) << "the sun comes back with the default sky";
    EXPECT_EQ(later.session->sceneLights().size(), 1u);
}

// A light list the user edited stays as edited when the environment changes.
TEST(Session, AnEnvironmentMapKeepsEditedLights) {
    Sandbox s(std::string(GIS_SHARED_DIR) + "/assets/gltf/Box/glTF-Binary/Box.glb");
    s.act("light 0 intensity 2");
    s.act("environment " + std::string(GIS_SOURCE_DIR) + "/assets/environments/sky_sun.hdr");
    s.session->relight(s.state);
    ASSERT_EQ(s.state.lights.size(), 1u);
    EXPECT_TRUE(s.state.lightsEdited);
    EXPECT_TRUE(s.state.sceneLights.empty()) << "what \"lights reset\" returns to: the map alone";
}

TEST(Session, OpeningABadSceneKeepsThePreviousOne) {
    Sandbox s;
    const ImageU8 base = s.view(32, 32);
    const std::string dir = tempDir("view_bad_scene");
    { std::ofstream(dir + "/broken.gltf") << "{\"asset\": "; }
    for (const std::string& bad : {dir + "/broken.gltf", dir + "/missing.glb", std::string("builtin:nothing")}) {
        EXPECT_FALSE(s.session->openScene(s.state, bad));
        const std::string& error = s.session->lastError();
        const std::string name = bad.substr(bad.find_last_of("/:") + 1);
        EXPECT_NE(error.find(name), std::string::npos) << error;
        EXPECT_EQ(error.find(name), error.rfind(name)) << "the path is said once: " << error;
        EXPECT_EQ(s.state.scene, "builtin:cornell");
        EXPECT_EQ(meanAbsDiff(s.view(32, 32), base), 0.0);
    }
    EXPECT_TRUE(s.session->openScene(s.state, "builtin:cornell-area"));
    EXPECT_GT(meanAbsDiff(s.view(32, 32), base), 1.0);
}

TEST(Session, ScreenshotWritesPngAndSidecarAtomically) {
    Sandbox s;
    s.act("mode split");
    s.act("specular 1 none");
    s.settle(64, 48);
    const std::string dir = tempDir("view_screenshot");
    const std::string png = s.session->writeScreenshot(s.state, dir, "test GL");
    EXPECT_EQ(fs::path(png).filename().string().rfind("cornell_none-vs-vct_", 0), 0u) << png;  // the default split: none | vct
    const std::string json = png.substr(0, png.size() - 4) + ".json";
    ASSERT_TRUE(fs::exists(png));
    ASSERT_TRUE(fs::exists(json));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2) << "temporary files left";
    const ImageU8 img = readPng(png);
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
    // The sidecar is a settings file: loading it gives the same state back.
    const ViewState loaded = loadViewSettings(json);
    EXPECT_EQ(viewStateToJson(loaded).dump(), viewStateToJson(s.state).dump());
    std::ifstream f(json);
    const auto side = nlohmann::json::parse(f);
    ASSERT_EQ(side["panes"].size(), 2u);
    EXPECT_EQ(side["panes"][1]["render_settings"]["specular"], "none");
    EXPECT_FALSE(side["panes"][0]["passes"].empty());
    EXPECT_EQ(side["gl_renderer"], "test GL");
    // A second one in the same second gets its own name.
    const std::string png2 = s.session->writeScreenshot(s.state, dir, "test GL");
    EXPECT_NE(png2, png);
}

TEST(Session, ResizeRecreatesSizeDependentResources) {
    Sandbox s;
    s.act("display 0 normal");
    for (glm::ivec2 size : {glm::ivec2(40, 30), glm::ivec2(17, 61), glm::ivec2(1, 1), glm::ivec2(40, 30)}) {
        s.session->renderFrame(s.state, size.x, size.y);
        EXPECT_EQ(s.session->paneSize(), size);
        const ImageU8 img = s.session->readPane(0);
        EXPECT_EQ(img.width, size.x);
        EXPECT_EQ(s.session->pane(0).renderer->settings().width, size.x);
    }
    s.act("render-scale 0.5");
    s.session->renderFrame(s.state, 40, 30);
    EXPECT_EQ(s.session->paneSize(), glm::ivec2(20, 15));
}

// 1000 switches of method, preset, BRDFs, view mode and display (heatmaps included) through the
// panel's actions: every GL object the panes, references and displays made is gone again.
TEST(Session, NoGlObjectsLeakOver1000Switches) {
    Sandbox s;
    s.act("reference-spp 2");
    // The grid's last two panes as this cycle was timed (a new view opens them on probes and the
    // path tracer; rebuilding those 40 times would double the test's time, not its coverage).
    s.act("method 2 none");
    s.act("method 3 none");
    const GlObjectCounts empty = countGlObjects();
    // Mostly low presets: a rebuild renders the shadow maps, and high ones cost llvmpipe ~100 ms.
    const char* cycle[] = {"method 0 pathtrace", "specular 0 none",   "mode split",        "method 1 pathtrace",
                           "preset 0 low",       "display 1 heatmap", "mode grid",         "display 2 depth",
                           "diffuse 3 lambert",  "specular 0 ggx",    "method 0 none",     "preset 1 low",
                           "mode single",        "display 1 lit",     "display 2 lit",     "method 1 none",
                           "preset 0 medium",    "display 0 normal",  "display 0 heatmap", "preset 0 low",
                           "display 0 lit",      "tonemap linear",    "exposure 1",        "tonemap aces",
                           "exposure 0"};
    const int n = int(sizeof cycle / sizeof cycle[0]);
    auto runCycle = [&] {
        for (int i = 0; i < n; ++i) {
            s.act(cycle[i]);
            s.session->renderFrame(s.state, 24, 16);
            ASSERT_TRUE(s.session->lastError().empty()) << cycle[i] << ": " << s.session->lastError();
        }
    };
    // Twice first: what is kept between frames (references for coming back to, display textures,
    // each pass's ring of 4 timer queries) reaches its steady state.
    runCycle();
    runCycle();
    const GlObjectCounts steady = countGlObjects();
    const int64_t steadyBytes = s.session->gpuBytes();
    const int buildsBefore = s.session->rebuilds();
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < 1000 / n; ++k) runCycle();  // 40 cycles of 25
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const GlObjectCounts after = countGlObjects();
    std::printf("1000 switches in %.1f s (%d renderers built); live GL objects: %s\n", seconds,
                s.session->rebuilds() - buildsBefore, describe(after).c_str());
    EXPECT_GE(s.session->rebuilds() - buildsBefore, 400);
    EXPECT_EQ(describe(after), describe(steady));
    EXPECT_EQ(s.session->gpuBytes(), steadyBytes);
    s.session->releaseRenderers();
    EXPECT_EQ(describe(countGlObjects()), describe(empty)) << "released: back to the session's own objects";
    s.session.reset();
    const GlObjectCounts none = countGlObjects();
    EXPECT_EQ(none.total(), 0) << describe(none);
}

// The lobe plot's CPU BRDF table against the lighting pass (shaders/brdf.glsl): a floor under a
// directional light, seen by an orthographic camera, has one (N, V, L) at every pixel, so its
// radiance is f(L, V) E N.L exactly.
TEST(BrdfTable, MatchesTheLightingPass) {
    viewContext();
    struct Case {
        float lightDeg, viewDeg, roughness;
        SpecularModel specular;
        DiffuseModel diffuse = DiffuseModel::Lambert;
    };
    std::vector<Case> cases = {{30, 30, 102 / 255.0f, SpecularModel::Ggx},  // mirror: the specular peak
                               {60, 20, 153 / 255.0f, SpecularModel::Ggx},
                               {10, 70, 51 / 255.0f, SpecularModel::Ggx},
                               {45, 45, 102 / 255.0f, SpecularModel::None}};
    // Every entry of the table (every model brdf.glsl has), away from the mirror direction: the
    // camera is orthographic but the lighting pass takes V per pixel, so the peak is not a fair place.
    for (const DiffuseModelInfo& d : diffuseModels())
        for (const SpecularModelInfo& sp : specularModels())
            for (glm::vec2 angles : {glm::vec2(60, 20), glm::vec2(10, 70)}) {
                // Toon specular steps on R.V: keep R.V on the flat part of its ramp (R.V = cos 20).
                if (sp.model == SpecularModel::Toon && angles.x == 10) angles = glm::vec2(20, 40);
                cases.push_back({angles.x, angles.y, 102 / 255.0f, sp.model, d.model});
            }
    EXPECT_EQ(diffuseModels().size(), 4u);
    EXPECT_EQ(specularModels().size(), 4u);
    for (const Case& c : cases) {
        Scene scene;
        Material m;
        m.baseColorFactor = glm::vec4(1.0f);
        m.metallicFactor = 0.0f;
        m.roughnessFactor = c.roughness;
        scene.materials.push_back(m);
        Primitive p;
        for (glm::vec2 q : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            Vertex v;
            v.position = glm::vec3(q.x, 0.0f, q.y);
            v.normal = glm::vec3(0, 1, 0);
            p.vertices.push_back(v);
        }
        p.indices = {0, 2, 1, 0, 3, 2};
        p.material = 0;
        scene.primitives.push_back(p);
        scene.draws.push_back({0, glm::mat4(1.0f)});
        const float tl = glm::radians(c.lightDeg), tv = glm::radians(c.viewDeg);
        const glm::vec3 L(std::sin(tl), std::cos(tl), 0.0f), V(-std::sin(tv), std::cos(tv), 0.0f), N(0, 1, 0);
        Light light;
        light.type = LightType::Directional;
        light.intensity = 2.0f;
        light.direction = -L;
        scene.lights.push_back(light);
        Camera cam;
        cam.orthographic = true;
        cam.xmag = cam.ymag = 0.2f;
        cam.znear = 0.01f;
        cam.zfar = 10.0f;
        cam.cameraToWorld = glm::inverse(glm::lookAt(V * 3.0f, glm::vec3(0.0f), glm::vec3(0, 0, -1)));
        scene.cameras.push_back(cam);
        finalizeScene(scene);
        RenderSettings rs;
        rs.width = rs.height = 8;
        rs.hdr32 = true;
        rs.shadows = false;
        rs.ambient = glm::vec3(0.0f);
        rs.specular = c.specular;
        rs.diffuse = c.diffuse;
        Renderer r(scene, rs);
        r.renderFrame();
        const ImageF img = r.readHdr();
        const CpuSurfaceBrdf surface = makeCpuSurfaceBrdf(glm::vec3(1.0f), 0.0f, c.roughness, 1.0f);
        const glm::vec3 expected = evaluateCpuBrdf(surface, N, V, L, c.diffuse, c.specular) *
                                   light.intensity * glm::dot(N, L);
        const float got = img.at(4, 4)[0];
        EXPECT_NEAR(got, expected.r, std::max(2e-3f * expected.r, 1e-5f))
            << "light " << c.lightDeg << " view " << c.viewDeg << " roughness " << c.roughness << " "
            << diffuseModelName(c.diffuse) << "+" << specularModelName(c.specular);
    }
}

}  // namespace
}  // namespace gis::test
