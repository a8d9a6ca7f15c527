// The sandbox from the command line: `render --settings` reproduces the panel's image and equals
// the same render made with flags; bad settings and scripts fail cleanly; and one end-to-end run of
// the real window under Xvfb, driven by a script.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_util.h"
#include "cli/panel_action.h"
#include "cli/settings_io.h"
#include "view/view_session.h"
#include "view_test_util.h"

namespace gis::test {
namespace {

using namespace gis::view;
namespace fs = std::filesystem;

ImageU8 renderCli(const std::string& args) {
    CliResult r = runCli("render " + args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
    const std::string out = args.substr(args.find("--out ") + 6, args.find(".png") + 4 - args.find("--out ") - 6);
    return readPng(out);
}

TEST(RenderSettings, EqualsTheSameRenderWithFlags) {
    const std::string dir = tempDir("view_render_settings");
    ViewState s;
    const Scene scene = makeBuiltinScene("cornell-area");
    s.scene = "builtin:cornell-area";
    resetCamera(s, scene, 0);
    resetLights(s, scene.lights);
    s.viewWidth = 48;
    s.viewHeight = 40;
    for (const char* line : {"specular 0 none", "exposure 1.5", "tonemap linear", "ambient 0.05 0.1 0.2", "preset 0 low"})
        applyPanelAction(s, parsePanelAction(splitWords(line)));
    saveViewSettings(dir + "/s.json", s);
    const ImageU8 fromSettings = renderCli("--settings " + dir + "/s.json --out " + dir + "/a.png");
    const ImageU8 fromFlags =
        renderCli("--scene builtin:cornell-area --size 48x40 --specular none --exposure 1.5 --tonemap linear "
                  "--ambient 0.05,0.1,0.2 --shadow-size 256 --shadow-cube-size 128 --out " + dir + "/b.png");
    EXPECT_EQ(fromSettings.width, 48);
    EXPECT_EQ(meanAbsDiff(fromSettings, fromFlags), 0.0);
    // A flag given explicitly overrides the file; the rest still comes from it.
    const ImageU8 overridden = renderCli("--settings " + dir + "/s.json --exposure 0 --size 32x32 --out " + dir + "/c.png");
    const ImageU8 overriddenFlags =
        renderCli("--scene builtin:cornell-area --size 32x32 --specular none --exposure 0 --tonemap linear "
                  "--ambient 0.05,0.1,0.2 --shadow-size 256 --shadow-cube-size 128 --out " + dir + "/d.png");
    EXPECT_EQ(meanAbsDiff(overridden, overriddenFlags), 0.0);
    EXPECT_GT(meanAbsDiff(overridden, renderCli("--settings " + dir + "/s.json --size 32x32 --out " + dir + "/e.png")),
              1.0);
}

// The panel's image, with a free camera, edited lights and a path-traced pane, rendered again
// headless from the saved settings: the same pixels.
TEST(RenderSettings, ReproducesThePanelsImage) {
    viewContext();
    ViewState state;
    ViewSession session;
    ASSERT_TRUE(session.openScene(state, "builtin:cornell"));
    for (const char* line : {"mode split", "method 1 pathtrace", "preset 1 low", "camera orbit 25 -10", "camera zoom 0.8",
                             "light 0 intensity 1.7", "light 0 color 1 0.8 0.6", "exposure 0.5"})
        applyPanelAction(state, parsePanelAction(splitWords(line)));
    state.viewWidth = 40;
    state.viewHeight = 32;
    for (int i = 0; i < 50 && !(i > 0 && session.settled()); ++i) session.renderFrame(state, 40, 32);
    ASSERT_TRUE(session.settled());
    const std::string dir = tempDir("view_reproduce");
    saveViewSettings(dir + "/s.json", state);
    for (int pane = 0; pane < 2; ++pane) {
        const ImageU8 cli = renderCli("--settings " + dir + "/s.json --pane " + std::to_string(pane) + " --out " + dir +
                                      "/p" + std::to_string(pane) + ".png");
        EXPECT_EQ(meanAbsDiff(cli, session.readPane(pane)), 0.0) << "pane " << pane;
    }
}

TEST(RenderSettings, BadInputFailsCleanly) {
    const std::string dir = tempDir("view_render_bad");
    { std::ofstream(dir + "/bad.json") << "{\"exposure\": []}"; }
    { std::ofstream(dir + "/single.json") << "{\"mode\": \"single\"}"; }
    struct Case {
        std::string args;
        const char* mention;
    };
    const Case cases[] = {
        {"--settings " + dir + "/missing.json --out " + dir + "/x.png", "missing.json"},
        {"--settings " + dir + "/bad.json --out " + dir + "/x.png", "exposure"},
        {"--settings " + dir + "/single.json --pane 1 --out " + dir + "/x.png", "--pane 1"},
        {"--scene builtin:cornell --pane 1 --out " + dir + "/x.png", "--pane needs --settings"},
        {"--out " + dir + "/x.png", "--scene is required"},
    };
    for (const Case& c : cases) {
        CliResult r = runCli("render " + c.args);
        EXPECT_NE(r.status, 0) << c.args;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.mention), std::string::npos) << r.err;
        EXPECT_FALSE(fileExists(dir + "/x.png"));
    }
    // A bad script is reported before any window opens.
    { std::ofstream(dir + "/bad.txt") << "wait 1\nmethod 0 magic\n"; }
    CliResult r = runCli("view --script " + dir + "/bad.txt");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("bad.txt:2:"), std::string::npos) << r.err;
    // --frame-log never replaces a file the viewer has open (here its own script), as
    // save-settings and capture do not; refused before any window opens.
    const std::string script = "wait 1\nquit\n";
    { std::ofstream(dir + "/good.txt") << script; }
    r = runCli("view --script " + dir + "/good.txt --frame-log " + dir + "/good.txt");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("the running script"), std::string::npos) << r.err;
    std::ifstream kept(dir + "/good.txt");
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>()), script);
}

// A pane's display reaches `render --pane`: a method's view is rendered (it came out as the lit
// image: the loader set the display before the method, which reset it), the heatmap, which render
// cannot draw, is refused, and a view of another method is refused when the file is read.
TEST(RenderSettings, ThePanesDisplayIsRenderedOrRefused) {
    const std::string dir = tempDir("view_pane_display");
    ViewState s;
    for (const char* line : {"method 0 vct", "display 0 vct.voxels"}) applyPanelAction(s, parsePanelAction(splitWords(line)));
    saveViewSettings(dir + "/voxels.json", s);
    const ImageU8 pane = renderCli("--settings " + dir + "/voxels.json --size 32x32 --out " + dir + "/pane.png");
    const ImageU8 voxels =
        renderCli("--scene builtin:cornell --gi vct --view vct.voxels --size 32x32 --out " + dir + "/voxels.png");
    const ImageU8 lit = renderCli("--scene builtin:cornell --gi vct --size 32x32 --out " + dir + "/lit.png");
    EXPECT_EQ(meanAbsDiff(pane, voxels), 0.0);
    EXPECT_GT(meanAbsDiff(pane, lit), 1.0);

    applyPanelAction(s, parsePanelAction(splitWords("display 0 heatmap")));
    saveViewSettings(dir + "/heatmap.json", s);
    CliResult r = runCli("render --settings " + dir + "/heatmap.json --size 32x32 --out " + dir + "/h.png");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("--pane 0 displays the error heatmap"), std::string::npos) << r.err;
    EXPECT_EQ(renderCli("--settings " + dir + "/heatmap.json --view final --size 32x32 --out " + dir + "/f.png").width, 32);

    nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/voxels.json"));
    j["panes"][0]["display"] = "sdf.slice";
    { std::ofstream(dir + "/other.json") << j.dump(); }
    r = runCli("render --settings " + dir + "/other.json --size 32x32 --out " + dir + "/o.png");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("panes[0].display': view 'sdf.slice' is a view of --gi sdf, not produced by --gi vct"),
              std::string::npos)
        << r.err;
}

// The real window under a virtual X server, driven by a script: a few frames, a split view of the
// rasterizer against the path tracer, a screenshot and a capture of the whole window.
TEST(Window, ScriptedSplitViewScreenshotUnderXvfb) {
    const std::string dir = tempDir("view_window");
    const int winW = 900, winH = 360, panelW = 420;
    {
        std::ofstream(dir + "/script.txt") << "wait 2\n"
                                              "mode split\n"
                                              "method 1 pathtrace\n"
                                              "preset 1 low\n"
                                              "camera orbit 10 0\n"
                                              "wait 1\n"
                                              "resize 700 300\n"  // size-dependent resources are rebuilt
                                              "wait 2\n"
                                              "resize " << winW << " " << winH << "\n"
                                              "converge\n"
                                              "screenshot\n"
                                              "capture " << dir << "/window.png\n"
                                              "save-settings " << dir << "/saved.json\n"
                                              "quit\n";
    }
    CliResult r = runCli("view --size " + std::to_string(winW) + "x" + std::to_string(winH) + " --script " + dir +
                             "/script.txt --screenshot-dir " + dir + "/shots -v",
                         "xvfb-run -a");
    ASSERT_EQ(r.status, 0) << r.err << r.out;
    EXPECT_NE(r.err.find("backend: glfw"), std::string::npos) << r.err;

    // The screenshot and its sidecar.
    std::string png;
    for (const auto& e : fs::directory_iterator(dir + "/shots"))
        if (e.path().extension() == ".png") png = e.path().string();
    ASSERT_FALSE(png.empty());
    EXPECT_EQ(fs::path(png).filename().string().rfind("cornell_none-vs-pathtrace_", 0), 0u) << png;
    const std::string sidecar = png.substr(0, png.size() - 4) + ".json";
    ASSERT_TRUE(fileExists(sidecar));
    const ImageU8 shot = readPng(png);
    const int viewW = winW - panelW;
    ASSERT_EQ(shot.width, viewW);
    ASSERT_EQ(shot.height, winH);

    // Its halves come from different methods: each matches its own pane rendered headless from
    // the sidecar (`render --settings`) and not the other one. (Below the labels, off the divider.)
    const ImageU8 left = renderCli("--settings " + sidecar + " --pane 0 --out " + dir + "/left.png");
    const ImageU8 right = renderCli("--settings " + sidecar + " --pane 1 --out " + dir + "/right.png");
    auto regionDiff = [&](const ImageU8& a, const ImageU8& b, int x0, int x1) {
        double sum = 0.0;
        int n = 0;
        for (int y = 30; y < a.height; ++y)
            for (int x = x0; x < x1; ++x)
                for (int k = 0; k < 3; ++k, ++n)
                    sum += std::abs(int(a.rgba[(size_t(y) * a.width + x) * 4 + k]) - int(b.rgba[(size_t(y) * b.width + x) * 4 + k]));
        return sum / n;
    };
    const int split = viewW / 2;
    EXPECT_LT(regionDiff(shot, left, 0, split - 2), 0.01);
    EXPECT_LT(regionDiff(shot, right, split + 2, viewW), 0.01);
    EXPECT_GT(regionDiff(shot, right, 0, split - 2), 2.0) << "the left half is not the path tracer's";
    EXPECT_GT(regionDiff(shot, left, split + 2, viewW), 2.0) << "the right half is not the rasterizer's";

    // The whole window: the 3D view on the left as in the screenshot, the ImGui panel on the right
    // (its dark window background, with light text on it).
    const ImageU8 window = readPng(dir + "/window.png");
    ASSERT_EQ(window.width, winW);
    ASSERT_EQ(window.height, winH);
    int panelBackground = 0, panelText = 0, total = 0;
    for (int y = 0; y < winH; ++y)
        for (int x = viewW + 10; x < winW - 20; ++x, ++total) {
            const uint8_t* p = &window.rgba[(size_t(y) * winW + x) * 4];
            panelBackground += p[0] < 30 && p[1] < 30 && p[2] < 30;
            panelText += p[0] > 180 && p[1] > 180 && p[2] > 180;
        }
    EXPECT_GT(panelBackground, total / 3) << "no ImGui window background where the panel should be";
    EXPECT_GT(panelText, 200) << "no text in the panel";
    EXPECT_LT(regionDiff(window, shot, 40, split - 40) /* the view region, away from the labels */, 2.0);

    // Saved settings equal the sidecar's.
    EXPECT_EQ(viewStateToJson(loadViewSettings(dir + "/saved.json")).dump(), viewStateToJson(loadViewSettings(sidecar)).dump());
}

// Keys are read from GLFW's callbacks, queued until the frame reads them: a tap whose press and
// release both come before the next frame (a press shorter than a frame) still switches the view.
TEST(Window, AKeyTapShorterThanAFrameTakesEffectUnderXvfb) {
    const std::string dir = tempDir("view_key_tap");
    { std::ofstream(dir + "/script.txt") << "wait 1\nkey 2\nmethod 1 ssao\nkey B\nwait 1\nsave-settings " << dir
                                         << "/saved.json\nquit\n"; }
    CliResult r = runCli("view --size 560x200 --script " + dir + "/script.txt", "xvfb-run -a");
    ASSERT_EQ(r.status, 0) << r.err << r.out;
    const ViewState saved = loadViewSettings(dir + "/saved.json");
    EXPECT_EQ(saved.mode, ViewMode::Split) << "the tap of 2 was lost";
    EXPECT_EQ(saved.panes[0].gi, "ssao") << "B, tapped in the same frame as 2, did not swap the sides";
    { std::ofstream(dir + "/bad.txt") << "wait 1\nkey F13\nquit\n"; }
    r = runCli("view --size 560x200 --script " + dir + "/bad.txt", "xvfb-run -a");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("bad.txt:2:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gis::test
