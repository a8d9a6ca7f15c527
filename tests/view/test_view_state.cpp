// The sandbox's panel logic without GL: actions (what the widgets, keys and scripts call),
// settings for the renderers, the camera, settings files, scripts and the CPU BRDF table.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "brdf_cpu.h"
#include "cli_util.h"
#include "gi/method.h"
#include "cli/settings_io.h"
#include "view/view_script.h"
#include "view/view_session.h"
#include "cli/view_state.h"

namespace gis::test {
namespace {

using namespace gis::view;

ViewState stateFor(const Scene& scene) {
    ViewState s;
    resetCamera(s, scene, 0);
    resetLights(s, scene.lights);
    return s;
}

// A state with every group of settings away from its default.
ViewState unusualState(const Scene& scene) {
    ViewState s = stateFor(scene);
    for (const char* line :
         {"mode grid", "method 1 pathtrace", "preset 1 high", "specular 2 none", "display 3 normal", "direct-only 0 on",
          "divider 0.3", "exposure -1.5", "tonemap linear", "ambient 0.1 0.2 0.3", "shadows off", "background 0.5 0.25 1",
          "max-bounces 3", "render-scale 0.5", "metric ssim", "reference-spp 32", "camera orbit 20 -10",
          "camera zoom 0.8", "camera mode fly", "light 0 intensity 2.5", "light 0 color 1 0.5 0.25",
          "light add spot", "light 1 direction 0 -1 0.1", "light 0 off", "plot material 0.2 0.4 0.6 0.5 0.7 0.9",
          "plot view-angle 30", "plot log on", "plot pane 2"})
        applyPanelAction(s, parsePanelAction(splitWords(line)));
    return s;
}

TEST(PanelActions, ChangeOnlyWhatTheySay) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    applyPanelAction(s, PanelAction::method(1, "pathtrace"));
    EXPECT_EQ(s.panes[1].gi, "pathtrace");
    EXPECT_EQ(s.panes[0].gi, "none");
    applyPanelAction(s, PanelAction::specular(0, "none"));
    EXPECT_EQ(s.panes[0].specular, SpecularModel::None);
    EXPECT_EQ(s.panes[1].specular, SpecularModel::Ggx);
    applyPanelAction(s, PanelAction::viewMode(ViewMode::Split));
    EXPECT_EQ(s.mode, ViewMode::Split);
    applyPanelAction(s, PanelAction::dividerAt(5.0f));
    EXPECT_FLOAT_EQ(s.divider, 0.98f) << "dragging past the edge clamps";
}

TEST(PanelActions, BadValuesThrowAndLeaveTheStateAlone) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    const std::string before = viewStateToJson(s).dump();
    const char* bad[] = {"method 0 magic",  "method 4 none",     "preset 0 ultra",    "diffuse 0 velvet",
                         "specular 0 x",    "display 0 albedo",  "mode quad",         "exposure 1e9",
                         "tonemap filmic",  "ambient -1",        "render-scale 2",    "metric psnr",
                         "reference-spp 0", "max-bounces 1.5",   "camera zoom 0",     "camera mode walk",
                         "light 7 off",     "light 0 direction 0 0 0", "light add area", "shadows maybe",
                         "exposure abc",    "method 0",          "frobnicate"};
    for (const char* line : bad) {
        EXPECT_THROW(applyPanelAction(s, parsePanelAction(splitWords(line))), Error) << line;
        EXPECT_EQ(viewStateToJson(s).dump(), before) << line;
    }
}

// The panel draws a pane's method's table and then the shared emitters.* table (a deferred
// method's frame reads it; the path tracer's does not), and an edit there reaches the pane's
// renderer settings like a method's.
TEST(PanelTables, DeferredPanesShowTheEmitterTableAfterTheMethods) {
    const Scene scene = makeBuiltinScene("cornell-area");
    ViewState s = stateFor(scene);
    applyPanelAction(s, PanelAction::method(0, "vct"));
    const std::vector<ParamTableView> vct = paneParamTables(s.panes[0]);
    ASSERT_EQ(vct.size(), 2u);
    EXPECT_EQ(vct[0].name, "vct");
    EXPECT_EQ(vct[0].params, &giMethod("vct").params);
    EXPECT_EQ(vct[1].name, "emitters");
    EXPECT_EQ(vct[1].params, &paramGroups()[0].params);
    applyPanelAction(s, PanelAction::method(1, "pathtrace"));
    for (const ParamTableView& t : paneParamTables(s.panes[1])) EXPECT_NE(t.name, "emitters");
    for (const ParamDesc& d : *vct[1].params) {
        if (d.type != ParamType::Int) continue;
        const std::string key = "emitters." + d.key;
        applyPanelAction(s, PanelAction::param(0, key, formatParamValue(d, ParamValue{d.max})));
        EXPECT_EQ(paneParam(s, 0, "emitters", d).number, d.max) << key;
        EXPECT_EQ(paneSettings(s, 0, {64, 64}).params.at(key).number, d.max) << key;
    }
}

TEST(PaneSettings, CombineSharedPaneAndDebugOptions) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    applyPanelAction(s, parsePanelAction(splitWords("exposure 1.25")));
    applyPanelAction(s, parsePanelAction(splitWords("method 0 pathtrace")));
    applyPanelAction(s, parsePanelAction(splitWords("preset 0 low")));
    RenderSettings r = paneSettings(s, 0, {64, 32});
    EXPECT_EQ(r.gi, "pathtrace");
    EXPECT_EQ(getParam(r, "pathtrace.spp").number, 4) << "pathtrace/low is 4 spp";
    EXPECT_EQ(r.samplesPerFrame, 1) << "the view adds a sample per frame";
    EXPECT_EQ(r.width, 64);
    EXPECT_EQ(r.height, 32);
    EXPECT_FLOAT_EQ(r.exposureEV, 1.25f);
    applyPanelAction(s, PanelAction::directOnly(0, true));
    EXPECT_EQ(getParam(paneSettings(s, 0, {8, 8}), "pathtrace.bounces").number, 0);
    applyPanelAction(s, PanelAction::method(0, "none"));
    EXPECT_EQ(paneSettings(s, 0, {8, 8}).ambient, glm::vec3(0.0f)) << "direct only: no ambient term";
    applyPanelAction(s, PanelAction::preset(0, "high"));
    EXPECT_EQ(paneSettings(s, 0, {8, 8}).shadowMapSize, 2048);
    // A G-buffer display keeps the pane's method: every method can show its G-buffer.
    applyPanelAction(s, PanelAction::method(0, "pathtrace"));
    applyPanelAction(s, PanelAction::display(0, PaneDisplay::Normal));
    EXPECT_EQ(paneSettings(s, 0, {8, 8}).gi, "pathtrace");
    EXPECT_EQ(paneSettings(s, 0, {8, 8}).view, "gbuffer.normal");
    // The reference: full GI at reference-spp, the pane's BRDFs.
    applyPanelAction(s, PanelAction::specular(0, "none"));
    const RenderSettings ref = referenceSettings(s, 0, {8, 8});
    EXPECT_EQ(ref.gi, "pathtrace");
    EXPECT_EQ(getParam(ref, "pathtrace.spp").number, s.referenceSpp);
    EXPECT_EQ(getParam(ref, "pathtrace.bounces").number, s.maxBounces);
    EXPECT_EQ(ref.specular, SpecularModel::None);
}

TEST(PaneSettings, RectsAndRenderSizes) {
    ViewState s;
    EXPECT_EQ(paneRects(ViewMode::Single, 200, 100).size(), 1u);
    const auto split = paneRects(ViewMode::Split, 200, 100);
    ASSERT_EQ(split.size(), 2u);
    EXPECT_EQ(split[1].w, 200) << "split panes both cover the view; the divider picks what shows";
    const auto grid = paneRects(ViewMode::Grid, 201, 101);
    ASSERT_EQ(grid.size(), 4u);
    EXPECT_EQ(grid[3].x + grid[3].w, 201);
    EXPECT_EQ(grid[3].y + grid[3].h, 101);
    s.mode = ViewMode::Grid;
    s.renderScale = 0.5f;
    EXPECT_EQ(paneRenderSize(s, 200, 100), glm::ivec2(50, 25));
    EXPECT_EQ(paneRenderSize(s, 0, 0), glm::ivec2(1, 1)) << "a minimised window still gives a valid size";
}

TEST(Camera, StartsAtTheSceneCameraAndOrbitsItsTarget) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    EXPECT_FALSE(s.camera.free);
    const CameraMatrices scenes = cameraMatrices(scene, 0, 1.0f);
    EXPECT_EQ(viewCameraMatrices(s, scene, 1.0f).viewProj, scenes.viewProj) << "untouched: exactly the scene camera";
    // The free camera's pose is the scene camera's.
    s.camera.free = true;
    const CameraMatrices free = viewCameraMatrices(s, scene, 1.0f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(free.view[c][r], scenes.view[c][r], 1e-5f);
    s.camera.free = false;

    const glm::vec3 target = s.camera.position + cameraForward(s.camera) * s.camera.distance;
    applyPanelAction(s, PanelAction::orbit(0.7f, 0.3f));
    EXPECT_TRUE(s.camera.free);
    const glm::vec3 target2 = s.camera.position + cameraForward(s.camera) * s.camera.distance;
    EXPECT_NEAR(glm::length(target2 - target), 0.0f, 1e-4f) << "orbiting keeps the target";
    EXPECT_NEAR(glm::length(s.camera.position - target), s.camera.distance, 1e-4f);
    applyPanelAction(s, PanelAction::orbit(0.0f, 10.0f));
    EXPECT_LT(s.camera.pitch, 1.56f) << "pitch stops short of straight up";
    applyPanelAction(s, PanelAction::zoom(0.5f));
    const glm::vec3 target3 = s.camera.position + cameraForward(s.camera) * s.camera.distance;
    EXPECT_NEAR(glm::length(target3 - target), 0.0f, 1e-4f);
    const glm::vec3 before = s.camera.position;
    applyPanelAction(s, PanelAction::move(glm::vec3(0.0f, 0.0f, 1.0f)));
    EXPECT_NEAR(glm::length(s.camera.position - before - cameraForward(s.camera)), 0.0f, 1e-5f) << "fly forward";
    PanelAction reset;
    reset.kind = PanelAction::ResetCamera;
    applyPanelAction(s, reset);
    EXPECT_FALSE(s.camera.free);
    EXPECT_EQ(viewCameraMatrices(s, scene, 1.0f).viewProj, scenes.viewProj);
}

TEST(Lights, EditsReplaceTheScenesLightsAndReset) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    EXPECT_EQ(effectiveLights(s, scene.lights).size(), scene.lights.size());
    applyPanelAction(s, parsePanelAction(splitWords("light 0 intensity 3")));
    applyPanelAction(s, parsePanelAction(splitWords("light add point")));
    ASSERT_EQ(effectiveLights(s, scene.lights).size(), 2u);
    EXPECT_FLOAT_EQ(effectiveLights(s, scene.lights)[0].intensity, 3.0f);
    applyPanelAction(s, parsePanelAction(splitWords("light 1 off")));
    EXPECT_EQ(effectiveLights(s, scene.lights).size(), 1u);
    applyPanelAction(s, parsePanelAction(splitWords("light remove 0")));
    EXPECT_EQ(effectiveLights(s, scene.lights).size(), 0u) << "the only enabled light was removed";
    applyPanelAction(s, parsePanelAction(splitWords("lights reset")));
    EXPECT_FALSE(s.lightsEdited);
    EXPECT_FLOAT_EQ(effectiveLights(s, scene.lights)[0].intensity, scene.lights[0].intensity);
}

TEST(SettingsFile, RoundTripIsIdentical) {
    const Scene scene = makeBuiltinScene("cornell");
    const ViewState s = unusualState(scene);
    const std::string dir = tempDir("view_settings_roundtrip");
    saveViewSettings(dir + "/a.json", s);
    const ViewState loaded = loadViewSettings(dir + "/a.json");
    EXPECT_EQ(viewStateToJson(loaded).dump(), viewStateToJson(s).dump());
    // What the renderers get is identical too, pane by pane, and the camera.
    for (int i = 0; i < kMaxPanes; ++i)
        EXPECT_EQ(renderSettingsToJson(paneSettings(loaded, i, {64, 48})).dump(),
                  renderSettingsToJson(paneSettings(s, i, {64, 48})).dump());
    EXPECT_EQ(viewCameraMatrices(loaded, scene, 1.5f).viewProj, viewCameraMatrices(s, scene, 1.5f).viewProj);
    ASSERT_EQ(effectiveLights(loaded, scene.lights).size(), effectiveLights(s, scene.lights).size());
    EXPECT_EQ(lightToJson(effectiveLights(loaded, scene.lights)[0]).dump(),
              lightToJson(effectiveLights(s, scene.lights)[0]).dump());
    // Saved twice, byte for byte the same file.
    saveViewSettings(dir + "/b.json", loaded);
    std::ifstream a(dir + "/a.json"), b(dir + "/b.json");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 2)
        << "a temporary file was left behind";
}

TEST(SettingsFile, BadFilesNameTheProblem) {
    const std::string dir = tempDir("view_settings_bad");
    struct Case {
        const char* json;
        const char* mention;
    };
    const Case cases[] = {
        {"{\"exposure\": \"bright\"}", "exposure"},
        {"{\"panes\": [{\"gi\": \"magic\"}]}", "panes[0].gi"},
        {"{\"camera\": {\"yfov\": 0}}", "camera"},
        {"{\"lights\": [{\"type\": \"area\"}]}", "lights[0]"},
        {"{\"gisandbox_view_settings\": 99}", "version"},
        {"{\"colour\": 1}", "colour"},
        {"[1, 2]", "object"},
        {"{\"mode\": ", "not valid JSON"},
        {"{\"exposure\": 1e-400}", "1e-400"},  // underflows: read as 0 before
        {"{\"exposure\": -2.5e-999}", "-2.5e-999"},
    };
    for (const Case& c : cases) {
        {
            std::ofstream(dir + "/bad.json") << c.json;
        }
        try {
            loadViewSettings(dir + "/bad.json");
            ADD_FAILURE() << c.json << " loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(c.mention), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
        }
    }
    {
        std::ofstream(dir + "/zero.json") << "{\"exposure\": 0.0e-400}";  // zero, however it is written
    }
    EXPECT_NO_THROW(loadViewSettings(dir + "/zero.json"));
    EXPECT_THROW(loadViewSettings(dir + "/missing.json"), Error);
}

// A whole-number key written as a double (64.0, as a tool that writes every number as a double
// does) loads as the integer; a fraction is still refused naming the key (issue 27: 64.0 was
// refused as "must be a whole number").
TEST(SettingsFile, AWholeNumberWrittenAsADoubleLoads) {
    const std::string dir = tempDir("view_settings_whole");
    {
        std::ofstream(dir + "/whole.json") << R"({"panes": [{"gi": "vct", "params": {"vct.resolution": 64.0}}]})";
        std::ofstream(dir + "/half.json") << R"({"panes": [{"gi": "vct", "params": {"vct.resolution": 64.5}}]})";
    }
    ViewState s;
    ASSERT_NO_THROW(s = loadViewSettings(dir + "/whole.json"));
    ASSERT_EQ(s.panes[0].params.count("vct.resolution"), 1u);
    EXPECT_EQ(s.panes[0].params.at("vct.resolution").number, 64.0);
    try {
        loadViewSettings(dir + "/half.json");
        ADD_FAILURE() << "64.5 loaded as a whole number";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vct.resolution' must be a whole number"), std::string::npos) << e.what();
    }
}

// A method parameter's value in a script's or the panel's `set`, and in `render --set` and its
// aliases, is a number as a settings file writes it: 0x10, +5, .5 and inf are refused naming the
// word, and 1e-400 (strtod reads it as 0; ssao.radius 0 means "15% of the scene") is refused as
// too small, where they were all taken silently. 0.0e-400 is zero however it is written.
TEST(Script, ParameterValuesAreStrictNumbers) {
    for (const char* bad : {"0x10", "+5", ".5", "inf", "1e-400", "5e-999", "1e-50"}) {
        for (const std::string& line : {std::string("set 0 ssao.radius ") + bad, std::string("set 0 ssao.slices ") + bad}) {
            try {
                parseScript("method 0 ssao\n" + line + "\n", "s.txt");
                ADD_FAILURE() << line << " was accepted";
            } catch (const Error& e) {
                const std::string what = e.what();
                EXPECT_EQ(what.rfind("s.txt:2: ", 0), 0u) << what;
                EXPECT_NE(what.find(bad), std::string::npos) << what;
                EXPECT_TRUE(what.find("is not a number") != std::string::npos ||
                            what.find("is not an integer") != std::string::npos || what.find("too small") != std::string::npos)
                    << what;
            }
        }
        ViewState s;
        applyPanelAction(s, PanelAction::method(0, "ssao"));
        const ViewState before = s;
        EXPECT_THROW(applyPanelAction(s, PanelAction::param(0, "ssao.radius", bad)), Error) << bad;
        EXPECT_EQ(s.panes[0].params, before.panes[0].params) << bad;
        const std::string dir = tempDir("view_set_numbers");
        for (const std::string& flag : {std::string("--set ssao.radius="), std::string("--ao-radius=")}) {
            const CliResult r = runCli("render --scene builtin:cornell --gi ssao --size 8x8 " + flag + bad + " --out " + dir +
                                       "/x.png");
            EXPECT_EQ(r.status, 1) << flag << bad;
            EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
            EXPECT_FALSE(std::filesystem::exists(dir + "/x.png")) << flag << bad;
        }
    }
    for (const char* good : {"0.5", "5e-1", "2", "1E+1", "0.0e-400", "0"})
        EXPECT_NO_THROW(parseScript(std::string("method 0 ssao\nset 0 ssao.radius ") + good + "\n", "s.txt")) << good;
    EXPECT_NO_THROW(parseScript("method 0 ssao\nset 0 ssao.slices 8\n", "s.txt"));
}

TEST(Script, ParsesTimedActionsAndNamesBadLines) {
    const auto steps = parseScript(
        "# a comment\nwait 3\nmode split\n\nmethod 1 pathtrace  # trailing comment\nconverge\nsleep 0.5\n"
        "screenshot\ncapture out.png\nresize 640 480\nscene builtin:cornell-area\nquit\n",
        "t.txt");
    ASSERT_EQ(steps.size(), 10u);
    EXPECT_EQ(steps[0].kind, ScriptStep::Wait);
    EXPECT_EQ(steps[0].frames, 3);
    EXPECT_EQ(steps[1].kind, ScriptStep::Action);
    EXPECT_EQ(steps[2].action.kind, PanelAction::SetMethod);
    EXPECT_EQ(steps[2].line, 5);
    EXPECT_EQ(steps[3].kind, ScriptStep::Converge);
    EXPECT_DOUBLE_EQ(steps[4].seconds, 0.5);
    EXPECT_EQ(steps[6].path, "out.png");
    EXPECT_EQ(steps[7].width, 640);
    EXPECT_EQ(steps[9].kind, ScriptStep::Quit);
    for (const char* bad : {"wait x", "wait -1", "capture", "resize 10", "method 1", "fly away"}) {
        try {
            parseScript(std::string("wait 1\n") + bad + "\n", "s.txt");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind("s.txt:2: ", 0), 0u) << e.what();
        }
    }
}

// The script's error for `lines` in context (checkScriptInContext on `state`), without "NAME:LINE: ".
std::string contextError(const std::string& lines, const ViewState& state, int* line = nullptr) {
    try {
        checkScriptInContext(parseScript(lines, "c.txt"), state, "c.txt");
    } catch (const Error& e) {
        const std::string what = e.what();
        const size_t colon = what.find(':', 6);
        if (line) *line = std::stoi(what.substr(6, colon - 6));
        return what.substr(colon + 2);
    }
    return "";
}

// What `render` says about the same settings (its one error line, without "gisandbox: error: ").
std::string cliError(const std::string& args) {
    // A directory per test: two tests calling this at once under ctest -j2 emptied each other's.
    const std::string dir =
        tempDir(std::string("view_context_cli_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const CliResult r = runCli("render --scene builtin:cornell --size 8x8 --out " + dir + "/x.png " + args);
    EXPECT_NE(r.status, 0) << args;
    const std::string prefix = "gisandbox: error: ";
    const size_t at = r.err.find(prefix);
    return at == std::string::npos ? r.err : r.err.substr(at + prefix.size(), r.err.find('\n', at) - at - prefix.size());
}

// Each command below is valid on a fresh state, so checking one line at a time let it through
// (exit 0, a black or unchanged pane); in the script's context it is refused before the window opens,
// with the message render gives for the same settings.
TEST(Script, LinesThatFailOnlyInContextAreRefusedBeforeTheWindowOpens) {
    const Scene scene = loadScene("builtin:cornell");
    const ViewState state = stateFor(scene);
    for (const char* line : {"display 0 sdf.slice", "set 0 sdf.rays 8", "method 2 vct", "display 0 indirect.diffuse"})
        EXPECT_NO_THROW(parseScript(std::string(line) + "\n", "one.txt")) << line << ": valid alone";

    // A view of another method: the CLI's message for --gi vct --view sdf.slice.
    int line = 0;
    EXPECT_EQ(contextError("method 0 vct\ndisplay 0 sdf.slice\n", state, &line), cliError("--gi vct --view sdf.slice"));
    EXPECT_EQ(line, 2);
    EXPECT_EQ(contextError("method 0 sdf\ndisplay 0 sdf.slice\n", state), "");
    // A lighting term a method without the lighting pass does not write itself (issue 26's
    // per-term views: the AO reference writes none; the path tracer writes them all).
    const std::string term = contextError("method 0 ao-reference\ndisplay 0 indirect.diffuse\n", state);
    EXPECT_EQ(term, cliError("--gi ao-reference --view indirect.diffuse"));
    EXPECT_NE(term.find("none, ssao, pathtrace, vct"), std::string::npos) << term;
    EXPECT_EQ(contextError("method 0 pathtrace\ndisplay 0 direct\ndisplay 0 pathtrace.indirect\ndisplay 0 indirect.diffuse\n", state), "");
    EXPECT_NE(contextError("method 0 ao-reference\ndisplay 0 direct\n", state).find("pathtrace"), std::string::npos);
    EXPECT_EQ(contextError("method 0 ssao\ndisplay 0 indirect.diffuse\nmethod 0 pathtrace\n", state), "")
        << "a new method resets the display";

    // A value the parameter's range allows but the method refuses: render's message.
    EXPECT_EQ(contextError("method 0 vct\nset 0 vct.resolution 33\n", state), cliError("--gi vct --set vct.resolution=33"));
    EXPECT_EQ(contextError("method 0 vct\nset 0 vct.debug-level 2\n", state),
              cliError("--gi vct --set vct.debug-level=2"));
    EXPECT_EQ(contextError("method 0 vct\nset 0 vct.debug-channel occupancy\nset 0 vct.debug-level 2\n", state), "");

    // Another method's parameter does nothing on this pane.
    const std::string other = contextError("method 0 vct\nset 0 sdf.rays 8\n", state);
    EXPECT_NE(other.find("sdf.rays is a parameter of another method than pane 0's vct"), std::string::npos) << other;
    EXPECT_EQ(contextError("method 0 sdf\nset 0 sdf.rays 8\nset 0 emitters.mode lights\n", state), "");

    // A pane the mode does not show; keys 1 2 3 change the mode as the buttons do.
    const std::string hidden = contextError("mode split\nmethod 2 vct\n", state, &line);
    EXPECT_NE(hidden.find("pane 2 is not shown in split mode"), std::string::npos) << hidden;
    EXPECT_EQ(line, 2);
    EXPECT_NE(contextError("method 1 ssao\n", state).find("pane 1 is not shown in single mode"), std::string::npos);
    EXPECT_EQ(contextError("mode grid\nmethod 2 vct\nkey 2\nmethod 1 ssao\nkey B\nset 0 ssao.radius 0.5\n", state), "")
        << "after B, pane 0 is the ssao pane";

    // Lights past what the shadow maps hold: the renderer's own message, at the first light too many.
    std::string many;
    for (int i = 0; i < 500; ++i) many += "light add point\n";
    const std::string lights = contextError(many, state, &line);
    EXPECT_NE(lights.find("shadow cube maps hold at most 341"), std::string::npos) << lights;
    EXPECT_EQ(line, 341) << "cornell's own point light plus 340 added fit";
    EXPECT_EQ(contextError("shadows off\n" + many, state), "");
    EXPECT_NE(contextError("shadows off\n" + many + "shadows on\n", state).find("hold at most 341"), std::string::npos);
    EXPECT_NE(contextError("light 0 color 3e38 3e38 3e38\n", state).find("magnitude <= 1e18"), std::string::npos);
    EXPECT_NE(contextError("light 1 intensity 2\n", state).find("light 1 does not exist"), std::string::npos)
        << "light edits are checked against the scene's lights";

}

// The lines after a `scene` or `settings` line are checked against the state that file gives, as
// the run will find it (they were once checked one at a time, so a light the new scene lacks or a
// pane its mode hides went through with exit 0).
TEST(Script, LinesAfterASceneOrSettingsFileAreCheckedAgainstWhatItLoads) {
    const Scene scene = loadScene("builtin:cornell");
    const ViewState state = stateFor(scene);
    int line = 0;
    EXPECT_EQ(contextError("light 0 intensity 2\n", state), "") << "cornell has its point light";
    const std::string gone = contextError("scene builtin:cornell-area\nlight 0 intensity 2\n", state, &line);
    EXPECT_NE(gone.find("light 0 does not exist"), std::string::npos) << gone << ": the emitter box has no light";
    EXPECT_EQ(line, 2);
    EXPECT_EQ(contextError("scene builtin:no-such-scene\nlight 0 intensity 2\n", state), "")
        << "a scene that does not open leaves the state as it was (the run's warning)";

    const std::string dir = tempDir("view_context_settings");
    ViewState grid = state, split = state;
    grid.mode = ViewMode::Grid;
    split.mode = ViewMode::Split;
    saveViewSettings(dir + "/grid.json", grid);
    saveViewSettings(dir + "/split.json", split);
    EXPECT_EQ(contextError("settings " + dir + "/grid.json\nmethod 2 vct\n", state), "");
    const std::string hidden = contextError("settings " + dir + "/split.json\nmethod 2 vct\n", state, &line);
    EXPECT_NE(hidden.find("pane 2 is not shown in split mode"), std::string::npos) << hidden;
    EXPECT_EQ(line, 2);
    const std::string missing = contextError("settings " + dir + "/none.json\nmethod 0 vct\n", state, &line);
    EXPECT_NE(missing.find("none.json"), std::string::npos) << missing;
    EXPECT_EQ(line, 1) << "a settings file that does not load stops the run: refused at its line";
}

// What save-settings writes always loads (issue 27): a camera moved 20000 units from the Cornell
// box, or zoomed out as far, has its znear 0.01 at 5e-7 of the scene's depth, which the settings
// loader refuses (render --settings and the viewer alike); the file was written all the same and
// the script ended with exit 0. The save is refused now, naming the file, before the window opens
// for a script line and by the session for the panel's button; the file is not written.
TEST(Script, ASaveTheLoaderWouldRefuseIsRefused) {
    const Scene scene = loadScene("builtin:cornell");
    const ViewState state = stateFor(scene);
    const std::string dir = tempDir("view_save_far");
    for (const std::string& move : {std::string("camera move 20000 0 0"), std::string("camera zoom 1e6")}) {
        try {
            checkScriptInContext(parseScript(move + "\nwait 1\nsave-settings " + dir + "/far.json\n", "c.txt"), state,
                                 "c.txt", &scene.bounds);
            ADD_FAILURE() << move << ": the save was accepted";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("c.txt:3: ", 0), 0u) << what;
            EXPECT_NE(what.find("far.json: camera: znear"), std::string::npos) << what;
            EXPECT_NE(what.find("not saved, the file would not load"), std::string::npos) << what;
        }
    }
    EXPECT_NO_THROW(checkScriptInContext(parseScript("camera move 2 0 0\nsave-settings " + dir + "/near.json\n", "c.txt"),
                                         state, "c.txt", &scene.bounds));
    // After a scene line, that scene's bounds: the emitter box is the same size, so the same refusal.
    EXPECT_THROW(checkScriptInContext(parseScript("scene builtin:cornell-area\ncamera move 20000 0 0\nsave-settings " +
                                                      dir + "/far.json\n",
                                                  "c.txt"),
                                      state, "c.txt", &scene.bounds),
                 Error);

    // The session (the panel's button and a running script's line).
    ViewSession session;
    ViewState s = state;
    ASSERT_TRUE(session.openScene(s, "builtin:cornell")) << session.lastError();
    applyPanelAction(s, parsePanelAction(splitWords("camera move 20000 0 0")));
    EXPECT_FALSE(session.saveSettings(s, dir + "/far.json"));
    EXPECT_NE(session.lastError().find("would not load"), std::string::npos) << session.lastError();
    EXPECT_FALSE(std::filesystem::exists(dir + "/far.json"));
    applyPanelAction(s, parsePanelAction(splitWords("camera move -19998 0 0")));
    ASSERT_TRUE(session.saveSettings(s, dir + "/near.json")) << session.lastError();
    ViewState loaded = state;
    EXPECT_TRUE(session.loadSettings(loaded, dir + "/near.json")) << session.lastError();
}

// vct.debug-level is a live parameter: chosen in the panel it reached the voxel view without the
// check the pass makes when it is built, and the albedo grid (no mips) at level 2 showed black.
// The action is refused when set, naming the channel to use, and the state is left as it was.
TEST(PanelActions, ALiveVoxelDebugLevelTheChannelLacksIsRefused) {
    ViewState s;
    applyPanelAction(s, PanelAction::method(0, "vct"));
    applyPanelAction(s, PanelAction::display(0, "vct.voxels"));
    const ViewState before = s;
    try {
        applyPanelAction(s, PanelAction::param(0, "vct.debug-level", "2"));
        ADD_FAILURE() << "level 2 of the albedo grid accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("use vct.debug-channel=radiance or occupancy"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s.panes[0].params, before.panes[0].params);
    applyPanelAction(s, PanelAction::param(0, "vct.debug-channel", "occupancy"));
    applyPanelAction(s, PanelAction::param(0, "vct.debug-level", "2"));
    EXPECT_THROW(applyPanelAction(s, PanelAction::param(0, "vct.debug-channel", "albedo")), Error)
        << "back to albedo at level 2";
}

// A host that records what the runner asks for.
struct FakeHost : ScriptHost {
    ViewState state;
    std::vector<std::string> log;
    bool isSettled = false;
    double clock = 0.0;
    void apply(const PanelAction& a) override { applyPanelAction(state, a); log.push_back("apply"); }
    void openScene(const std::string& s) override { log.push_back("scene " + s); }
    void loadSettings(const std::string& p) override { log.push_back("load " + p); }
    void saveSettings(const std::string& p) override { log.push_back("save " + p); }
    void requestScreenshot() override { log.push_back("screenshot"); }
    void requestCapture(const std::string& p) override { log.push_back("capture " + p); }
    void resize(int w, int h) override { log.push_back("resize " + std::to_string(w) + "x" + std::to_string(h)); }
    void quit() override { log.push_back("quit"); }
    void pressKey(const std::string& k) override { log.push_back("key " + k); }
    bool settled() const override { return isSettled; }
    double seconds() const override { return clock; }
};

TEST(Script, RunnerWaitsFramesSecondsAndConvergence) {
    ScriptRunner runner(parseScript("wait 2\nmode grid\nsleep 1\nconverge\nscreenshot\nquit\n", "r.txt"), "r.txt");
    FakeHost host;
    runner.frame(host);  // wait: frame 1
    runner.frame(host);  // frame 2
    EXPECT_TRUE(host.log.empty());
    runner.frame(host);  // mode grid, then the sleep starts
    EXPECT_EQ(host.state.mode, ViewMode::Grid);
    runner.frame(host);
    EXPECT_EQ(host.log.size(), 1u) << "still sleeping";
    host.clock = 1.5;
    runner.frame(host);  // sleep over; converge needs one frame, then settled
    runner.frame(host);
    EXPECT_EQ(host.log.size(), 1u) << "not settled";
    host.isSettled = true;
    runner.frame(host);
    ASSERT_EQ(host.log.size(), 2u);
    EXPECT_EQ(host.log[1], "screenshot") << "one request per frame: taken after it is drawn";
    runner.frame(host);
    EXPECT_EQ(host.log.back(), "quit");
    EXPECT_TRUE(runner.finished());
}

TEST(BrdfTable, EveryModelHasAnEntryAndTheShapesAreRight) {
    std::set<std::string> names;
    for (const DiffuseModelInfo& m : diffuseModels()) {
        EXPECT_TRUE(names.insert(std::string("d:") + m.name).second) << m.name;
        EXPECT_STREQ(diffuseModelName(m.model), m.name);
        EXPECT_EQ(parseDiffuse(m.name), m.model) << "the renderer knows the name";
        ASSERT_NE(m.evaluate, nullptr);
    }
    for (const SpecularModelInfo& m : specularModels()) {
        EXPECT_TRUE(names.insert(std::string("s:") + m.name).second) << m.name;
        EXPECT_STREQ(specularModelName(m.model), m.name);
        EXPECT_EQ(parseSpecular(m.name), m.model);
    }
    const CpuSurfaceBrdf s = makeCpuSurfaceBrdf(glm::vec3(0.5f), 0.0f, 0.2f, 1.0f);
    // Lambert alone: f cos = albedo/pi cos, zero below the horizon.
    const auto lambertOnly = brdfLobe(s, 0.5f, DiffuseModel::Lambert, SpecularModel::None, 181);
    for (const LobeSample& l : lambertOnly) {
        EXPECT_NEAR(l.diffuse.r, std::max(0.0f, std::cos(l.angle)) * 0.5f / 3.14159265f, 1e-6f);
        EXPECT_EQ(l.specular, glm::vec3(0.0f));
    }
    // GGX at low roughness peaks at the mirror direction.
    const float view = 0.6f;
    const auto ggx = brdfLobe(s, view, DiffuseModel::Lambert, SpecularModel::Ggx, 361);
    const LobeSample* peak = &ggx[0];
    for (const LobeSample& l : ggx)
        if (l.specular.r > peak->specular.r) peak = &l;
    EXPECT_NEAR(peak->angle, view, 0.05f);
    // f is symmetric in L and V.
    const glm::vec3 N(0, 0, 1), V = glm::normalize(glm::vec3(-0.3f, 0.1f, 0.9f)), L = glm::normalize(glm::vec3(0.5f, -0.2f, 0.7f));
    const glm::vec3 a = evaluateCpuBrdf(s, N, V, L, DiffuseModel::Lambert, SpecularModel::Ggx);
    const glm::vec3 b = evaluateCpuBrdf(s, N, L, V, DiffuseModel::Lambert, SpecularModel::Ggx);
    EXPECT_NEAR(a.r, b.r, 1e-5f * a.r);
    EXPECT_EQ(evaluateCpuBrdf(s, N, V, -L, DiffuseModel::Lambert, SpecularModel::Ggx), glm::vec3(0.0f));
}

// A new user's first split or grid is a comparison, and a method picked for a pane starts at the
// default preset instead of the previous method's (vct/low by accident).
TEST(FirstHour, PanesStartDistinctAndAMethodChangeResetsThePreset) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    std::set<std::string> methods;
    for (const PaneState& p : s.panes) methods.insert(p.gi);
    EXPECT_EQ(methods.size(), s.panes.size());
    EXPECT_EQ(s.panes[0].gi, "none");
    EXPECT_NE(s.panes[1].gi, s.panes[0].gi) << "split mode compares panes 0 and 1";
    applyPanelAction(s, parsePanelAction(splitWords("preset 1 low")));
    applyPanelAction(s, parsePanelAction(splitWords("method 1 ssao")));
    EXPECT_EQ(s.panes[1].preset, PaneState{}.preset);
    applyPanelAction(s, parsePanelAction(splitWords("preset 1 high")));
    applyPanelAction(s, parsePanelAction(splitWords("method 1 ssao")));
    EXPECT_EQ(s.panes[1].preset, "high") << "choosing the same method again keeps its preset";
}

// A script may pick any preset the pane's method has (vct's realtime, ssao's hemisphere ones), as
// render --preset does; one the method lacks is an error naming the method's presets.
TEST(FirstHour, AScriptPicksAMethodsOwnPresets) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    applyPanelAction(s, parsePanelAction(splitWords("method 1 vct")));
    applyPanelAction(s, parsePanelAction(splitWords("preset 1 realtime")));
    EXPECT_EQ(s.panes[1].preset, "realtime");
    EXPECT_EQ(getParam(paneSettings(s, 1, {8, 8}), "vct.trace-scale").text, "4") << "vct/realtime traces every 4x4";
    applyPanelAction(s, parsePanelAction(splitWords("method 0 ssao")));
    applyPanelAction(s, parsePanelAction(splitWords("preset 0 hemisphere-high")));
    EXPECT_EQ(s.panes[0].preset, "hemisphere-high");
    try {
        applyPanelAction(s, parsePanelAction(splitWords("preset 1 hemisphere-high")));
        ADD_FAILURE() << "vct took ssao's preset";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("realtime"), std::string::npos) << e.what();
    }
    EXPECT_EQ(s.panes[1].preset, "realtime") << "a refused action changes nothing";
}

TEST(FirstHour, SwapFlipsTheSplitsSides) {
    const Scene scene = makeBuiltinScene("cornell");
    ViewState s = stateFor(scene);
    applyPanelAction(s, parsePanelAction(splitWords("mode split")));
    applyPanelAction(s, parsePanelAction(splitWords("preset 1 low")));
    const PaneState left = s.panes[0], right = s.panes[1];
    applyPanelAction(s, parsePanelAction(splitWords("swap")));
    EXPECT_EQ(s.panes[0].gi, right.gi);
    EXPECT_EQ(s.panes[0].preset, "low");
    EXPECT_EQ(s.panes[1].gi, left.gi);
    applyPanelAction(s, parsePanelAction(splitWords("swap")));
    EXPECT_EQ(s.panes[0].gi, left.gi);
    EXPECT_THROW(parsePanelAction(splitWords("swap 1")), Error);
}

// --environment in the viewer: the script line says what render says for the same settings, and a
// settings file carries the map.
TEST(Script, EnvironmentLinesSayWhatRenderSays) {
    const Scene scene = loadScene("builtin:cornell");
    const ViewState state = stateFor(scene);
    const std::string sky = std::string(GIS_SOURCE_DIR) + "/assets/environments/sky_sun.hdr";
    const std::string missing = tempDir("view_environment") + "/missing.hdr";
    EXPECT_EQ(contextError("environment " + missing + "\n", state), cliError("--environment " + missing));
    const std::string both = cliError("--background 1 --environment " + sky);
    EXPECT_NE(both.find("give one of them"), std::string::npos) << both;
    EXPECT_EQ(contextError("background 1 1 1\nenvironment " + sky + "\n", state), both);
    EXPECT_EQ(contextError("environment " + sky + "\nbackground 1 1 1\n", state), both);
    EXPECT_EQ(contextError("environment " + sky + "\nenvironment off\nbackground 1 1 1\n", state), "");

    // The rotation: a map to turn, a finite number; `environment off` leaves none to turn.
    EXPECT_EQ(contextError("environment-rotation 90\n", state), cliError("--environment-rotation 90"));
    EXPECT_EQ(contextError("environment " + sky + "\nenvironment-rotation 400\n", state),
              cliError("--environment " + sky + " --environment-rotation 400"));
    EXPECT_EQ(contextError("environment " + sky + "\nenvironment-rotation 90\nenvironment off\n", state), "");
    EXPECT_THROW(parseScript("environment-rotation nan\n", "c.txt"), Error);

    ViewState s = state;
    applyPanelAction(s, parsePanelAction(splitWords("environment " + sky)));
    applyPanelAction(s, parsePanelAction(splitWords("environment-rotation -45")));
    EXPECT_EQ(paneSettings(s, 0, {64, 48}).environment, sky);
    EXPECT_EQ(paneSettings(s, 0, {64, 48}).environmentRotation, -45.0f);
    const std::string dir = tempDir("view_environment_roundtrip");
    saveViewSettings(dir + "/a.json", s);
    EXPECT_EQ(viewStateToJson(loadViewSettings(dir + "/a.json")).dump(), viewStateToJson(s).dump());
    EXPECT_EQ(loadViewSettings(dir + "/a.json").environmentRotation, -45.0f) << "the settings key environment_rotation";
    // render --settings renders the file's turned map as the view does.
    const CliResult r = runCli("render --settings " + dir + "/a.json --size 8x8 --out " + dir + "/a.png");
    EXPECT_EQ(r.status, 0) << r.err;
    applyPanelAction(s, parsePanelAction(splitWords("environment off")));
    EXPECT_EQ(s.environmentRotation, 0.0f);
}

}  // namespace
}  // namespace gis::test
