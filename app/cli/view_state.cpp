#include "cli/view_state.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "brdf_cpu.h"
#include "gi/method.h"

namespace gis::view {

void checkPane(int pane) {
    if (pane < 0 || pane >= kMaxPanes)
        throw Error("pane " + std::to_string(pane) + " does not exist (0.." + std::to_string(kMaxPanes - 1) + ")");
}


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

void checkPaneDisplay(const ViewState& state, int pane) {
    checkPane(pane);
    const PaneState& p = state.panes[pane];
    if (p.display == PaneDisplay::Method) checkViewOfMethod(p.gi, p.methodView);
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
    return scaledSize({r.w, r.h}, state.renderScale);
}

glm::ivec2 scaledSize(glm::ivec2 size, float scale) {
    return glm::max(glm::ivec2(glm::round(glm::vec2(size) * scale)), glm::ivec2(1));
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
    s.environmentRotation = state.environmentRotation;
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
