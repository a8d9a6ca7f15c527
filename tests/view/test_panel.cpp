// The panel laid out headless (Dear ImGui without a backend: its font atlas built, no drawing): in
// every view mode, at the window the viewer opens by default, the timings are on screen (#42 item
// 11: in split and grid modes the pane sections pushed "Timings and memory" below the window).
#include <gtest/gtest.h>
#include <imgui.h>

#include <memory>

#include "cli/panel_action.h"
#include "view/panel.h"
#include "view_test_util.h"

namespace gis::view {
namespace {

using test::viewContext;

struct ImGuiFrames {
    ImGuiFrames() {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(1280.0f, 720.0f);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the atlas NewFrame asks for
    }
    ~ImGuiFrames() { ImGui::DestroyContext(); }
};

TEST(Panel, TheTimingsAreOnScreenInEveryMode) {
    viewContext();
    ViewState state;
    ViewSession session;
    ASSERT_TRUE(session.openScene(state, "builtin:cornell")) << session.lastError();
    std::string message, scenePath = "builtin:cornell", settingsPath, environmentPath;
    PanelContext ctx{state, session, message, scenePath, settingsPath, environmentPath, "llvmpipe", {}, false, {}};
    ImGuiFrames imgui;
    // The viewer's default window (1280x720) and panel (420 pixels at the right).
    const float panelX = 860.0f, panelW = 420.0f, height = 720.0f;
    for (const char* mode : {"single", "split", "grid"}) {
        applyPanelAction(state, parsePanelAction({"mode", mode}));
        session.renderFrame(state, 64, 48);  // the panes' status lines and timings exist
        for (int frame = 0; frame < 2; ++frame) {  // the second frame lays out with the first's sizes
            ImGui::NewFrame();
            drawPanel(ctx, panelX, 0.0f, panelW, height);
            ImGui::Render();
        }
        float timings = -1.0f;
        for (const auto& [title, top] : ctx.sectionTops)
            if (title == "Timings and memory") timings = top;
        ASSERT_GE(timings, 0.0f) << mode;
        EXPECT_LT(timings + ImGui::GetFrameHeight(), height) << mode << ": the timings header is below the window";
    }
}

}  // namespace
}  // namespace gis::view
