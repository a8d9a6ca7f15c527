// The ImGui side of `gisandbox view`: the panel docked at the window's right side and the labels
// drawn over the 3D view. Widgets only read the ViewState and call applyPanelAction (or the
// session's open/load/save), so everything they do is what the tests exercise headless.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "view/view_session.h"
#include "cli/panel_action.h"

namespace gis::view {

// The app's frame, smoothed alike: wall ms from the end of the event wait to the swap, and the GPU
// ms of the pass timings that arrived during it (ViewSession::gpuMsCollected); the difference is
// the CPU's own work (panel, uploads) and its waits for the GPU and the swap.
struct FrameTimes {
    float frameMs = 0.0f, gpuMs = 0.0f;
};

struct PanelContext {
    ViewState& state;
    ViewSession& session;
    std::string& message;          // the last status or error line, shown at the top
    std::string& scenePath;        // text fields
    std::string& settingsPath;
    std::string& environmentPath;  // the environment map field (applied by its Load button)
    std::string glRenderer;
    FrameTimes times;
    bool screenshotRequested = false;  // set by the button
    // Each section header's top (window y) as drawPanel last drew them, in order: the layout the
    // panel test checks against the window's height.
    std::vector<std::pair<std::string, float>> sectionTops;
};

// Applies an action, turning a gis::Error into the panel's message.
void act(PanelContext& ctx, const PanelAction& action);

// The panel at (x, y, width, height) in ImGui (window) coordinates.
void drawPanel(PanelContext& ctx, float x, float y, float width, float height);

// The pixel inspector's tooltip at the cursor (mx, my in the 3D view of w x h, window
// coordinates): each pane's radiance there, the reference's and the error.
void drawPixelInspector(const ViewState& state, const ViewSession& session, float mx, float my, float w, float h);

// Pane labels, progress and metric, and the split divider, over the 3D view at (x, y, w, h).
void drawViewOverlay(const ViewState& state, const ViewSession& session, float x, float y, float w, float h);

}  // namespace gis::view
