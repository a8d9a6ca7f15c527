#include "cli/view_state.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "brdf_cpu.h"
#include "environment.h"
#include "lights.h"
#include "gi/method.h"
#include "passes/lighting_pass.h"

namespace gis::view {

namespace {
// The lighting's term views ("direct", "emission" ...) are pane views too; "ao" is a pane display.
bool isTermView(const std::string& name) {
    const std::vector<std::string> terms = LightingPass::termViewNames();
    return name != "ao" && std::find(terms.begin(), terms.end(), name) != terms.end();
}

constexpr float kMaxPitch = 1.5533430f;  // 89 degrees: never straight up or down (lookAt's up vector)

float radians(float degrees) { return degrees * 0.017453292519943295f; }

void checkPane(int pane) {
    if (pane < 0 || pane >= kMaxPanes)
        throw Error("pane " + std::to_string(pane) + " does not exist (0.." + std::to_string(kMaxPanes - 1) + ")");
}

void checkFinite(const char* what, float v) {
    if (!std::isfinite(v) || std::abs(double(v)) > kMaxSettingMagnitude)
        throw Error(std::string(what) + " must be a finite number of magnitude <= 1e18");
}

void checkFinite(const char* what, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) checkFinite(what, v[i]);
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

void checkLight(const ViewState& s, int index) {
    if (index < 0 || index >= int(s.lights.size()))
        throw Error("light " + std::to_string(index) + " does not exist (the list has " +
                    std::to_string(s.lights.size()) + ")");
}

// Makes the edited list the one the renderers use (from the first edit on).
void beginLightEdit(ViewState& s) { s.lightsEdited = true; }

glm::vec3 orbitTarget(const ViewCamera& c) { return c.position + cameraForward(c) * c.distance; }

}  // namespace

int paneCount(ViewMode mode) { return mode == ViewMode::Single ? 1 : mode == ViewMode::Split ? 2 : 4; }

const char* viewModeName(ViewMode m) {
    switch (m) {
        case ViewMode::Single: return "single";
        case ViewMode::Split: return "split";
        case ViewMode::Grid: return "grid";
    }
    return "?";
}

ViewMode parseViewMode(const std::string& s) {
    for (ViewMode m : {ViewMode::Single, ViewMode::Split, ViewMode::Grid})
        if (s == viewModeName(m)) return m;
    throw Error("unknown view mode '" + s + "' (expected single, split or grid)");
}

const std::vector<PaneDisplay>& allPaneDisplays() {
    static const std::vector<PaneDisplay> all{PaneDisplay::Lit,    PaneDisplay::Heatmap,   PaneDisplay::Depth,
                                              PaneDisplay::Normal, PaneDisplay::BaseColor, PaneDisplay::Material,
                                              PaneDisplay::Emissive, PaneDisplay::Ao};
    return all;
}

const char* paneDisplayName(PaneDisplay d) {
    switch (d) {
        case PaneDisplay::Lit: return "lit";
        case PaneDisplay::Heatmap: return "heatmap";
        case PaneDisplay::Depth: return "depth";
        case PaneDisplay::Normal: return "normal";
        case PaneDisplay::BaseColor: return "basecolor";
        case PaneDisplay::Material: return "material";
        case PaneDisplay::Emissive: return "emissive";
        case PaneDisplay::Ao: return "ao";
        case PaneDisplay::Method: return "method";
    }
    return "?";
}

PaneDisplay parsePaneDisplay(const std::string& s) {
    for (PaneDisplay d : allPaneDisplays())
        if (s == paneDisplayName(d)) return d;
    throw Error("unknown display '" + s + "' (expected lit, heatmap, depth, normal, basecolor, material, emissive or ao)");
}

bool isGBufferDisplay(PaneDisplay d) {
    return d != PaneDisplay::Lit && d != PaneDisplay::Heatmap && d != PaneDisplay::Ao && d != PaneDisplay::Method;
}

// --- Action constructors.

PanelAction PanelAction::method(int pane, std::string gi) {
    PanelAction a;
    a.kind = SetMethod;
    a.index = pane;
    a.text = std::move(gi);
    return a;
}
PanelAction PanelAction::preset(int pane, std::string name) {
    PanelAction a;
    a.kind = SetPreset;
    a.index = pane;
    a.text = std::move(name);
    return a;
}
PanelAction PanelAction::diffuse(int pane, std::string name) {
    PanelAction a;
    a.kind = SetDiffuse;
    a.index = pane;
    a.text = std::move(name);
    return a;
}
PanelAction PanelAction::specular(int pane, std::string name) {
    PanelAction a;
    a.kind = SetSpecular;
    a.index = pane;
    a.text = std::move(name);
    return a;
}
PanelAction PanelAction::display(int pane, PaneDisplay d) {
    PanelAction a;
    a.kind = SetDisplay;
    a.index = pane;
    a.text = paneDisplayName(d);
    return a;
}
PanelAction PanelAction::display(int pane, std::string name) {
    PanelAction a;
    a.kind = SetDisplay;
    a.index = pane;
    a.text = std::move(name);
    return a;
}
PanelAction PanelAction::param(int pane, std::string fullKey, std::string value) {
    PanelAction a;
    a.kind = SetParam;
    a.index = pane;
    a.text = std::move(fullKey);
    a.valueText = std::move(value);
    return a;
}
PanelAction PanelAction::directOnly(int pane, bool on) {
    PanelAction a;
    a.kind = SetDirectOnly;
    a.index = pane;
    a.flag = on;
    return a;
}
PanelAction PanelAction::viewMode(ViewMode m) {
    PanelAction a;
    a.kind = SetMode;
    a.text = viewModeName(m);
    return a;
}
PanelAction PanelAction::dividerAt(float fraction) {
    PanelAction a;
    a.kind = SetDivider;
    a.value = fraction;
    return a;
}
PanelAction PanelAction::exposure(float ev) {
    PanelAction a;
    a.kind = SetExposure;
    a.value = ev;
    return a;
}
PanelAction PanelAction::tonemapper(std::string name) {
    PanelAction a;
    a.kind = SetTonemap;
    a.text = std::move(name);
    return a;
}
PanelAction PanelAction::orbit(float dyaw, float dpitch) {
    PanelAction a;
    a.kind = OrbitCamera;
    a.vec = glm::vec3(dyaw, dpitch, 0.0f);
    return a;
}
PanelAction PanelAction::pan(float dx, float dy) {
    PanelAction a;
    a.kind = PanCamera;
    a.vec = glm::vec3(dx, dy, 0.0f);
    return a;
}
PanelAction PanelAction::zoom(float factor) {
    PanelAction a;
    a.kind = ZoomCamera;
    a.value = factor;
    return a;
}
PanelAction PanelAction::move(glm::vec3 local) {
    PanelAction a;
    a.kind = MoveCamera;
    a.vec = local;
    return a;
}
PanelAction PanelAction::look(float dyaw, float dpitch) {
    PanelAction a;
    a.kind = LookCamera;
    a.vec = glm::vec3(dyaw, dpitch, 0.0f);
    return a;
}

// --- Camera.

glm::vec3 cameraForward(const ViewCamera& c) {
    return glm::vec3(std::sin(c.yaw) * std::cos(c.pitch), std::sin(c.pitch), -std::cos(c.yaw) * std::cos(c.pitch));
}

void resetCamera(ViewState& state, const Scene& scene, int cameraIndex) {
    if (!scene.cameras.empty() && (cameraIndex < 0 || cameraIndex >= int(scene.cameras.size())))
        throw Error("camera " + std::to_string(cameraIndex) + " does not exist (the scene has " +
                    std::to_string(scene.cameras.size()) + ")");
    const float aspect = float(std::max(state.viewWidth, 1)) / float(std::max(state.viewHeight, 1));
    const Camera cam = scene.cameras.empty() ? defaultCamera(scene.bounds, aspect) : scene.cameras[cameraIndex];
    const Aabb bounds = scene.bounds.empty() ? Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)} : scene.bounds;
    const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-4f);
    ViewCamera c;
    c.sceneCamera = cameraIndex;
    c.free = false;
    c.position = glm::vec3(cam.cameraToWorld[3]);
    const glm::vec3 fwd = -glm::normalize(glm::vec3(cam.cameraToWorld[2]));
    c.pitch = std::clamp(std::asin(std::clamp(fwd.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    c.yaw = std::atan2(fwd.x, -fwd.z);
    float d = glm::dot(bounds.center() - c.position, fwd);
    if (!(d > 1e-3f * radius)) d = std::max(glm::length(bounds.center() - c.position), radius);
    c.distance = d;
    c.yfov = cam.orthographic ? 0.6981317f : cam.yfov;
    c.znear = cam.znear;
    // Far enough to zoom out a long way from the scene.
    c.zfar = cam.zfar <= 0.0f ? 0.0f : std::max(cam.zfar, 20.0f * (d + radius));
    c.speed = radius;
    state.camera = c;
    state.homeCamera = c;
}

void resetLights(ViewState& state, const std::vector<Light>& sceneLights) {
    state.sceneLights = sceneLights;
    state.lights.clear();
    for (const Light& l : sceneLights) state.lights.push_back({l, true});
    state.lightsEdited = false;
}

std::vector<Light> effectiveLights(const ViewState& state, const std::vector<Light>& sceneLights) {
    if (!state.lightsEdited) return sceneLights;
    std::vector<Light> out;
    for (const LightState& l : state.lights)
        if (l.enabled) out.push_back(l.light);
    return out;
}

CameraMatrices viewCameraMatrices(const ViewState& state, const Scene& scene, float aspect) {
    const ViewCamera& c = state.camera;
    if (!c.free) return cameraMatrices(scene, c.sceneCamera, aspect);
    CameraMatrices m;
    m.position = c.position;
    m.view = glm::lookAt(c.position, c.position + cameraForward(c), glm::vec3(0.0f, 1.0f, 0.0f));
    m.znear = c.znear;
    m.zfar = c.zfar;
    m.proj = c.zfar <= 0.0f ? glm::infinitePerspective(c.yfov, aspect, c.znear)
                            : glm::perspective(c.yfov, aspect, c.znear, c.zfar);
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
    return m;
}

std::array<PaneState, kMaxPanes> defaultPanes() {
    std::array<PaneState, kMaxPanes> panes;
    const char* methods[kMaxPanes] = {"none", "vct", "probes", "pathtrace"};
    for (int i = 0; i < kMaxPanes; ++i) panes[size_t(i)].gi = methods[i];
    return panes;
}

// --- Applying actions.

ParamValue parsePaneParam(const PanelAction& a) {
    checkPane(a.index);
    std::string method;
    const ParamDesc& d = findParam(a.text, &method);
    if (a.text != method + "." + d.key) throw Error("set takes METHOD.KEY, not the flag '" + a.text + "'");
    ParamValue v = parseParamValue(method, d, a.valueText);
    checkParamValue(method, d, v);
    return v;
}

void applyPanelAction(ViewState& state, const PanelAction& a) {
    ViewState s = state;  // all or nothing: a throw leaves `state` as it was
    ViewCamera& cam = s.camera;
    switch (a.kind) {
        case PanelAction::SetMethod:
            checkPane(a.index);
            giMethod(a.text);  // throws for an unknown one
            // A new method starts at the default preset: the old method's one was chosen for it.
            if (s.panes[a.index].gi != a.text) s.panes[a.index].preset = PaneState{}.preset;
            s.panes[a.index].gi = a.text;
            if (s.panes[a.index].display == PaneDisplay::Method) s.panes[a.index].display = PaneDisplay::Lit;
            break;
        case PanelAction::SetParam:
            s.panes[a.index].params[a.text] = parsePaneParam(a);
            checkParams(paneSettings(s, a.index, {1, 1}).params);  // what the ranges cannot say, as render does
            break;
        case PanelAction::ResetParams:
            checkPane(a.index);
            s.panes[a.index].params.clear();
            break;
        case PanelAction::SetPreset: {
            checkPane(a.index);
            const auto& names = presetNames();
            if (std::find(names.begin(), names.end(), a.text) == names.end())
                throw Error("unknown preset '" + a.text + "' (expected low, medium or high)");
            s.panes[a.index].preset = a.text;
            break;
        }
        case PanelAction::SetDiffuse:
            checkPane(a.index);
            s.panes[a.index].diffuse = diffuseByName(a.text);
            break;
        case PanelAction::SetSpecular:
            checkPane(a.index);
            s.panes[a.index].specular = specularByName(a.text);
            break;
        case PanelAction::SetDisplay:
            checkPane(a.index);
            // A method's views have a dot ("vct.slice"; the renderer says whether it exists), the
            // lighting's term views are named by the lighting pass ("direct", "emission").
            if ((a.text.find('.') != std::string::npos && a.text.rfind("gbuffer.", 0) != 0) || isTermView(a.text)) {
                s.panes[a.index].display = PaneDisplay::Method;  // the renderer says whether it exists
                s.panes[a.index].methodView = a.text;
            } else {
                s.panes[a.index].display = parsePaneDisplay(a.text);
            }
            break;
        case PanelAction::SetDirectOnly:
            checkPane(a.index);
            s.panes[a.index].directOnly = a.flag;
            break;
        case PanelAction::SetMode: s.mode = parseViewMode(a.text); break;
        case PanelAction::SwapSides: std::swap(s.panes[0], s.panes[1]); break;
        case PanelAction::SetDivider:
            checkFinite("divider", a.value);
            s.divider = std::clamp(a.value, 0.02f, 0.98f);
            break;
        case PanelAction::SetExposure:
            checkFinite("exposure", a.value);
            if (std::abs(a.value) > 64.0f) throw Error("exposure must be in [-64, 64] EV");
            s.exposureEV = a.value;
            break;
        case PanelAction::SetTonemap: s.tonemap = parseTonemapper(a.text); break;
        case PanelAction::SetAmbient:
            checkFinite("ambient", a.vec);
            if (glm::any(glm::lessThan(a.vec, glm::vec3(0.0f)))) throw Error("ambient radiance must be non-negative");
            s.ambient = a.vec;
            break;
        case PanelAction::SetShadows: s.shadows = a.flag; break;
        case PanelAction::SetBackground:
            if (!a.flag) {
                s.background.reset();
                break;
            }
            checkFinite("background", a.vec);
            if (glm::any(glm::lessThan(a.vec, glm::vec3(0.0f)))) throw Error("background radiance must be non-negative");
            checkEnvironmentChoice(true, s.environment);
            s.background = a.vec;
            break;
        case PanelAction::SetEnvironment:
            if (!a.text.empty()) {
                checkEnvironmentChoice(s.background.has_value(), a.text);
                loadEnvironmentMap(a.text);  // the render's own check, now: a bad file is this line's error
            }
            s.environment = a.text;
            break;
        case PanelAction::SetMaxBounces:  // the path tracer's row gives the range
            checkParamValue(methodInRole(MethodRole::Reference).name, findParam(roleParamKey(MethodRole::Reference, "bounces")),
                            ParamValue{a.value});
            s.maxBounces = int(a.value);
            break;
        case PanelAction::SetRenderScale:
            checkFinite("render scale", a.value);
            if (a.value < 0.125f || a.value > 1.0f) throw Error("render scale must be in [0.125, 1]");
            s.renderScale = a.value;
            break;
        case PanelAction::SetHeatmapMetric: s.heatmapMetric = parseErrorMetric(a.text); break;
        case PanelAction::SetReferenceSpp:
            checkParamValue(methodInRole(MethodRole::Reference).name, findParam(roleParamKey(MethodRole::Reference, "spp")),
                            ParamValue{a.value});
            s.referenceSpp = int(a.value);
            break;
        case PanelAction::SetCameraMode:
            if (a.text == "orbit") cam.mode = CameraMode::Orbit;
            else if (a.text == "fly") cam.mode = CameraMode::Fly;
            else throw Error("unknown camera mode '" + a.text + "' (expected orbit or fly)");
            break;
        case PanelAction::OrbitCamera: {
            checkFinite("camera orbit", a.vec);
            const glm::vec3 target = orbitTarget(cam);
            cam.yaw = std::remainder(cam.yaw + a.vec.x, 6.283185307179586f);
            cam.pitch = std::clamp(cam.pitch + a.vec.y, -kMaxPitch, kMaxPitch);
            cam.position = target - cameraForward(cam) * cam.distance;
            cam.free = true;
            break;
        }
        case PanelAction::PanCamera: {
            checkFinite("camera pan", a.vec);
            const glm::vec3 fwd = cameraForward(cam);
            const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0.0f, 1.0f, 0.0f)));
            const glm::vec3 up = glm::cross(right, fwd);
            cam.position += (right * a.vec.x + up * a.vec.y) * cam.distance;
            cam.free = true;
            break;
        }
        case PanelAction::ZoomCamera: {
            checkFinite("camera zoom", a.value);
            if (a.value <= 0.0f) throw Error("camera zoom factor must be positive");
            const glm::vec3 target = orbitTarget(cam);
            cam.distance = std::clamp(cam.distance * a.value, 1e-4f, 1e7f);
            cam.position = target - cameraForward(cam) * cam.distance;
            cam.free = true;
            break;
        }
        case PanelAction::MoveCamera: {
            checkFinite("camera move", a.vec);
            const glm::vec3 fwd = cameraForward(cam);
            const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0.0f, 1.0f, 0.0f)));
            const glm::vec3 up = glm::cross(right, fwd);
            const glm::vec3 moved = cam.position + right * a.vec.x + up * a.vec.y + fwd * a.vec.z;
            checkFinite("camera position after the move", moved);  // else saved as null
            cam.position = moved;
            cam.free = true;
            break;
        }
        case PanelAction::LookCamera:
            checkFinite("camera look", a.vec);
            cam.yaw = std::remainder(cam.yaw + a.vec.x, 6.283185307179586f);
            cam.pitch = std::clamp(cam.pitch + a.vec.y, -kMaxPitch, kMaxPitch);
            cam.free = true;
            break;
        case PanelAction::ResetCamera: {
            const CameraMode mode = cam.mode;
            cam = s.homeCamera;
            cam.mode = mode;
            break;
        }
        case PanelAction::SetLightEnabled:
            checkLight(s, a.index);
            beginLightEdit(s);
            s.lights[a.index].enabled = a.flag;
            break;
        case PanelAction::SetLightIntensity:
            checkLight(s, a.index);
            checkFinite("light intensity", a.value);
            if (a.value < 0.0f) throw Error("light intensity must be non-negative");
            beginLightEdit(s);
            s.lights[a.index].light.intensity = a.value;
            break;
        case PanelAction::SetLightColor:
            checkLight(s, a.index);
            checkFinite("light colour", a.vec);
            if (glm::any(glm::lessThan(a.vec, glm::vec3(0.0f)))) throw Error("light colour must be non-negative");
            beginLightEdit(s);
            s.lights[a.index].light.color = a.vec;
            break;
        case PanelAction::SetLightPosition:
            checkLight(s, a.index);
            checkFinite("light position", a.vec);
            beginLightEdit(s);
            s.lights[a.index].light.position = a.vec;
            break;
        case PanelAction::SetLightDirection: {
            checkLight(s, a.index);
            checkFinite("light direction", a.vec);
            const float len = glm::length(a.vec);
            if (!(len > 1e-6f)) throw Error("light direction must not be zero");
            beginLightEdit(s);
            s.lights[a.index].light.direction = a.vec / len;
            break;
        }
        case PanelAction::AddLight: {
            Light l;
            if (a.text == "point") l.type = LightType::Point;
            else if (a.text == "spot") l.type = LightType::Spot;
            else if (a.text == "directional") l.type = LightType::Directional;
            else throw Error("unknown light type '" + a.text + "' (expected point, spot or directional)");
            l.name = "added " + a.text;
            l.position = orbitTarget(cam);  // where the camera looks: visible right away
            l.direction = cameraForward(cam);
            beginLightEdit(s);
            s.lights.push_back({l, true});
            break;
        }
        case PanelAction::RemoveLight:
            checkLight(s, a.index);
            beginLightEdit(s);
            s.lights.erase(s.lights.begin() + a.index);
            break;
        case PanelAction::ResetLights:
            s.lights.clear();
            for (const Light& l : s.sceneLights) s.lights.push_back({l, true});
            s.lightsEdited = false;
            break;
        case PanelAction::SetPlotPane: checkPane(a.index); s.plotPane = a.index; break;
        case PanelAction::SetPlotMaterial:
            checkFinite("plot base colour", a.vec);
            for (int i = 0; i < 4; ++i) checkFinite("plot material", a.vec4[i]);
            s.plotBaseColor = glm::clamp(a.vec, glm::vec3(0.0f), glm::vec3(1.0f));
            s.plotMetallic = std::clamp(a.vec4.x, 0.0f, 1.0f);
            s.plotRoughness = std::clamp(a.vec4.y, 0.0f, 1.0f);
            s.plotSpecular = std::clamp(a.vec4.z, 0.0f, 1.0f);
            break;
        case PanelAction::SetPlotViewAngle:
            checkFinite("plot view angle", a.value);
            s.plotViewAngle = std::clamp(a.value, 0.0f, radians(89.0f));
            break;
        case PanelAction::SetPlotLog: s.plotLog = a.flag; break;
    }
    const bool moreShadows = a.kind == PanelAction::AddLight || (a.kind == PanelAction::SetLightEnabled && a.flag) ||
                             (a.kind == PanelAction::SetShadows && a.flag);
    if (moreShadows && s.shadows) checkShadowLayers(effectiveLights(s, s.sceneLights), kMinArrayTextureLayers, "`shadows off` first");
    state = std::move(s);
}

void checkPaneDisplay(const ViewState& state, int pane) {
    checkPane(pane);
    const PaneState& p = state.panes[pane];
    if (p.display == PaneDisplay::Method) checkViewOfMethod(p.gi, p.methodView);
}

// --- Words to actions.

std::vector<std::string> splitWords(const std::string& line) {
    std::istringstream in(line.substr(0, line.find('#')));
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

namespace {

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

}  // namespace

PanelAction parsePanelAction(const std::vector<std::string>& w) {
    if (w.empty()) throw Error("empty action");
    auto need = [&](size_t n, const char* usage) {
        if (w.size() != n) throw Error(std::string("usage: ") + usage);
    };
    const std::string& cmd = w[0];
    PanelAction a;
    auto paneText = [&](PanelAction::Kind kind, const char* usage) {
        need(3, usage);
        a.kind = kind;
        a.index = integer(w[1]);
        a.text = w[2];
        return a;
    };
    if (cmd == "method") return paneText(PanelAction::SetMethod, "method PANE NAME (gisandbox methods)");
    if (cmd == "set") {
        need(4, "set PANE METHOD.KEY VALUE");
        return PanelAction::param(integer(w[1]), w[2], w[3]);
    }
    if (cmd == "reset-params") {
        need(2, "reset-params PANE");
        a.kind = PanelAction::ResetParams;
        a.index = integer(w[1]);
        return a;
    }
    if (cmd == "preset") return paneText(PanelAction::SetPreset, "preset PANE low|medium|high");
    if (cmd == "diffuse") return paneText(PanelAction::SetDiffuse, "diffuse PANE NAME");
    if (cmd == "specular") return paneText(PanelAction::SetSpecular, "specular PANE NAME");
    if (cmd == "display")
        return paneText(PanelAction::SetDisplay, "display PANE lit|heatmap|depth|normal|basecolor|material|emissive|ao|VIEW");
    if (cmd == "direct-only") {
        need(3, "direct-only PANE on|off");
        return PanelAction::directOnly(integer(w[1]), onOff(w[2]));
    }
    if (cmd == "mode") {
        need(2, "mode single|split|grid");
        a.kind = PanelAction::SetMode;
        a.text = w[1];
        return a;
    }
    if (cmd == "swap") {
        need(1, "swap (panes 0 and 1 trade places: the split's A/B)");
        a.kind = PanelAction::SwapSides;
        return a;
    }
    if (cmd == "divider") {
        need(2, "divider FRACTION");
        return PanelAction::dividerAt(number(w[1]));
    }
    if (cmd == "exposure") {
        need(2, "exposure EV");
        return PanelAction::exposure(number(w[1]));
    }
    if (cmd == "tonemap") {
        need(2, "tonemap aces|linear");
        return PanelAction::tonemapper(w[1]);
    }
    if (cmd == "ambient") {
        if (w.size() != 2 && w.size() != 4) throw Error("usage: ambient V | ambient R G B");
        a.kind = PanelAction::SetAmbient;
        a.vec = w.size() == 2 ? glm::vec3(number(w[1])) : glm::vec3(number(w[1]), number(w[2]), number(w[3]));
        return a;
    }
    if (cmd == "shadows") {
        need(2, "shadows on|off");
        a.kind = PanelAction::SetShadows;
        a.flag = onOff(w[1]);
        return a;
    }
    if (cmd == "background") {
        a.kind = PanelAction::SetBackground;
        if (w.size() == 2 && w[1] == "off") return a;
        if (w.size() != 4) throw Error("usage: background R G B | background off");
        a.flag = true;
        a.vec = glm::vec3(number(w[1]), number(w[2]), number(w[3]));
        return a;
    }
    if (cmd == "environment") {
        need(2, "environment FILE.hdr | environment off");
        a.kind = PanelAction::SetEnvironment;
        a.text = w[1] == "off" ? "" : w[1];
        return a;
    }
    auto oneNumber = [&](PanelAction::Kind kind, const char* usage) {
        need(2, usage);
        a.kind = kind;
        a.value = number(w[1]);
        return a;
    };
    if (cmd == "max-bounces") return oneNumber(PanelAction::SetMaxBounces, "max-bounces N");
    if (cmd == "render-scale") return oneNumber(PanelAction::SetRenderScale, "render-scale S");
    if (cmd == "reference-spp") return oneNumber(PanelAction::SetReferenceSpp, "reference-spp N");
    if (cmd == "metric") {
        need(2, "metric flip|rmse|relmse|ssim");
        a.kind = PanelAction::SetHeatmapMetric;
        a.text = w[1];
        return a;
    }
    if (cmd == "camera") {
        if (w.size() < 2) throw Error("usage: camera mode|orbit|pan|zoom|move|look|reset ...");
        const std::string& sub = w[1];
        if (sub == "mode") {
            need(3, "camera mode orbit|fly");
            a.kind = PanelAction::SetCameraMode;
            a.text = w[2];
            return a;
        }
        if (sub == "orbit") {
            need(4, "camera orbit DYAW DPITCH (degrees)");
            return PanelAction::orbit(radians(number(w[2])), radians(number(w[3])));
        }
        if (sub == "look") {
            need(4, "camera look DYAW DPITCH (degrees)");
            return PanelAction::look(radians(number(w[2])), radians(number(w[3])));
        }
        if (sub == "pan") {
            need(4, "camera pan DX DY (fractions of the orbit distance)");
            return PanelAction::pan(number(w[2]), number(w[3]));
        }
        if (sub == "zoom") {
            need(3, "camera zoom FACTOR");
            return PanelAction::zoom(number(w[2]));
        }
        if (sub == "move") {
            need(5, "camera move RIGHT UP FORWARD (scene units)");
            return PanelAction::move(glm::vec3(number(w[2]), number(w[3]), number(w[4])));
        }
        if (sub == "reset") {
            need(2, "camera reset");
            a.kind = PanelAction::ResetCamera;
            return a;
        }
        throw Error("unknown camera action '" + sub + "'");
    }
    if (cmd == "lights") {
        if (w.size() != 2 || w[1] != "reset") throw Error("usage: lights reset");
        a.kind = PanelAction::ResetLights;
        return a;
    }
    if (cmd == "light") {
        if (w.size() == 3 && w[1] == "add") {
            a.kind = PanelAction::AddLight;
            a.text = w[2];
            return a;
        }
        if (w.size() == 3 && w[1] == "remove") {
            a.kind = PanelAction::RemoveLight;
            a.index = integer(w[2]);
            return a;
        }
        if (w.size() < 3) throw Error("usage: light I on|off|intensity V|color R G B|position X Y Z|direction X Y Z");
        a.index = integer(w[1]);
        const std::string& what = w[2];
        if (what == "on" || what == "off") {
            need(3, "light I on|off");
            a.kind = PanelAction::SetLightEnabled;
            a.flag = what == "on";
            return a;
        }
        if (what == "intensity") {
            need(4, "light I intensity V");
            a.kind = PanelAction::SetLightIntensity;
            a.value = number(w[3]);
            return a;
        }
        auto vec3 = [&](PanelAction::Kind kind, const char* usage) {
            need(6, usage);
            a.kind = kind;
            a.vec = glm::vec3(number(w[3]), number(w[4]), number(w[5]));
            return a;
        };
        if (what == "color") return vec3(PanelAction::SetLightColor, "light I color R G B");
        if (what == "position") return vec3(PanelAction::SetLightPosition, "light I position X Y Z");
        if (what == "direction") return vec3(PanelAction::SetLightDirection, "light I direction X Y Z");
        throw Error("unknown light property '" + what + "'");
    }
    if (cmd == "plot") {
        if (w.size() < 2) throw Error("usage: plot pane P | material R G B METALLIC ROUGHNESS SPECULAR | view-angle DEG | log on|off");
        const std::string& sub = w[1];
        if (sub == "pane") {
            need(3, "plot pane P");
            a.kind = PanelAction::SetPlotPane;
            a.index = integer(w[2]);
            return a;
        }
        if (sub == "material") {
            need(8, "plot material R G B METALLIC ROUGHNESS SPECULAR");
            a.kind = PanelAction::SetPlotMaterial;
            a.vec = glm::vec3(number(w[2]), number(w[3]), number(w[4]));
            a.vec4 = glm::vec4(number(w[5]), number(w[6]), number(w[7]), 0.0f);
            return a;
        }
        if (sub == "view-angle") {
            need(3, "plot view-angle DEGREES");
            a.kind = PanelAction::SetPlotViewAngle;
            a.value = radians(number(w[2]));
            return a;
        }
        if (sub == "log") {
            need(3, "plot log on|off");
            a.kind = PanelAction::SetPlotLog;
            a.flag = onOff(w[2]);
            return a;
        }
        throw Error("unknown plot action '" + sub + "'");
    }
    throw Error("unknown action '" + cmd + "'");
}

// --- Settings for the renderers.

std::vector<PaneRect> paneRects(ViewMode mode, int w, int h) {
    w = std::max(w, 1);
    h = std::max(h, 1);
    if (mode == ViewMode::Single) return {{0, 0, w, h}};
    if (mode == ViewMode::Split) return {{0, 0, w, h}, {0, 0, w, h}};
    const int hw = std::max(w / 2, 1), hh = std::max(h / 2, 1);
    return {{0, 0, hw, hh}, {w - hw, 0, hw, hh}, {0, h - hh, hw, hh}, {w - hw, h - hh, hw, hh}};
}

glm::ivec2 paneRenderSize(const ViewState& state, int viewWidth, int viewHeight) {
    const PaneRect r = paneRects(state.mode, viewWidth, viewHeight)[0];
    return glm::max(glm::ivec2(glm::round(glm::vec2(r.w, r.h) * state.renderScale)), glm::ivec2(1));
}

namespace {
std::string rendererView(const PaneState& p) {
    switch (p.display) {
        case PaneDisplay::Depth: return "gbuffer.depth";
        case PaneDisplay::Normal: return "gbuffer.normal";
        case PaneDisplay::BaseColor: return "gbuffer.basecolor";
        case PaneDisplay::Material: return "gbuffer.material";
        case PaneDisplay::Emissive: return "gbuffer.emissive";
        case PaneDisplay::Ao: return "ao";
        case PaneDisplay::Method: return p.methodView;
        default: return "final";
    }
}
}  // namespace

RenderSettings paneSettings(const ViewState& state, int pane, glm::ivec2 size) {
    checkPane(pane);
    const PaneState& p = state.panes[pane];
    RenderSettings s;
    s.width = size.x;
    s.height = size.y;
    s.camera = state.camera.sceneCamera;
    s.tonemap = state.tonemap;
    s.exposureEV = state.exposureEV;
    s.ambient = state.ambient;
    s.shadows = state.shadows;
    s.background = state.background;
    s.environment = state.environment;
    applyPreset(s, p.gi, p.preset);
    const std::string bounces = roleParamKey(MethodRole::Reference, "bounces");
    s.params[bounces] = ParamValue{double(state.maxBounces)};  // shared by every pane
    for (const auto& [key, value] : p.params) s.params[key] = value;       // the pane's own edits
    s.samplesPerFrame = 1;  // progressive: a sample per displayed frame
    s.diffuse = p.diffuse;
    s.specular = p.specular;
    s.view = rendererView(p);
    if (p.directOnly) {
        if (giMethod(s.gi).pipeline == MethodPipeline::Deferred) s.ambient = glm::vec3(0.0f);
        if (giMethod(s.gi).role == MethodRole::Reference) s.params[bounces] = ParamValue{0.0};
    }
    return s;
}

RenderSettings referenceSettings(const ViewState& state, int pane, glm::ivec2 size) {
    RenderSettings s = paneSettings(state, pane, size);
    s.gi = methodInRole(MethodRole::Reference).name;
    s.params = {{roleParamKey(MethodRole::Reference, "spp"), ParamValue{double(state.referenceSpp)}},
                {roleParamKey(MethodRole::Reference, "bounces"), ParamValue{double(state.maxBounces)}}};
    s.samplesPerFrame = 1;
    s.ambient = state.ambient;
    s.view = "final";
    return s;
}

std::vector<std::string> methodChoices() {
    std::vector<std::string> names;
    for (const GiMethod& m : giMethods()) names.push_back(m.name);
    return names;
}

std::vector<std::string> displayChoices(const std::vector<DebugViewDesc>& views) {
    std::vector<std::string> names;
    for (PaneDisplay d : allPaneDisplays()) names.push_back(paneDisplayName(d));
    for (const DebugViewDesc& v : views)
        if (v.name != "final" && v.name != "ao" && v.name.rfind("gbuffer.", 0) != 0) names.push_back(v.name);
    return names;
}

ParamValue paneParam(const ViewState& state, int pane, const std::string& method, const ParamDesc& desc) {
    const RenderSettings s = paneSettings(state, pane, {1, 1});
    auto it = s.params.find(method + "." + desc.key);
    return it == s.params.end() ? desc.defaultValue : it->second;
}

std::vector<ParamTableView> paneParamTables(const PaneState& pane) {
    const GiMethod& m = giMethod(pane.gi);
    std::vector<ParamTableView> tables;
    if (!m.params.empty()) tables.push_back({m.name, &m.params});
    if (m.pipeline == MethodPipeline::Deferred)
        for (const ParamGroup& g : paramGroups()) tables.push_back({g.name, &g.params});
    return tables;
}

std::string paneLabel(const ViewState& state, int pane) {
    const PaneState& p = state.panes[pane];
    std::string label = p.gi + "/" + p.preset + (p.params.empty() ? "" : "*") + " " + diffuseModelName(p.diffuse) +
                        "+" + specularModelName(p.specular);
    if (p.directOnly && !isGBufferDisplay(p.display)) label += " direct";
    if (p.display != PaneDisplay::Lit)
        label += std::string(" [") +
                 (p.display == PaneDisplay::Heatmap  ? std::string(errorMetricName(state.heatmapMetric)) + " heatmap"
                  : p.display == PaneDisplay::Method ? p.methodView
                                                     : paneDisplayName(p.display)) +
                 "]";
    return label;
}

}  // namespace gis::view
