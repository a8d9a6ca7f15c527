// The panel laid out headless (Dear ImGui without a backend: its font atlas built, no drawing): in
// every view mode, at the window the viewer opens by default, the timings are on screen (#42 item
// 11: in split and grid modes the pane sections pushed "Timings and memory" below the window), and
// no row runs past the panel's right edge with any method's parameters open.
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <memory>

#include "cli/panel_action.h"
#include "view/panel.h"
#include "view_test_util.h"

namespace gis::view {
namespace {

using test::viewContext;

// Lays the panel out twice (the second frame with the first's sizes) at the viewer's default
// window (1280x720) and panel (420 pixels at the right).
constexpr float kPanelX = 860.0f, kPanelWidth = 420.0f, kHeight = 720.0f;
void layOut(PanelContext& ctx) {
    for (int frame = 0; frame < 2; ++frame) {
        ImGui::NewFrame();
        drawPanel(ctx, kPanelX, 0.0f, kPanelWidth, kHeight);
        ImGui::Render();
    }
}

// Opens the parameter tables' tree nodes of the first pane as a click would (their state lives in
// the panel window's storage, under the pane's ID).
void openParameterTables(const PaneState& pane) {
    ImGui::NewFrame();
    ImGui::Begin("gisandbox");
    ImGui::PushID(0);
    for (const ParamTableView& table : paneParamTables(pane))
        ImGui::GetStateStorage()->SetInt(ImGui::GetID(table.name.c_str()), 1);
    ImGui::PopID();
    ImGui::End();
    ImGui::Render();
}

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

// The viewer's state and session on the Cornell box, and a panel drawing them headless.
class Panel : public ::testing::Test {
protected:
    void SetUp() override {
        viewContext();
        ASSERT_TRUE(session.openScene(state, "builtin:cornell")) << session.lastError();
    }
    ViewState state;
    ViewSession session;
    std::string message, scenePath = "builtin:cornell", settingsPath, environmentPath;
    PanelContext ctx{state, session, message, scenePath, settingsPath, environmentPath, "llvmpipe", {}, false, {}};
    ImGuiFrames imgui;
};

TEST_F(Panel, TheTimingsAreOnScreenInEveryMode) {
    for (const char* mode : {"single", "split", "grid"}) {
        applyPanelAction(state, parsePanelAction({"mode", mode}));
        session.renderFrame(state, 64, 48);  // the panes' status lines and timings exist
        layOut(ctx);
        float timings = -1.0f;
        for (const auto& [title, top] : ctx.sectionTops)
            if (title == "Timings and memory") timings = top;
        ASSERT_GE(timings, 0.0f) << mode;
        EXPECT_LT(timings + ImGui::GetFrameHeight(), kHeight) << mode << ": the timings header is below the window";
    }
}

// Every method's parameter tables open in the single pane (the tree nodes opened as a click would):
// the widest label decides the label column. With a fixed column of 130 pixels the rows ran 7
// (ao-reference) to 77 (vct) pixels past the edge, their text cut.
TEST_F(Panel, NoRowRunsPastThePanelsEdge) {
    for (const GiMethod& m : giMethods()) {
        applyPanelAction(state, PanelAction::method(0, m.name));
        layOut(ctx);
        const ImGuiWindow* panel = ImGui::FindWindowByName("gisandbox");
        ASSERT_NE(panel, nullptr);
        const float closedBottom = panel->DC.CursorMaxPos.y;
        openParameterTables(state.panes[0]);
        layOut(ctx);
        // The tables' rows were laid out: the tree nodes' IDs above are the panel's.
        ASSERT_GT(panel->DC.CursorMaxPos.y, closedBottom) << m.name << ": its parameter tables did not open";
        EXPECT_LE(panel->DC.CursorMaxPos.x, panel->WorkRect.Max.x + 0.5f)
            << m.name << ": a row reaches " << panel->DC.CursorMaxPos.x - panel->WorkRect.Max.x << " pixels past the panel";
    }
}

}  // namespace
}  // namespace gis::view
