#include "view/view_script.h"

#include <cmath>
#include <sstream>

#include "gi/method.h"
#include "scene/user_file.h"
#include "cli/user_json.h"
#include "view/view_session.h"

namespace gis::view {

namespace {
constexpr double kConvergeTimeout = 300.0;

double parseNumber(const std::string& w) {
    if (!isPlainNumber(w)) throw Error("'" + w + "' is not a number");
    size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(w, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != w.size() || !std::isfinite(v)) throw Error("'" + w + "' is not a number");
    return v;
}

// Names and ranges are checked now, so a typo fails before any window opens; light edits depend
// on the scene's lights and are checked in context.
void checkActionAlone(const PanelAction& a) {
    const PanelAction::Kind k = a.kind;
    const bool dependsOnScene = actionEdits(k) == PanelAction::Edits::Light;
    // A parameter's value alone: whether the method takes it with the pane's other values is for
    // checkScriptInContext (vct.debug-level 2 after vct.debug-channel occupancy).
    if (k == PanelAction::SetParam) parsePaneParam(a);
    // A rotation's map may come from an earlier line or the settings: its number alone, here.
    if (k == PanelAction::SetEnvironmentRotation) return checkEnvironmentRotationValue(a.value);
    ViewState scratch;
    if (!dependsOnScene && k != PanelAction::SetParam) applyPanelAction(scratch, a);
}

// A line's step (its words; the line number is the caller's). Throws gis::Error naming the problem.
ScriptStep parseStep(const std::vector<std::string>& w) {
    ScriptStep s;
    auto need = [&](size_t n, const char* usage) {
        if (w.size() != n) throw Error(std::string("usage: ") + usage);
    };
    const std::string& cmd = w[0];
    if (cmd == "wait") {
        need(2, "wait FRAMES");
        const double n = parseNumber(w[1]);
        if (n < 0 || n > 1e7 || n != std::floor(n)) throw Error("wait takes a whole number of frames");
        s.kind = ScriptStep::Wait;
        s.frames = int(n);
    } else if (cmd == "sleep") {
        need(2, "sleep SECONDS");
        s.kind = ScriptStep::Sleep;
        s.seconds = parseNumber(w[1]);
        if (s.seconds < 0 || s.seconds > 3600) throw Error("sleep takes 0 to 3600 seconds");
    } else if (cmd == "converge") {
        need(1, "converge");
        s.kind = ScriptStep::Converge;
    } else if (cmd == "screenshot") {
        need(1, "screenshot");
        s.kind = ScriptStep::Screenshot;
    } else if (cmd == "capture") {
        need(2, "capture PATH.png");
        // The window is written as PNG whatever the name says: any other name is a mistake.
        const std::string& p = w[1];
        if (p.size() < 4 || (p.compare(p.size() - 4, 4, ".png") != 0 && p.compare(p.size() - 4, 4, ".PNG") != 0))
            throw Error("capture writes a PNG: '" + p + "' does not end in .png");
        s.kind = ScriptStep::Capture;
        s.path = p;
    } else if (cmd == "scene") {
        need(2, "scene PATH|builtin:NAME");
        s.kind = ScriptStep::OpenScene;
        s.path = w[1];
    } else if (cmd == "settings") {
        need(2, "settings FILE");
        s.kind = ScriptStep::LoadSettings;
        s.path = w[1];
    } else if (cmd == "save-settings") {
        need(2, "save-settings FILE");
        s.kind = ScriptStep::SaveSettings;
        s.path = w[1];
    } else if (cmd == "resize") {
        need(3, "resize WIDTH HEIGHT");
        const double a = parseNumber(w[1]), b = parseNumber(w[2]);
        if (a < 0 || b < 0 || a > 16384 || b > 16384 || a != std::floor(a) || b != std::floor(b))
            throw Error("resize takes whole numbers in [0, 16384]");
        s.kind = ScriptStep::Resize;
        s.width = int(a);
        s.height = int(b);
    } else if (cmd == "key") {
        need(2, "key NAME");
        s.kind = ScriptStep::Key;
        s.path = w[1];
    } else if (cmd == "quit") {
        need(1, "quit");
        s.kind = ScriptStep::Quit;
    } else {
        s.kind = ScriptStep::Action;
        s.action = parsePanelAction(w);
        checkActionAlone(s.action);
    }
    return s;
}

}  // namespace

std::vector<ScriptStep> parseScript(const std::string& text, const std::string& name) {
    std::vector<ScriptStep> steps;
    // A UTF-8 byte order mark, as an editor may write it (settings files accept one too).
    std::istringstream in(text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text);
    int lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        const std::vector<std::string> w = splitWords(line);
        if (w.empty()) continue;
        try {
            steps.push_back(parseStep(w));
        } catch (const Error& e) {
            throw Error(name + ":" + std::to_string(lineNo) + ": " + e.what());
        }
        steps.back().line = lineNo;
    }
    return steps;
}

std::vector<ScriptStep> loadScript(const std::string& path) {
    return parseScript(readUserFile(path, kMaxUserTextBytes, "script"), path);
}

namespace {
// What an action needs of the state it is applied to, beyond applyPanelAction's own checks.
void checkActionInContext(const ViewState& s, const PanelAction& a) {
    if (actionEdits(a.kind) != PanelAction::Edits::Pane) return;
    const int shown = paneCount(s.mode);
    if (a.index >= shown && a.index < kMaxPanes)
        throw Error("pane " + std::to_string(a.index) + " is not shown in " + viewModeName(s.mode) + " mode (panes 0.." +
                    std::to_string(shown - 1) + "): switch the mode first (mode " +
                    (a.index < paneCount(ViewMode::Split) ? "split" : "grid") + ")");
    if (a.kind != PanelAction::SetParam) return;
    std::string method;
    findParam(a.text, &method);  // applyPanelAction names an unknown key
    const std::string& gi = s.panes[a.index].gi;
    if (method != gi && !isGroupParam(a.text))
        throw Error(a.text + " is a parameter of another method than pane " + std::to_string(a.index) + "'s " + gi +
                    ": it would do nothing (method " + std::to_string(a.index) + " " + method + " first)");
}

// The keys that change what the panes are (docs/viewer.md): the rest move the camera or take a
// screenshot, which no later line depends on.
void applyKeyInContext(ViewState& s, const std::string& key) {
    if (key == "1") applyPanelAction(s, PanelAction::viewMode(ViewMode::Single));
    else if (key == "2") applyPanelAction(s, PanelAction::viewMode(ViewMode::Split));
    else if (key == "3") applyPanelAction(s, PanelAction::viewMode(ViewMode::Grid));
    else if (key == "B") {
        PanelAction swap;
        swap.kind = PanelAction::SwapSides;
        applyPanelAction(s, swap);
    }
}
}  // namespace

void checkScriptInContext(const std::vector<ScriptStep>& steps, ViewState state, const std::string& name,
                          const Aabb* bounds) {
    // A session of its own opens the script's scenes and settings files into the copy, as the run
    // will (CPU only: a session makes no GL object before its first frame), so the lines after
    // them are checked against the state they will find.
    ViewSession scratch;
    for (const ScriptStep& step : steps) {
        try {
            // A scene that does not open is the run's warning, the state unchanged; a settings file
            // that does not load stops the run, so it is refused here.
            if (step.kind == ScriptStep::OpenScene) scratch.openScene(state, step.path);
            if (step.kind == ScriptStep::LoadSettings && !scratch.loadSettings(state, step.path))
                throw Error(scratch.lastError());
            if (step.kind == ScriptStep::Key) applyKeyInContext(state, step.path);
            if (step.kind == ScriptStep::SaveSettings || step.kind == ScriptStep::Capture)
                checkNotAnOpenFile(state, step.path, name);
            if (step.kind == ScriptStep::SaveSettings && (scratch.hasScene() || bounds))
                checkSavedCamera(state, scratch.hasScene() ? scratch.scene().bounds : *bounds, step.path);
            if (step.kind != ScriptStep::Action) continue;
            checkActionInContext(state, step.action);
            applyPanelAction(state, step.action);
            if (step.action.kind == PanelAction::SetDisplay || step.action.kind == PanelAction::SetMethod)
                checkPaneDisplay(state, step.action.index);
        } catch (const Error& e) {
            throw Error(name + ":" + std::to_string(step.line) + ": " + e.what());
        }
    }
}

void ScriptRunner::frame(ScriptHost& host) {
    while (next_ < steps_.size()) {
        const ScriptStep& s = steps_[next_];
        try {
            switch (s.kind) {
                case ScriptStep::Wait:
                    if (framesLeft_ < 0) framesLeft_ = s.frames;
                    if (framesLeft_-- > 0) return;
                    framesLeft_ = -1;
                    break;
                case ScriptStep::Sleep:
                    if (until_ < 0) until_ = host.seconds() + s.seconds;
                    if (host.seconds() < until_) return;
                    until_ = -1.0;
                    break;
                case ScriptStep::Converge:
                    if (until_ < 0) {
                        until_ = host.seconds() + kConvergeTimeout;
                        return;  // at least one frame with the current state
                    }
                    if (!host.settled()) {
                        if (host.seconds() > until_) throw Error("did not converge within 300 s");
                        return;
                    }
                    until_ = -1.0;
                    break;
                case ScriptStep::Action: host.apply(s.action); break;
                case ScriptStep::OpenScene: host.openScene(s.path); break;
                case ScriptStep::LoadSettings: host.loadSettings(s.path); break;
                case ScriptStep::SaveSettings: host.saveSettings(s.path); break;
                case ScriptStep::Screenshot:
                    host.requestScreenshot();
                    ++next_;
                    return;  // taken once this frame is drawn
                case ScriptStep::Capture:
                    host.requestCapture(s.path);
                    ++next_;
                    return;
                case ScriptStep::Resize:
                    host.resize(s.width, s.height);
                    ++next_;
                    return;
                case ScriptStep::Key: host.pressKey(s.path); break;
                case ScriptStep::Quit:
                    host.quit();
                    ++next_;
                    return;
            }
        } catch (const Error& e) {
            throw Error(name_ + ":" + std::to_string(s.line) + ": " + e.what());
        }
        ++next_;
    }
}

}  // namespace gis::view
