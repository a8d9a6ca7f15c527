#include "cli/settings_io.h"

#include <cmath>

#include "brdf_cpu.h"
#include "gi/method.h"
#include "image.h"
#include "scene/atomic_file.h"
#include "scene/user_file.h"
#include "cli/panel_action.h"
#include "cli/user_json.h"

namespace gis::view {

namespace {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

ojson vec(glm::vec3 v) { return ojson::array({v.x, v.y, v.z}); }

float number(const json& j, const std::string& key) {
    if (!j.is_number()) throw Error("'" + key + "' must be a number");
    const double v = j.get<double>();
    if (!std::isfinite(v) || std::abs(v) > kMaxSettingMagnitude)
        throw Error("'" + key + "' must be a finite number of magnitude <= 1e18");
    return float(v);
}

glm::vec3 vec3(const json& j, const std::string& key) {
    if (!j.is_array() || j.size() != 3) throw Error("'" + key + "' must be an array of 3 numbers");
    return glm::vec3(number(j[0], key), number(j[1], key), number(j[2], key));
}

std::string text(const json& j, const std::string& key) {
    if (!j.is_string()) throw Error("'" + key + "' must be a string");
    return j.get<std::string>();
}

bool boolean(const json& j, const std::string& key) {
    if (!j.is_boolean()) throw Error("'" + key + "' must be true or false");
    return j.get<bool>();
}

int integer(const json& j, const std::string& key) {
    // 64.0 is the whole number 64 (a tool that writes every number as a double is not wrong).
    const bool whole = j.is_number_integer() ||
                       (j.is_number_float() && std::isfinite(j.get<double>()) && j.get<double>() == std::floor(j.get<double>()) &&
                        std::abs(j.get<double>()) <= double(int64_t(1) << 30));
    if (!whole) throw Error("'" + key + "' must be a whole number");
    const int64_t v = j.is_number_integer() ? j.get<int64_t>() : int64_t(j.get<double>());
    if (v < -(int64_t(1) << 30) || v > (int64_t(1) << 30)) throw Error("'" + key + "' is out of range");
    return int(v);
}

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Directional: return "directional";
        case LightType::Point: return "point";
        case LightType::Spot: return "spot";
    }
    return "?";
}

}  // namespace

ojson paramToJson(const ParamDesc& d, const ParamValue& v) {
    switch (d.type) {
        case ParamType::Int: return int64_t(v.number);
        case ParamType::Float: return v.number;
        case ParamType::Bool: return v.number != 0;
        case ParamType::Choice: return v.text;
        case ParamType::Colour: return vec(v.colour);
    }
    return nullptr;
}

ParamValue paramFromJson(const std::string& fullKey, const json& j) {
    std::string method;
    const ParamDesc& d = findParam(fullKey, &method);
    if (fullKey != method + "." + d.key) throw Error("'" + fullKey + "' is a flag, not METHOD.KEY");
    ParamValue v;
    switch (d.type) {
        case ParamType::Int: v.number = integer(j, fullKey); break;
        case ParamType::Float:
            if (!j.is_number() || !std::isfinite(j.get<double>())) throw Error("'" + fullKey + "' must be a number");
            v.number = j.get<double>();
            break;
        case ParamType::Bool: v.number = boolean(j, fullKey) ? 1 : 0; break;
        case ParamType::Choice: v.text = text(j, fullKey); break;
        case ParamType::Colour: v.colour = vec3(j, fullKey); break;
    }
    checkParamValue(method, d, v);
    return v;
}

ojson paramsToJson(const ParamValues& values) {
    ojson j = ojson::object();
    for (const auto& [key, value] : values) j[key] = paramToJson(findParam(key), value);
    return j;
}

ojson lightToJson(const Light& l) {
    return ojson{{"name", l.name},
                 {"type", lightTypeName(l.type)},
                 {"color", vec(l.color)},
                 {"intensity", l.intensity},
                 {"range", l.range},
                 {"inner_cone", l.innerConeAngle},
                 {"outer_cone", l.outerConeAngle},
                 {"position", vec(l.position)},
                 {"direction", vec(l.direction)}};
}

Light lightFromJson(const json& j) {
    if (!j.is_object()) throw Error("a light must be an object");
    Light l;
    for (const auto& [key, v] : j.items()) {
        if (key == "name") l.name = text(v, key);
        else if (key == "type") {
            const std::string t = text(v, key);
            if (t == "directional") l.type = LightType::Directional;
            else if (t == "point") l.type = LightType::Point;
            else if (t == "spot") l.type = LightType::Spot;
            else throw Error("unknown light type '" + t + "'");
        } else if (key == "color") l.color = vec3(v, key);
        else if (key == "intensity") l.intensity = number(v, key);
        else if (key == "range") l.range = number(v, key);
        else if (key == "inner_cone") l.innerConeAngle = number(v, key);
        else if (key == "outer_cone") l.outerConeAngle = number(v, key);
        else if (key == "position") l.position = vec3(v, key);
        else if (key == "direction") l.direction = vec3(v, key);
        else if (key != "enabled") throw Error("unknown light key '" + key + "'");
    }
    if (l.intensity < 0.0f || glm::any(glm::lessThan(l.color, glm::vec3(0.0f))) || l.range < 0.0f)
        throw Error("light '" + l.name + "': intensity, colour and range must be non-negative");
    if (!(glm::length(l.direction) > 1e-6f)) throw Error("light '" + l.name + "': direction must not be zero");
    return l;  // (the direction is normalised where it is used: makeGpuLights)
}

ojson viewStateToJson(const ViewState& s) {
    ojson j;
    j["gisandbox_view_settings"] = kSettingsVersion;
    j["scene"] = s.scene;
    j["lighting"] = s.lighting;
    j["view_size"] = {s.viewWidth, s.viewHeight};
    j["mode"] = viewModeName(s.mode);
    j["divider"] = s.divider;
    for (const PaneState& p : s.panes)
        j["panes"].push_back(ojson{{"gi", p.gi},
                                   {"preset", p.preset},
                                   {"params", paramsToJson(p.params)},
                                   {"diffuse", diffuseModelName(p.diffuse)},
                                   {"specular", specularModelName(p.specular)},
                                   {"display", p.display == PaneDisplay::Method ? p.methodView
                                                                                : paneDisplayName(p.display)},
                                   {"direct_only", p.directOnly}});
    j["tonemap"] = s.tonemap == Tonemapper::Aces ? "aces" : "linear";
    j["exposure"] = s.exposureEV;
    j["ambient"] = vec(s.ambient);
    j["shadows"] = s.shadows;
    j["background"] = s.background ? vec(*s.background) : ojson(nullptr);
    if (!s.environment.empty()) j["environment"] = s.environment;
    if (s.environmentRotation != 0.0f) j["environment_rotation"] = s.environmentRotation;
    j["max_bounces"] = s.maxBounces;
    j["render_scale"] = s.renderScale;
    j["frame_budget_ms"] = s.frameBudgetMs;
    j["heatmap_metric"] = errorMetricName(s.heatmapMetric);
    j["reference_spp"] = s.referenceSpp;
    const ViewCamera& c = s.camera;
    j["camera"] = ojson{{"scene_camera", c.sceneCamera},
                        {"free", c.free},
                        {"mode", c.mode == CameraMode::Orbit ? "orbit" : "fly"},
                        {"position", vec(c.position)},
                        {"yaw", c.yaw},
                        {"pitch", c.pitch},
                        {"distance", c.distance},
                        {"yfov", c.yfov},
                        {"znear", c.znear},
                        {"zfar", c.zfar},
                        {"speed", c.speed}};
    if (s.lightsEdited) {
        j["lights"] = ojson::array();
        for (const LightState& l : s.lights) {
            ojson e = lightToJson(l.light);
            e["enabled"] = l.enabled;
            j["lights"].push_back(e);
        }
    } else {
        j["lights"] = nullptr;  // the scene's own
    }
    j["brdf_plot"] = ojson{{"pane", s.plotPane},
                           {"base_color", vec(s.plotBaseColor)},
                           {"metallic", s.plotMetallic},
                           {"roughness", s.plotRoughness},
                           {"specular", s.plotSpecular},
                           {"view_angle", s.plotViewAngle},
                           {"log", s.plotLog}};
    return j;
}

namespace {

// Each reader below sets `key` to what it reads, so an error names it.

void readPane(const json& v, int p, ViewState& s, std::string& key) {
    const std::string prefix = "panes[" + std::to_string(p) + "]";
    // The method first: a new method resets the pane's preset and debug view, which the keys
    // after it (alphabetical, "display" before "gi") set for it.
    if (v.is_object() && v.contains("gi")) {
        key = prefix + ".gi";
        applyPanelAction(s, PanelAction::method(p, text(v["gi"], key)));
    }
    for (const auto& [pk, pv] : v.items()) {
        key = prefix + "." + pk;
        if (pk == "gi") continue;
        else if (pk == "preset") applyPanelAction(s, PanelAction::preset(p, text(pv, key)));
        else if (pk == "diffuse") applyPanelAction(s, PanelAction::diffuse(p, text(pv, key)));
        else if (pk == "specular") applyPanelAction(s, PanelAction::specular(p, text(pv, key)));
        else if (pk == "display") applyPanelAction(s, PanelAction::display(p, text(pv, key)));
        else if (pk == "params") {
            if (!pv.is_object()) throw Error("must be an object of \"method.key\": value");
            s.panes[p].params.clear();
            for (const auto& [name, value] : pv.items()) {
                key = prefix + ".params." + name;
                s.panes[p].params[name] = paramFromJson(name, value);
            }
        }
        else if (pk == "direct_only") applyPanelAction(s, PanelAction::directOnly(p, boolean(pv, key)));
        else throw Error("unknown key");
    }
}

void readPanes(const json& v, ViewState& s, std::string& key) {
    if (!v.is_array() || v.size() > size_t(kMaxPanes)) throw Error("'panes' must be an array of up to 4");
    for (size_t i = 0; i < v.size(); ++i) readPane(v[i], int(i), s, key);
}

void checkCamera(const ViewCamera& c) {
    if (c.sceneCamera < 0) throw Error("camera.scene_camera must be >= 0");
    if (!(c.distance > 0.0f)) throw Error("camera.distance must be > 0");
    if (!(c.yfov > 0.0f && c.yfov < 3.13f)) throw Error("camera.yfov must be in (0, 3.13) radians");
    if (!(c.znear > 0.0f)) throw Error("camera.znear must be > 0");
    if (c.zfar != 0.0f && !(c.zfar > c.znear)) throw Error("camera.zfar must be 0 (infinite) or > znear");
    if (std::abs(c.pitch) > 1.5708f) throw Error("camera.pitch must be in [-pi/2, pi/2]");
}

void readCamera(const json& v, ViewState& s, std::string& key) {
    if (!v.is_object()) throw Error("must be an object");
    ViewCamera& c = s.camera;
    for (const auto& [ck, cv] : v.items()) {
        key = "camera." + ck;
        if (ck == "scene_camera") c.sceneCamera = integer(cv, key);
        else if (ck == "free") c.free = boolean(cv, key);
        else if (ck == "mode") applyPanelAction(s, PanelAction::withText(PanelAction::SetCameraMode, text(cv, key)));
        else if (ck == "position") c.position = vec3(cv, key);
        else if (ck == "yaw") c.yaw = number(cv, key);
        else if (ck == "pitch") c.pitch = number(cv, key);
        else if (ck == "distance") c.distance = number(cv, key);
        else if (ck == "yfov") c.yfov = number(cv, key);
        else if (ck == "znear") c.znear = number(cv, key);
        else if (ck == "zfar") c.zfar = number(cv, key);
        else if (ck == "speed") c.speed = number(cv, key);
        else throw Error("unknown key");
    }
    // Each check names its own key: the loop above leaves `key` at the last one read.
    key = "camera";
    checkCamera(c);
}

void readLights(const json& v, ViewState& s, std::string& key) {
    if (v.is_null()) {
        s.lightsEdited = false;
        return;
    }
    if (!v.is_array()) throw Error("must be an array or null");
    s.lights.clear();
    for (size_t i = 0; i < v.size(); ++i) {
        key = "lights[" + std::to_string(i) + "]";
        LightState l{lightFromJson(v[i]), true};
        if (v[i].contains("enabled")) l.enabled = boolean(v[i]["enabled"], key + ".enabled");
        s.lights.push_back(l);
    }
    s.lightsEdited = true;
}

void readBrdfPlot(const json& v, ViewState& s, std::string& key) {
    if (!v.is_object()) throw Error("must be an object");
    PanelAction material = PanelAction::withVec(PanelAction::SetPlotMaterial, s.plotBaseColor);
    material.vec4 = glm::vec4(s.plotMetallic, s.plotRoughness, s.plotSpecular, 0.0f);
    for (const auto& [pk, pv] : v.items()) {
        key = "brdf_plot." + pk;
        if (pk == "pane") {
            applyPanelAction(s, PanelAction::withIndex(PanelAction::SetPlotPane, integer(pv, key)));
        } else if (pk == "base_color") material.vec = vec3(pv, key);
        else if (pk == "metallic") material.vec4.x = number(pv, key);
        else if (pk == "roughness") material.vec4.y = number(pv, key);
        else if (pk == "specular") material.vec4.z = number(pv, key);
        else if (pk == "view_angle") applyPanelAction(s, PanelAction::withValue(PanelAction::SetPlotViewAngle, number(pv, key)));
        else if (pk == "log") applyPanelAction(s, PanelAction::withFlag(PanelAction::SetPlotLog, boolean(pv, key)));
        else throw Error("unknown key");
    }
    applyPanelAction(s, material);
}

void readViewSize(const json& v, ViewState& s) {
    if (!v.is_array() || v.size() != 2) throw Error("'view_size' must be [width, height]");
    s.viewWidth = integer(v[0], "view_size");
    s.viewHeight = integer(v[1], "view_size");
    if (s.viewWidth < 1 || s.viewHeight < 1 || s.viewWidth > 16384 || s.viewHeight > 16384)
        throw Error("'view_size' is out of range (1..16384)");
}

PanelAction backgroundAction(const json& v) {
    if (v.is_null()) return PanelAction::withFlag(PanelAction::SetBackground, false);
    PanelAction a = PanelAction::withVec(PanelAction::SetBackground, vec3(v, "background"));
    a.flag = true;
    return a;
}

PanelAction environmentAction(const json& v) {
    if (!v.is_null() && !v.is_string()) throw Error("environment must be a file name or null");
    return PanelAction::withText(PanelAction::SetEnvironment, v.is_null() ? "" : v.get<std::string>());
}

// A top-level key whose value is one action's.
bool applyActionKey(const std::string& k, const json& v, ViewState& s) {
    PanelAction a;
    if (k == "mode") a = PanelAction::withText(PanelAction::SetMode, text(v, k));
    else if (k == "divider") a = PanelAction::dividerAt(number(v, k));
    else if (k == "tonemap") a = PanelAction::tonemapper(text(v, k));
    else if (k == "exposure") a = PanelAction::exposure(number(v, k));
    else if (k == "ambient") a = PanelAction::withVec(PanelAction::SetAmbient, vec3(v, k));
    else if (k == "shadows") a = PanelAction::withFlag(PanelAction::SetShadows, boolean(v, k));
    else if (k == "background") a = backgroundAction(v);
    else if (k == "environment") a = environmentAction(v);
    else if (k == "environment_rotation") a = PanelAction::withValue(PanelAction::SetEnvironmentRotation, number(v, k));
    else if (k == "max_bounces") a = PanelAction::withValue(PanelAction::SetMaxBounces, number(v, k));
    else if (k == "render_scale") a = PanelAction::withValue(PanelAction::SetRenderScale, number(v, k));
    else if (k == "frame_budget_ms") a = PanelAction::withValue(PanelAction::SetFrameBudget, number(v, k));
    else if (k == "reference_spp") a = PanelAction::withValue(PanelAction::SetReferenceSpp, number(v, k));
    else if (k == "heatmap_metric") a = PanelAction::withText(PanelAction::SetHeatmapMetric, text(v, k));
    else return false;
    applyPanelAction(s, a);
    return true;
}

void readKey(const std::string& k, const json& v, ViewState& s, std::string& key) {
    if (k == "gisandbox_view_settings") {
        if (integer(v, k) != kSettingsVersion)
            throw Error("version " + v.dump() + " is not supported (expected " + std::to_string(kSettingsVersion) + ")");
    } else if (k == "scene") {
        s.scene = text(v, k);
    } else if (k == "lighting") {
        s.lighting = lightingModeName(parseLightingMode(text(v, k)));
    } else if (k == "view_size") {
        readViewSize(v, s);
    } else if (k == "panes") {
        readPanes(v, s, key);
    } else if (k == "camera") {
        readCamera(v, s, key);
    } else if (k == "lights") {
        readLights(v, s, key);
    } else if (k == "brdf_plot") {
        readBrdfPlot(v, s, key);
    } else if (!applyActionKey(k, v, s)) {
        throw Error("unknown key");
    }
}

}  // namespace

void viewStateFromJson(const json& j, ViewState& state) {
    if (!j.is_object()) throw Error("settings must be a JSON object");
    ViewState s = state;
    std::string key;
    try {
        for (const auto& [k, v] : j.items()) {
            key = k;
            readKey(k, v, s, key);
        }
        for (int p = 0; p < kMaxPanes; ++p) {  // once the pane's method is known
            key = "panes[" + std::to_string(p) + "].display";
            checkPaneDisplay(s, p);
        }
    } catch (const Error& e) {
        throw Error("settings key '" + key + "': " + e.what());
    }
    state = std::move(s);
}

void saveViewSettings(const std::string& path, const ViewState& state) {
    const std::string text = viewStateToJson(state).dump(2) + "\n";
    writeFileAtomically(path, text);
}

ViewState loadViewSettings(const std::string& path) {
    const std::string text = readUserFile(path, kMaxUserTextBytes, "settings file");
    json j;
    try {
        j = parseUserJson(text);
    } catch (const json::exception& e) {
        throw Error(path + ": not valid JSON (" + std::string(e.what()) + ")");
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    // A screenshot's sidecar holds the settings under "settings", beside timings and the like.
    if (j.is_object() && !j.contains("gisandbox_view_settings") && j.contains("settings")) j = j["settings"];
    ViewState s;
    try {
        viewStateFromJson(j, s);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    return s;
}

ojson renderSettingsToJson(const RenderSettings& s) {
    // Every parameter of the method, defaults included, so a sidecar says what was rendered.
    ParamValues params;
    const GiMethod& m = giMethod(s.gi);
    for (const ParamDesc& d : m.params) {
        auto it = s.params.find(m.name + "." + d.key);
        params[m.name + "." + d.key] = it == s.params.end() ? d.defaultValue : it->second;
    }
    ojson j{{"width", s.width},
                 {"height", s.height},
                 {"camera", s.camera},
                 {"gi", s.gi},
                 {"params", paramsToJson(params)},
                 {"diffuse", diffuseModelName(s.diffuse)},
                 {"specular", specularModelName(s.specular)},
                 {"tonemap", s.tonemap == Tonemapper::Aces ? "aces" : "linear"},
                 {"exposure", s.exposureEV},
                 {"ambient", vec(s.ambient)},
                 {"shadow_map_size", s.shadowMapSize},
                 {"shadow_cube_size", s.shadowCubeSize},
                 {"shadows", s.shadows},
                 {"hdr32", s.hdr32},
                 {"background", s.background ? vec(*s.background) : ojson(nullptr)},
                 {"samples_per_frame", s.samplesPerFrame},
                 {"seed", s.seed},
                 {"view", s.view}};
    if (!s.environment.empty()) j["environment"] = s.environment;
    if (s.environmentRotation != 0.0f) j["environment_rotation"] = s.environmentRotation;
    return j;
}

}  // namespace gis::view
