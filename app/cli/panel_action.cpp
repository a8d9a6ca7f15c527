#include "cli/panel_action.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brdf_cpu.h"
#include "environment.h"
#include "lights.h"
#include "gi/method.h"
#include "passes/lighting_pass.h"

namespace gis::view {

namespace {

// --- Checks the appliers share.

// The lighting's term views ("direct", "emission" ...) are pane views too; "ao" is a pane display.
bool isTermView(const std::string& name) {
    const std::vector<std::string> terms = LightingPass::termViewNames();
    return name != "ao" && std::find(terms.begin(), terms.end(), name) != terms.end();
}

float radians(float degrees) { return degrees * 0.017453292519943295f; }

void checkFinite(const char* what, float v) {
    if (!std::isfinite(v) || std::abs(double(v)) > kMaxSettingMagnitude)
        throw Error(std::string(what) + " must be a finite number of magnitude <= 1e18");
}

void checkFinite(const char* what, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) checkFinite(what, v[i]);
}

void checkNonNegative(const char* what, glm::vec3 v) {
    if (glm::any(glm::lessThan(v, glm::vec3(0.0f)))) throw Error(std::string(what) + " must be non-negative");
}

DiffuseModel diffuseByName(const std::string& name) {
    std::string known;
    for (const DiffuseModelInfo& m : diffuseModels()) {
        if (name == m.name) return m.model;
        known += std::string(known.empty() ? "" : ", ") + m.name;
    }
    throw Error("unknown diffuse BRDF '" + name + "' (expected " + known + ")");
}

SpecularModel specularByName(const std::string& name) {
    std::string known;
    for (const SpecularModelInfo& m : specularModels()) {
        if (name == m.name) return m.model;
        known += std::string(known.empty() ? "" : ", ") + m.name;
    }
    throw Error("unknown specular BRDF '" + name + "' (expected " + known + ")");
}

// The light `a.index` names, made the edited list's (from the first edit on the renderers use it).
LightState& editedLight(ViewState& s, const PanelAction& a) {
    if (a.index < 0 || a.index >= int(s.lights.size()))
        throw Error("light " + std::to_string(a.index) + " does not exist (the list has " +
                    std::to_string(s.lights.size()) + ")");
    s.lightsEdited = true;
    return s.lights[a.index];
}

PaneState& pane(ViewState& s, const PanelAction& a) {
    checkPane(a.index);
    return s.panes[a.index];
}

glm::vec3 orbitTarget(const ViewCamera& c) { return c.position + cameraForward(c) * c.distance; }

// The camera's right and up vectors (the world's up keeps the horizon level).
glm::mat2x3 cameraRightUp(const ViewCamera& c) {
    const glm::vec3 right = glm::normalize(glm::cross(cameraForward(c), glm::vec3(0.0f, 1.0f, 0.0f)));
    return {right, glm::cross(right, cameraForward(c))};
}

void turnCamera(ViewCamera& c, glm::vec3 yawPitch) {
    c.yaw = std::remainder(c.yaw + yawPitch.x, 6.283185307179586f);
    c.pitch = std::clamp(c.pitch + yawPitch.y, -kMaxPitch, kMaxPitch);
}

void checkReferenceParam(const char* key, float value) {  // the path tracer's row gives the range
    checkParamValue(methodInRole(MethodRole::Reference).name, findParam(roleParamKey(MethodRole::Reference, key)),
                    ParamValue{value});
}

// --- Appliers: one per action, on a copy of the state (applyPanelAction keeps it or not).

void applyMethod(ViewState& s, const PanelAction& a) {
    PaneState& p = pane(s, a);
    giMethod(a.text);  // throws for an unknown one
    // A new method starts at the default preset: the old method's one was chosen for it.
    if (p.gi != a.text) p.preset = PaneState{}.preset;
    p.gi = a.text;
    if (p.display == PaneDisplay::Method) p.display = PaneDisplay::Lit;
}

void applyParam(ViewState& s, const PanelAction& a) {
    s.panes[a.index].params[a.text] = parsePaneParam(a);
    checkParams(paneSettings(s, a.index, {1, 1}).params);  // what the ranges cannot say, as render does
}

void applyResetParams(ViewState& s, const PanelAction& a) { pane(s, a).params.clear(); }

void applyPreset(ViewState& s, const PanelAction& a) {
    PaneState& p = pane(s, a);
    giMethod(p.gi).preset(a.text);  // the pane's method's own presets (vct's realtime); throws naming them
    p.preset = a.text;
}

void applyDiffuse(ViewState& s, const PanelAction& a) { pane(s, a).diffuse = diffuseByName(a.text); }
void applySpecular(ViewState& s, const PanelAction& a) { pane(s, a).specular = specularByName(a.text); }

void applyDisplay(ViewState& s, const PanelAction& a) {
    PaneState& p = pane(s, a);
    // A method's views have a dot ("vct.slice"; the renderer says whether it exists), the
    // lighting's term views are named by the lighting pass ("direct", "emission").
    if ((a.text.find('.') != std::string::npos && a.text.rfind("gbuffer.", 0) != 0) || isTermView(a.text)) {
        p.display = PaneDisplay::Method;  // the renderer says whether it exists
        p.methodView = a.text;
    } else {
        p.display = parsePaneDisplay(a.text);
    }
}

void applyDirectOnly(ViewState& s, const PanelAction& a) { pane(s, a).directOnly = a.flag; }
void applyMode(ViewState& s, const PanelAction& a) { s.mode = parseViewMode(a.text); }
void applySwapSides(ViewState& s, const PanelAction&) { std::swap(s.panes[0], s.panes[1]); }

void applyDivider(ViewState& s, const PanelAction& a) {
    checkFinite("divider", a.value);
    s.divider = std::clamp(a.value, 0.02f, 0.98f);
}

void applyExposure(ViewState& s, const PanelAction& a) {
    checkFinite("exposure", a.value);
    if (std::abs(a.value) > 64.0f) throw Error("exposure must be in [-64, 64] EV");
    s.exposureEV = a.value;
}

void applyTonemap(ViewState& s, const PanelAction& a) { s.tonemap = parseTonemapper(a.text); }

void applyAmbient(ViewState& s, const PanelAction& a) {
    checkFinite("ambient", a.vec);
    checkNonNegative("ambient radiance", a.vec);
    s.ambient = a.vec;
}

void applyShadows(ViewState& s, const PanelAction& a) { s.shadows = a.flag; }

void applyBackground(ViewState& s, const PanelAction& a) {
    if (!a.flag) {
        s.background.reset();
        return;
    }
    checkFinite("background", a.vec);
    checkNonNegative("background radiance", a.vec);
    checkEnvironmentChoice(true, s.environment);
    s.background = a.vec;
}

void applyEnvironment(ViewState& s, const PanelAction& a) {
    if (!a.text.empty()) {
        checkEnvironmentChoice(s.background.has_value(), a.text);
        loadEnvironmentMap(a.text);  // the render's own check, now: a bad file is this line's error
    }
    s.environment = a.text;
    if (a.text.empty()) s.environmentRotation = 0.0f;  // no map to turn (checkEnvironmentRotation)
}

void applyEnvironmentRotation(ViewState& s, const PanelAction& a) {
    checkEnvironmentRotation(a.value, s.environment);
    s.environmentRotation = a.value;
}

void applyMaxBounces(ViewState& s, const PanelAction& a) {
    checkReferenceParam("bounces", a.value);
    s.maxBounces = int(a.value);
}

void applyRenderScale(ViewState& s, const PanelAction& a) {
    checkFinite("render scale", a.value);
    if (a.value < 0.125f || a.value > 1.0f) throw Error("render scale must be in [0.125, 1]");
    s.renderScale = a.value;
}

void applyFrameBudget(ViewState& s, const PanelAction& a) {
    checkFinite("frame budget", a.value);
    if (a.value < 0.0f || a.value > 60000.0f) throw Error("frame budget must be in [0, 60000] ms (0: the renderer's default)");
    s.frameBudgetMs = a.value;
}

void applyHeatmapMetric(ViewState& s, const PanelAction& a) { s.heatmapMetric = parseErrorMetric(a.text); }

void applyReferenceSpp(ViewState& s, const PanelAction& a) {
    checkReferenceParam("spp", a.value);
    s.referenceSpp = int(a.value);
}

void applyCameraMode(ViewState& s, const PanelAction& a) {
    if (a.text == "orbit") s.camera.mode = CameraMode::Orbit;
    else if (a.text == "fly") s.camera.mode = CameraMode::Fly;
    else throw Error("unknown camera mode '" + a.text + "' (expected orbit or fly)");
}

void applyOrbit(ViewState& s, const PanelAction& a) {
    ViewCamera& cam = s.camera;
    checkFinite("camera orbit", a.vec);
    const glm::vec3 target = orbitTarget(cam);
    turnCamera(cam, a.vec);
    cam.position = target - cameraForward(cam) * cam.distance;
    cam.free = true;
}

void applyPan(ViewState& s, const PanelAction& a) {
    ViewCamera& cam = s.camera;
    checkFinite("camera pan", a.vec);
    const glm::mat2x3 rightUp = cameraRightUp(cam);
    cam.position += (rightUp[0] * a.vec.x + rightUp[1] * a.vec.y) * cam.distance;
    cam.free = true;
}

void applyZoom(ViewState& s, const PanelAction& a) {
    ViewCamera& cam = s.camera;
    checkFinite("camera zoom", a.value);
    if (a.value <= 0.0f) throw Error("camera zoom factor must be positive");
    const glm::vec3 target = orbitTarget(cam);
    cam.distance = std::clamp(cam.distance * a.value, 1e-4f, 1e7f);
    cam.position = target - cameraForward(cam) * cam.distance;
    cam.free = true;
}

void applyMove(ViewState& s, const PanelAction& a) {
    ViewCamera& cam = s.camera;
    checkFinite("camera move", a.vec);
    const glm::mat2x3 rightUp = cameraRightUp(cam);
    const glm::vec3 moved = cam.position + rightUp[0] * a.vec.x + rightUp[1] * a.vec.y + cameraForward(cam) * a.vec.z;
    checkFinite("camera position after the move", moved);  // else saved as null
    cam.position = moved;
    cam.free = true;
}

void applyLook(ViewState& s, const PanelAction& a) {
    checkFinite("camera look", a.vec);
    turnCamera(s.camera, a.vec);
    s.camera.free = true;
}

void applyResetCamera(ViewState& s, const PanelAction&) {
    const CameraMode mode = s.camera.mode;
    s.camera = s.homeCamera;
    s.camera.mode = mode;
}

void applyLightEnabled(ViewState& s, const PanelAction& a) { editedLight(s, a).enabled = a.flag; }

void applyLightIntensity(ViewState& s, const PanelAction& a) {
    LightState& l = editedLight(s, a);
    checkFinite("light intensity", a.value);
    if (a.value < 0.0f) throw Error("light intensity must be non-negative");
    l.light.intensity = a.value;
}

void applyLightColor(ViewState& s, const PanelAction& a) {
    LightState& l = editedLight(s, a);
    checkFinite("light colour", a.vec);
    checkNonNegative("light colour", a.vec);
    l.light.color = a.vec;
}

void applyLightPosition(ViewState& s, const PanelAction& a) {
    LightState& l = editedLight(s, a);
    checkFinite("light position", a.vec);
    l.light.position = a.vec;
}

void applyLightDirection(ViewState& s, const PanelAction& a) {
    LightState& l = editedLight(s, a);
    checkFinite("light direction", a.vec);
    const float len = glm::length(a.vec);
    if (!(len > 1e-6f)) throw Error("light direction must not be zero");
    l.light.direction = a.vec / len;
}

void applyAddLight(ViewState& s, const PanelAction& a) {
    Light l;
    if (a.text == "point") l.type = LightType::Point;
    else if (a.text == "spot") l.type = LightType::Spot;
    else if (a.text == "directional") l.type = LightType::Directional;
    else throw Error("unknown light type '" + a.text + "' (expected point, spot or directional)");
    l.name = "added " + a.text;
    l.position = orbitTarget(s.camera);  // where the camera looks: visible right away
    l.direction = cameraForward(s.camera);
    s.lightsEdited = true;
    s.lights.push_back({l, true});
}

void applyRemoveLight(ViewState& s, const PanelAction& a) {
    editedLight(s, a);
    s.lights.erase(s.lights.begin() + a.index);
}

void applyResetLights(ViewState& s, const PanelAction&) {
    s.lights.clear();
    for (const Light& l : s.sceneLights) s.lights.push_back({l, true});
    s.lightsEdited = false;
}

void applyPlotPane(ViewState& s, const PanelAction& a) {
    checkPane(a.index);
    s.plotPane = a.index;
}

void applyPlotMaterial(ViewState& s, const PanelAction& a) {
    checkFinite("plot base colour", a.vec);
    for (int i = 0; i < 4; ++i) checkFinite("plot material", a.vec4[i]);
    s.plotBaseColor = glm::clamp(a.vec, glm::vec3(0.0f), glm::vec3(1.0f));
    s.plotMetallic = std::clamp(a.vec4.x, 0.0f, 1.0f);
    s.plotRoughness = std::clamp(a.vec4.y, 0.0f, 1.0f);
    s.plotSpecular = std::clamp(a.vec4.z, 0.0f, 1.0f);
}

void applyPlotViewAngle(ViewState& s, const PanelAction& a) {
    checkFinite("plot view angle", a.value);
    s.plotViewAngle = std::clamp(a.value, 0.0f, radians(89.0f));
}

void applyPlotLog(ViewState& s, const PanelAction& a) { s.plotLog = a.flag; }

// --- Words to numbers.

float number(const std::string& w) {
    if (!isPlainNumber(w)) throw Error("'" + w + "' is not a number");
    size_t used = 0;
    float v = 0.0f;
    try {
        v = std::stof(w, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != w.size() || !std::isfinite(v)) throw Error("'" + w + "' is not a number");
    return v;
}

int integer(const std::string& w) {
    const float v = number(w);
    if (v != std::floor(v) || std::abs(v) > 1e9f) throw Error("'" + w + "' is not a whole number");
    return int(v);
}

bool onOff(const std::string& w) {
    if (w == "on" || w == "true" || w == "1") return true;
    if (w == "off" || w == "false" || w == "0") return false;
    throw Error("'" + w + "' is not on or off");
}

// --- Readers: a line's arguments, after the words that name its action.

struct ActionLine {
    const std::vector<std::string>& words;
    size_t first;        // the first argument's word
    const char* usage;

    size_t args() const { return words.size() - first; }
    void need(size_t n) const {
        if (args() != n) throw Error(std::string("usage: ") + usage);
    }
    const std::string& arg(size_t i) const { return words[first + i]; }
    float num(size_t i) const { return number(arg(i)); }
    glm::vec3 vec3(size_t i) const { return {num(i), num(i + 1), num(i + 2)}; }
};

void readNothing(const ActionLine& l, PanelAction&) { l.need(0); }

void readText(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.text = l.arg(0);
}

void readIndex(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.index = integer(l.arg(0));
}

void readPaneText(const ActionLine& l, PanelAction& a) {
    l.need(2);
    a.index = integer(l.arg(0));
    a.text = l.arg(1);
}

void readPaneFlag(const ActionLine& l, PanelAction& a) {
    l.need(2);
    a.index = integer(l.arg(0));
    a.flag = onOff(l.arg(1));
}

void readParam(const ActionLine& l, PanelAction& a) {
    l.need(3);
    a = PanelAction::param(integer(l.arg(0)), l.arg(1), l.arg(2));
}

void readFlag(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.flag = onOff(l.arg(0));
}

void readNumber(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.value = l.num(0);
}

void readDegrees(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.value = radians(l.num(0));
}

void readPair(const ActionLine& l, PanelAction& a) {
    l.need(2);
    a.vec = glm::vec3(l.num(0), l.num(1), 0.0f);
}

void readTurn(const ActionLine& l, PanelAction& a) {  // degrees in, radians kept
    l.need(2);
    a.vec = glm::vec3(radians(l.num(0)), radians(l.num(1)), 0.0f);
}

void readVec3(const ActionLine& l, PanelAction& a) {
    l.need(3);
    a.vec = l.vec3(0);
}

void readAmbient(const ActionLine& l, PanelAction& a) {
    if (l.args() != 1 && l.args() != 3) throw Error(std::string("usage: ") + l.usage);
    a.vec = l.args() == 1 ? glm::vec3(l.num(0)) : l.vec3(0);
}

void readBackground(const ActionLine& l, PanelAction& a) {
    if (l.args() == 1 && l.arg(0) == "off") return;
    l.need(3);
    a.flag = true;
    a.vec = l.vec3(0);
}

void readEnvironment(const ActionLine& l, PanelAction& a) {
    l.need(1);
    a.text = l.arg(0) == "off" ? "" : l.arg(0);
}

// "light I on|off": the index and the switch are the words that name the action.
void readLightSwitch(const ActionLine& l, PanelAction& a) {
    a.index = integer(l.words[1]);
    l.need(0);
    a.flag = l.words[2] == "on";
}

void readLightNumber(const ActionLine& l, PanelAction& a) {
    a.index = integer(l.words[1]);
    l.need(1);
    a.value = l.num(0);
}

void readLightVec3(const ActionLine& l, PanelAction& a) {
    a.index = integer(l.words[1]);
    l.need(3);
    a.vec = l.vec3(0);
}

void readPlotMaterial(const ActionLine& l, PanelAction& a) {
    l.need(6);
    a.vec = l.vec3(0);
    a.vec4 = glm::vec4(l.num(3), l.num(4), l.num(5), 0.0f);
}

// --- The table.

using Reader = void (*)(const ActionLine&, PanelAction&);
using Applier = void (*)(ViewState&, const PanelAction&);

struct ActionRow {
    PanelAction::Kind kind;
    PanelAction::Edits edits;
    const char* words;
    const char* usage;
    Reader read;
    Applier apply;
};

const ActionRow kActions[] = {
#define GIS_PANEL_ACTION_ROW(kind, edits, words, usage, read, apply) \
    {PanelAction::kind, PanelAction::Edits::edits, words, usage, read, apply},
    GIS_PANEL_ACTIONS(GIS_PANEL_ACTION_ROW)
#undef GIS_PANEL_ACTION_ROW
};

// The words of a line that name no action but begin a group's: the group's usage, or what is unknown.
struct ActionGroup {
    const char* word;
    const char* usage;
    size_t named;        // the word that names the action in the group
    const char* unknown; // "camera action"; null: the usage whatever follows
};

const ActionGroup kActionGroups[] = {
    {"camera", "camera mode|orbit|pan|zoom|move|look|reset ...", 1, "camera action"},
    {"light", "light I on|off|intensity V|color R G B|position X Y Z|direction X Y Z", 2, "light property"},
    {"lights", "lights reset", 1, nullptr},
    {"plot", "plot pane P | material R G B METALLIC ROUGHNESS SPECULAR | view-angle DEG | log on|off", 1, "plot action"},
};

// The number of words `pattern` names when `words` start with them, else 0.
size_t matchWords(const char* pattern, const std::vector<std::string>& words) {
    std::istringstream in(pattern);
    size_t n = 0;
    for (std::string p; in >> p; ++n) {
        if (n >= words.size()) return 0;
        if (p == "#") continue;
        std::istringstream alternatives(p);
        bool any = false;
        for (std::string alt; std::getline(alternatives, alt, '|');) any = any || alt == words[n];
        if (!any) return 0;
    }
    return n;
}

[[noreturn]] void throwNoAction(const std::vector<std::string>& w) {
    for (const ActionGroup& g : kActionGroups) {
        if (w[0] != g.word) continue;
        if (!g.unknown || w.size() <= g.named) throw Error(std::string("usage: ") + g.usage);
        if (g.named == 2) integer(w[1]);  // "light I ...": a bad index is the line's first error
        throw Error(std::string("unknown ") + g.unknown + " '" + w[g.named] + "'");
    }
    throw Error("unknown action '" + w[0] + "'");
}

}  // namespace

ParamValue parsePaneParam(const PanelAction& a) {
    checkPane(a.index);
    std::string method;
    const ParamDesc& d = findParam(a.text, &method);
    if (a.text != method + "." + d.key) throw Error("set takes METHOD.KEY, not the flag '" + a.text + "'");
    ParamValue v = parseParamValue(method, d, a.valueText);
    checkParamValue(method, d, v);
    return v;
}

PanelAction::Edits actionEdits(PanelAction::Kind kind) { return kActions[kind].edits; }

void applyPanelAction(ViewState& state, const PanelAction& a) {
    ViewState s = state;  // all or nothing: a throw leaves `state` as it was
    kActions[a.kind].apply(s, a);
    const bool moreShadows = a.kind == PanelAction::AddLight || (a.kind == PanelAction::SetLightEnabled && a.flag) ||
                             (a.kind == PanelAction::SetShadows && a.flag);
    if (moreShadows && s.shadows) checkShadowLayers(effectiveLights(s, s.sceneLights), kMinArrayTextureLayers, "`shadows off` first");
    state = std::move(s);
}

std::vector<std::string> splitWords(const std::string& line) {
    std::istringstream in(line.substr(0, line.find('#')));
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

PanelAction parsePanelAction(const std::vector<std::string>& w) {
    if (w.empty()) throw Error("empty action");
    for (const ActionRow& row : kActions) {
        const size_t named = matchWords(row.words, w);
        if (named == 0) continue;
        PanelAction a;
        a.kind = row.kind;
        row.read(ActionLine{w, named, row.usage}, a);
        return a;
    }
    throwNoAction(w);
}

// --- Action constructors.

PanelAction PanelAction::of(Kind kind) {
    PanelAction a;
    a.kind = kind;
    return a;
}
PanelAction PanelAction::withIndex(Kind kind, int index) {
    PanelAction a = of(kind);
    a.index = index;
    return a;
}
PanelAction PanelAction::withText(Kind kind, std::string text) {
    PanelAction a = of(kind);
    a.text = std::move(text);
    return a;
}
PanelAction PanelAction::withValue(Kind kind, float value) {
    PanelAction a = of(kind);
    a.value = value;
    return a;
}
PanelAction PanelAction::withFlag(Kind kind, bool flag) {
    PanelAction a = of(kind);
    a.flag = flag;
    return a;
}
PanelAction PanelAction::withVec(Kind kind, glm::vec3 vec) {
    PanelAction a = of(kind);
    a.vec = vec;
    return a;
}
PanelAction PanelAction::paneText(Kind kind, int pane, std::string text) {
    PanelAction a = withText(kind, std::move(text));
    a.index = pane;
    return a;
}

PanelAction PanelAction::method(int pane, std::string gi) { return paneText(SetMethod, pane, std::move(gi)); }
PanelAction PanelAction::preset(int pane, std::string name) { return paneText(SetPreset, pane, std::move(name)); }
PanelAction PanelAction::diffuse(int pane, std::string name) { return paneText(SetDiffuse, pane, std::move(name)); }
PanelAction PanelAction::specular(int pane, std::string name) { return paneText(SetSpecular, pane, std::move(name)); }
PanelAction PanelAction::display(int pane, PaneDisplay d) { return paneText(SetDisplay, pane, paneDisplayName(d)); }
PanelAction PanelAction::display(int pane, std::string name) { return paneText(SetDisplay, pane, std::move(name)); }
PanelAction PanelAction::param(int pane, std::string fullKey, std::string value) {
    PanelAction a = paneText(SetParam, pane, std::move(fullKey));
    a.valueText = std::move(value);
    return a;
}
PanelAction PanelAction::directOnly(int pane, bool on) {
    PanelAction a = withFlag(SetDirectOnly, on);
    a.index = pane;
    return a;
}
PanelAction PanelAction::viewMode(ViewMode m) { return withText(SetMode, viewModeName(m)); }
PanelAction PanelAction::dividerAt(float fraction) { return withValue(SetDivider, fraction); }
PanelAction PanelAction::exposure(float ev) { return withValue(SetExposure, ev); }
PanelAction PanelAction::tonemapper(std::string name) { return withText(SetTonemap, std::move(name)); }
PanelAction PanelAction::orbit(float dyaw, float dpitch) { return withVec(OrbitCamera, glm::vec3(dyaw, dpitch, 0.0f)); }
PanelAction PanelAction::pan(float dx, float dy) { return withVec(PanCamera, glm::vec3(dx, dy, 0.0f)); }
PanelAction PanelAction::zoom(float factor) { return withValue(ZoomCamera, factor); }
PanelAction PanelAction::move(glm::vec3 local) { return withVec(MoveCamera, local); }
PanelAction PanelAction::look(float dyaw, float dpitch) { return withVec(LookCamera, glm::vec3(dyaw, dpitch, 0.0f)); }

}  // namespace gis::view
