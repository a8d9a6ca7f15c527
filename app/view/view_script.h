// `gisandbox view --script FILE`: timed actions that drive the window like a user would, for
// end-to-end tests and reproducible demos. One action per line, '#' starts a comment:
//
//   wait N              let N frames pass          sleep S      let S seconds pass
//   converge            wait until every pane has converged (path tracer, heatmaps); 300 s at most
//   screenshot          as the button / F12       capture PATH  the whole window (panel too) as PNG
//   scene SPEC          open a scene (glTF path or builtin:NAME); a failure is shown, not fatal
//   settings FILE       load a settings file      save-settings FILE
//   resize W H          resize the window         quit
//   key NAME            tap a key (F12 F R 1 2 3 B I W A S D Q E): down and up before the frame reads
//                       its input, as a press shorter than a frame
//   anything else       a panel action (panel_action.h parsePanelAction), e.g. "method 1 pathtrace"
#pragma once

#include <string>
#include <vector>

#include "cli/panel_action.h"

namespace gis::view {

struct ScriptStep {
    enum Kind { Action, Wait, Sleep, Converge, OpenScene, LoadSettings, SaveSettings, Screenshot, Capture, Resize, Quit, Key };
    Kind kind = Action;
    int line = 0;
    PanelAction action;
    int frames = 0;
    double seconds = 0.0;
    std::string path;                 // or the key's name
    int width = 0, height = 0;
};

// Throws gis::Error "NAME:LINE: message" on the first bad line.
std::vector<ScriptStep> parseScript(const std::string& text, const std::string& name);
std::vector<ScriptStep> loadScript(const std::string& path);

// Runs the script's actions on a copy of `state` (the view as it opens: its scene's lights, the
// settings file's panes), with no GL and no window, so a line that is wrong only in context fails
// before any window opens: an edit of a pane the view mode does not show, a display the pane's
// method cannot produce, a parameter of another method than the pane's, a light past what the
// shadow maps hold. Keys 1 2 3 and B are followed (they change the mode and swap the sides).
// After a `scene` or `settings` line the state is the file's, unknown here: the lines after it
// are checked one at a time, as parseScript does. Throws gis::Error "NAME:LINE: message".
// With `bounds` (the view's scene; a `scene` or `settings` line's own after it), a save-settings
// line whose camera the loader would refuse is refused too (checkSavedCamera).
void checkScriptInContext(const std::vector<ScriptStep>& steps, ViewState state, const std::string& name,
                          const Aabb* bounds = nullptr);

// What a script needs from the app that runs it.
class ScriptHost {
public:
    virtual ~ScriptHost() = default;
    virtual void apply(const PanelAction& action) = 0;
    virtual void openScene(const std::string& spec) = 0;
    virtual void loadSettings(const std::string& path) = 0;   // throws gis::Error
    virtual void saveSettings(const std::string& path) = 0;   // throws gis::Error
    virtual void requestScreenshot() = 0;                     // after this frame is drawn
    virtual void requestCapture(const std::string& path) = 0; // after this frame is drawn
    virtual void resize(int width, int height) = 0;
    virtual void quit() = 0;
    virtual void pressKey(const std::string& name) = 0;      // throws gis::Error for an unknown key
    virtual bool settled() const = 0;
    virtual double seconds() const = 0;                       // a monotonic clock
};

class ScriptRunner {
public:
    ScriptRunner() = default;
    ScriptRunner(std::vector<ScriptStep> steps, std::string name) : steps_(std::move(steps)), name_(std::move(name)) {}
    // Once per frame, before it is rendered: runs steps until one has to wait for later frames.
    // Throws gis::Error "NAME:LINE: message" when a step fails.
    void frame(ScriptHost& host);
    bool finished() const { return next_ >= steps_.size(); }
    bool active() const { return !steps_.empty(); }

private:
    std::vector<ScriptStep> steps_;
    std::string name_;
    size_t next_ = 0;
    int framesLeft_ = -1;      // of the current wait
    double until_ = -1.0;      // end of the current sleep / converge deadline
};

}  // namespace gis::view
