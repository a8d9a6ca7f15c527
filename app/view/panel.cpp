#include "view/panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "brdf_cpu.h"
#include "gi/method.h"

namespace gis::view {

namespace {

// Greyed text wrapped at the panel's edge (TextDisabled cuts a long line off).
void greyWrapped(const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
}

constexpr float kDegrees = 57.29577951308232f;

// A combo over names; calls `choose` with the one picked.
template <typename F>
void combo(const char* label, const std::string& current, const std::vector<std::string>& names, F choose) {
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (const std::string& n : names) {
            const bool selected = n == current;
            if (ImGui::Selectable(n.c_str(), selected)) choose(n);
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
}

const char* paneTitle(ViewMode mode, int i) {
    static const char* const split[] = {"Left pane", "Right pane"};
    static const char* const grid[] = {"Top-left pane", "Top-right pane", "Bottom-left pane", "Bottom-right pane"};
    if (mode == ViewMode::Single) return "Pane";
    return mode == ViewMode::Split ? split[i] : grid[i];
}

double mib(int64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

// A parameter row's label in the panel: a rebuild row is marked.
std::string paramLabel(const ParamDesc& d) { return d.label + (d.update == ParamUpdate::Rebuild ? " *" : ""); }

// The panel's own labels ("Reference spp", "Tone mapper", ...) fit in this many pixels (the panel test
// checks that no row runs past the panel's edge).
constexpr float kOwnLabelColumn = 130.0f;

// The width kept right of the widgets for their labels: the widest label of the parameter rows the
// panes show, and the panel's own, so no label runs past the panel's edge (#42 item 11).
float labelColumn(const PanelContext& ctx) {
    float widest = 0.0f;
    for (int i = 0; i < paneCount(ctx.state.mode); ++i)
        for (const ParamTableView& table : paneParamTables(ctx.state.panes[i]))
            for (const ParamDesc& d : *table.params)
                widest = std::max(widest, ImGui::CalcTextSize(paramLabel(d).c_str()).x);
    return std::max(kOwnLabelColumn, widest + ImGui::GetStyle().ItemInnerSpacing.x);
}

// One widget per row of a parameter table the pane reads (its method's, the shared emitters.*),
// with the row's range; a change is a SetParam action (live rows never rebuild the pane's renderer).
void paramTableControls(PanelContext& ctx, int pane, const ParamTableView& table) {
    const PaneState& p = ctx.state.panes[pane];
    const std::string prefix = table.name + ".";
    const bool edited = std::any_of(p.params.begin(), p.params.end(),
                                    [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
    if (!ImGui::TreeNode(table.name.c_str(), "Parameters: %s (%zu)%s", table.name.c_str(), table.params->size(),
                         edited ? " *" : ""))
        return;
    for (const ParamDesc& d : *table.params) {
        const std::string key = prefix + d.key;
        const ParamValue v = paneParam(ctx.state, pane, table.name, d);
        auto set = [&](const ParamValue& nv) { act(ctx, PanelAction::param(pane, key, formatParamValue(d, nv))); };
        const std::string label = paramLabel(d);
        ParamValue nv = v;
        switch (d.type) {
            case ParamType::Int: {
                int x = int(v.number);
                const bool wide = d.max - d.min > 4096;
                if (wide ? ImGui::DragInt(label.c_str(), &x, 1.0f, int(d.min), int(d.max))
                         : ImGui::SliderInt(label.c_str(), &x, int(d.min), int(d.max))) {
                    nv.number = std::clamp(double(x), d.min, d.max);
                    set(nv);
                }
                break;
            }
            case ParamType::Float: {
                float x = float(v.number);
                if (ImGui::DragFloat(label.c_str(), &x, float(std::max(std::abs(v.number), 1e-3) * 0.01), float(d.min),
                                     float(std::min(d.max, 3e38)), "%.4g")) {
                    nv.number = std::clamp(double(x), d.min, d.max);
                    set(nv);
                }
                break;
            }
            case ParamType::Bool: {
                bool x = v.number != 0;
                if (ImGui::Checkbox(label.c_str(), &x)) {
                    nv.number = x ? 1 : 0;
                    set(nv);
                }
                break;
            }
            case ParamType::Choice:
                combo(label.c_str(), v.text, d.choices, [&](const std::string& n) {
                    nv.text = n;
                    set(nv);
                });
                break;
            case ParamType::Colour: {
                glm::vec3 c = v.colour;
                if (ImGui::ColorEdit3(label.c_str(), &c[0], ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) {
                    nv.colour = glm::clamp(c, glm::vec3(0.0f), glm::vec3(float(d.max)));
                    set(nv);
                }
                break;
            }
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s = %s\n%s\nrange %s, default %s%s", key.c_str(), formatParamValue(d, v).c_str(),
                              d.help.c_str(), describeParamRange(d).c_str(), formatParamValue(d, d.defaultValue).c_str(),
                              d.update == ParamUpdate::Rebuild ? "\n* rebuilds the pane's renderer" : "");
    }
    ImGui::TreePop();
}

void paramControls(PanelContext& ctx, int pane) {
    for (const ParamTableView& table : paneParamTables(ctx.state.panes[pane])) paramTableControls(ctx, pane, table);
    if (!ctx.state.panes[pane].params.empty() && ImGui::Button("Reset to preset"))
        act(ctx, PanelAction::withIndex(PanelAction::ResetParams, pane));
}

void paneControls(PanelContext& ctx, int i) {
    ViewState& s = ctx.state;
    const PaneState& p = s.panes[i];
    ImGui::PushID(i);
    combo("GI method", p.gi, methodChoices(), [&](const std::string& n) { act(ctx, PanelAction::method(i, n)); });
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", giMethod(p.gi).summary.c_str());
    std::vector<std::string> presets;
    for (const GiPreset& preset : giMethod(p.gi).presets) presets.push_back(preset.name);
    combo("Preset", p.preset, presets, [&](const std::string& n) { act(ctx, PanelAction::preset(i, n)); });
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", giMethod(p.gi).preset(p.preset).description.c_str());
    paramControls(ctx, i);
    std::vector<std::string> diffuse, specular;
    for (const DiffuseModelInfo& m : diffuseModels()) diffuse.push_back(m.name);
    for (const SpecularModelInfo& m : specularModels()) specular.push_back(m.name);
    combo("Diffuse BRDF", diffuseModelName(p.diffuse), diffuse,
          [&](const std::string& n) { act(ctx, PanelAction::diffuse(i, n)); });
    combo("Specular BRDF", specularModelName(p.specular), specular,
          [&](const std::string& n) { act(ctx, PanelAction::specular(i, n)); });
    const PaneView& view = ctx.session.pane(i);
    const std::vector<std::string> displays =
        displayChoices(view.renderer ? view.renderer->views() : std::vector<DebugViewDesc>{});
    combo("Display", p.display == PaneDisplay::Method ? p.methodView : paneDisplayName(p.display), displays,
          [&](const std::string& n) { act(ctx, PanelAction::display(i, n)); });
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("lit image, error heatmap against the path-traced reference, a G-buffer channel, or a "
                          "debug view of the method's passes");
    bool direct = p.directOnly;
    if (ImGui::Checkbox("Direct light only", &direct)) act(ctx, PanelAction::directOnly(i, direct));
    const PaneView& pv = ctx.session.pane(i);
    if (pv.fullFrameMs > 0.0) {
        char line[160];
        std::snprintf(line, sizeof line, "render scale in use %s: a full frame %.0f ms, budget %.0f ms",
                      scaleLabel(pv.scale).c_str(), pv.fullFrameMs, ctx.session.frameBudgetMs(ctx.state));
        greyWrapped(line);
    }
    if (!pv.status.empty()) greyWrapped(pv.status);
    if (pv.heatmapReady) {
        ImGui::Text("%s vs reference: %s", pv.metricName.c_str(), formatPaneMetric(pv.metricValue).c_str());
        ImGui::Text("colour bar (pane's bottom): 0 to %s", formatMetric(pv.heatmapMax, 3).c_str());
    }
    ImGui::PopID();
}

// An action on light `index`.
PanelAction ofLight(int index, PanelAction a) {
    a.index = index;
    return a;
}

void lightControls(PanelContext& ctx) {
    ViewState& s = ctx.state;
    static const char* const types[] = {"directional", "point", "spot"};
    for (int i = 0; i < int(s.lights.size()); ++i) {
        const LightState l = s.lights[i];
        ImGui::PushID(1000 + i);
        bool on = l.enabled;
        if (ImGui::Checkbox("##on", &on))
            act(ctx, ofLight(i, PanelAction::withFlag(PanelAction::SetLightEnabled, on)));
        ImGui::SameLine();
        const std::string title = std::to_string(i) + ": " + types[int(l.light.type)] + " " + l.light.name;
        if (ImGui::TreeNode("light", "%s", title.c_str())) {
            float intensity = l.light.intensity;
            if (ImGui::DragFloat("Intensity", &intensity, 0.01f * std::max(intensity, 0.1f), 0.0f, 1e6f, "%.3f"))
                act(ctx, ofLight(i, PanelAction::withValue(PanelAction::SetLightIntensity, std::max(intensity, 0.0f))));
            glm::vec3 color = l.light.color;
            if (ImGui::ColorEdit3("Colour", &color[0], ImGuiColorEditFlags_Float))
                act(ctx, ofLight(i, PanelAction::withVec(PanelAction::SetLightColor, glm::max(color, glm::vec3(0.0f)))));
            if (l.light.type != LightType::Directional) {
                glm::vec3 pos = l.light.position;
                if (ImGui::DragFloat3("Position", &pos[0], 0.01f * std::max(ctx.state.camera.speed, 1e-3f)))
                    act(ctx, ofLight(i, PanelAction::withVec(PanelAction::SetLightPosition, pos)));
            }
            if (l.light.type != LightType::Point) {
                glm::vec3 dir = l.light.direction;
                if (ImGui::DragFloat3("Direction", &dir[0], 0.01f, -1.0f, 1.0f) && glm::length(dir) > 1e-4f)
                    act(ctx, ofLight(i, PanelAction::withVec(PanelAction::SetLightDirection, dir)));
            }
            if (ImGui::Button("Remove"))
                act(ctx, PanelAction::withIndex(PanelAction::RemoveLight, i));
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    for (const char* type : {"point", "spot", "directional"}) {
        const std::string label = std::string("Add ") + type;
        if (ImGui::Button(label.c_str()))
            act(ctx, PanelAction::withText(PanelAction::AddLight, type));
        ImGui::SameLine();
    }
    if (ImGui::Button("Reset"))
        act(ctx, PanelAction::of(PanelAction::ResetLights));
    if (s.lightsEdited) ImGui::TextDisabled("edited: saved in settings files");
}

void timingControls(PanelContext& ctx) {
    const ViewSession& session = ctx.session;
    const FrameTimes& t = ctx.times;
    ImGui::Text("frame %.1f ms = GPU passes %.1f + CPU and waits %.1f", t.frameMs, t.gpuMs,
                std::max(0.0f, t.frameMs - t.gpuMs));
    greyWrapped("on " + ctx.glRenderer + "; a settled view renders nothing");
    ImGui::Text("GPU memory, all panes and references: %.2f MiB", mib(session.gpuBytes()));
    for (int i = 0; i < session.visiblePanes(); ++i) {
        const PaneView& p = session.pane(i);
        ImGui::PushID(2000 + i);
        ImGui::Separator();
        ImGui::Text("%s: %s", paneTitle(ctx.state.mode, i), paneLabel(ctx.state, i).c_str());
        std::vector<float> total(p.totalMs.begin(), p.totalMs.end());
        float peak = 0.0f;
        for (float v : total) peak = std::max(peak, v);
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "GPU %.2f ms", total.empty() ? 0.0f : total.back());
        ImGui::PlotLines("##gpu", total.data(), int(total.size()), 0, overlay, 0.0f, std::max(peak * 1.15f, 0.1f),
                         ImVec2(ImGui::GetContentRegionAvail().x, 56.0f));
        if (ImGui::BeginTable("passes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
            ImGui::TableSetupColumn("pass");
            ImGui::TableSetupColumn("ms (last)");
            ImGui::TableSetupColumn("ms (median)");
            ImGui::TableSetupColumn("MiB");
            ImGui::TableHeadersRow();
            int64_t bytes = 0;
            for (const PassHistory& h : p.passes) {
                std::deque<float> sorted = h.ms;
                std::sort(sorted.begin(), sorted.end());
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%s%s", h.pass.c_str(), h.cached ? " (cached)" : "");
                ImGui::TableNextColumn();
                ImGui::Text("%.3f", h.ms.empty() ? 0.0f : h.ms.back());
                ImGui::TableNextColumn();
                ImGui::Text("%.3f", sorted.empty() ? 0.0f : sorted[sorted.size() / 2]);
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", mib(h.bytes));
                bytes += h.bytes;
            }
            if (p.renderer) {
                const auto& owners = p.renderer->memory().bytesByOwner;
                auto it = owners.find("scene");
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted("scene");
                ImGui::TableNextColumn();
                ImGui::TableNextColumn();
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", mib(it == owners.end() ? 0 : it->second));
            }
            ImGui::EndTable();
        }
        if (p.renderer)  // what the method built: voxel size, probe count and storage
            for (const auto& pass : p.renderer->passes())
                for (const std::string& line : pass->stats()) ImGui::TextWrapped("%s: %s", pass->name(), line.c_str());
        ImGui::PopID();
    }
}

// The BRDF of the chosen pane in the plane of incidence, as the CPU table evaluates it.
void lobePlot(PanelContext& ctx) {
    ViewState& s = ctx.state;
    if (s.mode != ViewMode::Single) {
        int pane = std::min(s.plotPane, paneCount(s.mode) - 1);
        if (ImGui::SliderInt("Pane", &pane, 0, paneCount(s.mode) - 1))
            act(ctx, PanelAction::withIndex(PanelAction::SetPlotPane, pane));
    }
    const int pane = s.mode == ViewMode::Single ? 0 : std::min(s.plotPane, paneCount(s.mode) - 1);
    const PaneState& p = s.panes[pane];
    glm::vec3 base = s.plotBaseColor;
    glm::vec4 params(s.plotMetallic, s.plotRoughness, s.plotSpecular, 0.0f);
    bool changed = ImGui::ColorEdit3("Base colour", &base[0]);
    changed |= ImGui::SliderFloat("Metallic", &params.x, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("Roughness", &params.y, 0.0f, 1.0f);
    changed |= ImGui::SliderFloat("Specular", &params.z, 0.0f, 1.0f);
    if (changed) {
        PanelAction a;
        a.kind = PanelAction::SetPlotMaterial;
        a.vec = base;
        a.vec4 = params;
        act(ctx, a);
    }
    float view = s.plotViewAngle * kDegrees;
    if (ImGui::SliderFloat("View angle", &view, 0.0f, 89.0f, "%.0f deg"))
        act(ctx, PanelAction::withValue(PanelAction::SetPlotViewAngle, view / kDegrees));
    bool logScale = s.plotLog;
    if (ImGui::Checkbox("Log scale (3 decades)", &logScale))
        act(ctx, PanelAction::withFlag(PanelAction::SetPlotLog, logScale));

    const CpuSurfaceBrdf surface = makeCpuSurfaceBrdf(s.plotBaseColor, s.plotMetallic, s.plotRoughness, s.plotSpecular);
    const std::vector<LobeSample> lobe = brdfLobe(surface, s.plotViewAngle, p.diffuse, p.specular);
    auto lum = [](glm::vec3 c) { return (c.r + c.g + c.b) / 3.0f; };
    float peak = 0.0f;
    for (const LobeSample& l : lobe) peak = std::max(peak, lum(l.diffuse + l.specular));
    const float width = ImGui::GetContentRegionAvail().x, height = std::min(width * 0.55f, 220.0f);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("lobe", ImVec2(width, height));
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 centre(origin.x + width * 0.5f, origin.y + height - 16.0f);
    const float radius = std::min(width * 0.5f, height - 20.0f) - 4.0f;
    dl->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height), IM_COL32(20, 20, 24, 255));
    for (float f : {1.0f, 0.5f}) dl->PathArcTo(centre, radius * f, -3.14159265f, 0.0f, 48), dl->PathStroke(IM_COL32(70, 70, 80, 255), 0, 1.0f);
    dl->AddLine(ImVec2(centre.x - radius, centre.y), ImVec2(centre.x + radius, centre.y), IM_COL32(110, 110, 120, 255));
    dl->AddLine(centre, ImVec2(centre.x, centre.y - radius), IM_COL32(110, 110, 120, 255));  // N
    const float va = s.plotViewAngle;
    dl->AddLine(centre, ImVec2(centre.x - radius * std::sin(va), centre.y - radius * std::cos(va)),
                IM_COL32(120, 220, 120, 255), 2.0f);  // towards the viewer
    auto toRadius = [&](float v) {
        if (peak <= 0.0f) return 0.0f;
        if (!s.plotLog) return radius * v / peak;
        const float lo = peak * 1e-3f;
        return v <= lo ? 0.0f : radius * std::log10(v / lo) / 3.0f;
    };
    auto curve = [&](auto value, ImU32 colour, float thickness) {
        std::vector<ImVec2> pts;
        for (const LobeSample& l : lobe) {
            const float r = toRadius(value(l));
            pts.emplace_back(centre.x + r * std::sin(l.angle), centre.y - r * std::cos(l.angle));
        }
        dl->AddPolyline(pts.data(), int(pts.size()), colour, 0, thickness);
    };
    curve([&](const LobeSample& l) { return lum(l.diffuse); }, IM_COL32(90, 160, 255, 255), 1.5f);
    curve([&](const LobeSample& l) { return lum(l.specular); }, IM_COL32(255, 160, 60, 255), 1.5f);
    curve([&](const LobeSample& l) { return lum(l.diffuse + l.specular); }, IM_COL32(240, 240, 240, 255), 2.0f);
    dl->AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(200, 200, 200, 255),
                (std::string(diffuseModelName(p.diffuse)) + " + " + specularModelName(p.specular)).c_str());
    char buf[64];
    std::snprintf(buf, sizeof buf, "peak f*cos %.3g /sr", peak);
    dl->AddText(ImVec2(origin.x + 4, origin.y + 18), IM_COL32(200, 200, 200, 255), buf);
    ImGui::TextDisabled("white: total, blue: diffuse, orange: specular; green: view");
}

}  // namespace

void act(PanelContext& ctx, const PanelAction& action) {
    try {
        applyPanelAction(ctx.state, action);
    } catch (const Error& e) {
        ctx.message = e.what();
    }
}

namespace {

void messageLines(PanelContext& ctx) {
    if (!ctx.session.lastError().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 110, 100, 255));
        ImGui::TextWrapped("%s", ctx.session.lastError().c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("Dismiss")) ctx.session.clearError();
    }
    if (!ctx.message.empty()) ImGui::TextWrapped("%s", ctx.message.c_str());
}

void sceneControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    const Scene& scene = ctx.session.scene();
    // Wrapped, and the path's tail when it is long: a deep path must not push the counts off the panel.
    const std::string shown = s.scene.size() > 48 ? "..." + s.scene.substr(s.scene.size() - 45) : s.scene;
    ImGui::TextWrapped("%s: %zu triangles, %zu lights", shown.c_str(), scene.triangleCount(), scene.lights.size());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.scene.c_str());
    ImGui::InputText("##scene", &ctx.scenePath);
    ImGui::SameLine();
    if (ImGui::Button("Open")) {
        if (ctx.session.openScene(ctx.state, ctx.scenePath)) ctx.message = "opened " + ctx.scenePath;
    }
    ImGui::TextDisabled("or drop a .gltf/.glb on the window");
}

void cameraControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    int cam = int(s.camera.mode);
    bool camChanged = ImGui::RadioButton("Orbit", &cam, 0);
    ImGui::SameLine();
    camChanged |= ImGui::RadioButton("Fly", &cam, 1);
    if (camChanged) act(ctx, PanelAction::withText(PanelAction::SetCameraMode, cam == 0 ? "orbit" : "fly"));
    ImGui::SameLine();
    if (ImGui::Button("Reset camera")) act(ctx, PanelAction::of(PanelAction::ResetCamera));
    ImGui::TextDisabled(s.camera.mode == CameraMode::Orbit
                            ? "left drag: orbit, right/middle drag: pan, wheel: zoom"
                            : "WASD/QE: move (shift: x4), drag: look, wheel: speed");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("F: orbit/fly, R: reset, 1/2/3: single/split/grid, B: swap the split's sides (A/B), I: pixel inspector, F12: screenshot");
    ImGui::PopStyleColor();
}

void viewControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    int mode = int(s.mode);
    bool changed = ImGui::RadioButton("Single", &mode, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("Split", &mode, 1);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("2x2 grid", &mode, 2);
    if (changed) act(ctx, PanelAction::viewMode(ViewMode(mode)));
    if (s.mode == ViewMode::Split) {
        float divider = s.divider;
        if (ImGui::SliderFloat("Divider", &divider, 0.02f, 0.98f)) act(ctx, PanelAction::dividerAt(divider));
    }
    float scale = s.renderScale;
    if (ImGui::SliderFloat("Render scale", &scale, 0.125f, 1.0f, "%.3f"))
        act(ctx, PanelAction::withValue(PanelAction::SetRenderScale, scale));
    float budget = s.frameBudgetMs;
    if (ImGui::InputFloat("Frame budget ms", &budget, 0.0f, 0.0f, "%.0f", ImGuiInputTextFlags_EnterReturnsTrue))
        act(ctx, PanelAction::withValue(PanelAction::SetFrameBudget, budget));
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("a pane whose full frame takes longer renders at a lower scale while its camera moves or its "
                          "method converges, and climbs back to full scale when the view settles (0: %.0f ms here)",
                          defaultFrameBudgetMs(ctx.glRenderer));
    cameraControls(ctx);
}

// The environment map (render's --environment): the path in the field, applied by Load.
void environmentControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    ImGui::TextWrapped("Environment: %s", s.environment.empty() ? "constant (background / scene sky)"
                                                                : s.environment.c_str());
    ImGui::InputText("##environment", &ctx.environmentPath);
    ImGui::SameLine();
    if (ImGui::Button("Load")) act(ctx, PanelAction::withText(PanelAction::SetEnvironment, ctx.environmentPath));
    ImGui::SameLine();
    if (ImGui::Button("Off")) act(ctx, PanelAction::of(PanelAction::SetEnvironment));
    if (s.environment.empty()) return;  // a rotation needs a map to turn
    // Applied on Enter or a step, not while dragging: a new rotation rebuilds the renderers
    // (requiresRebuild), as a new map does.
    float degrees = s.environmentRotation;
    if (ImGui::InputFloat("Rotation (deg, +Y)", &degrees, 15.0f, 90.0f, "%.1f", ImGuiInputTextFlags_EnterReturnsTrue))
        act(ctx, PanelAction::withValue(PanelAction::SetEnvironmentRotation, degrees));
}

// The heatmap's metric and the path tracer's own controls, apart from the methods' bounce
// parameters (vct.bounces is in its pane).
void referenceControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    // Ranges from the reference's parameter rows, the one place they are declared.
    const ParamDesc& bouncesRow = *methodInRole(MethodRole::Reference).param("bounces");
    const ParamDesc& sppRow = *methodInRole(MethodRole::Reference).param("spp");
    combo("Heatmap metric", errorMetricName(s.heatmapMetric), {"flip", "rmse", "relmse", "ssim"},
          [&](const std::string& n) { act(ctx, PanelAction::withText(PanelAction::SetHeatmapMetric, n)); });
    ImGui::Separator();
    ImGui::TextDisabled("Path tracer and reference");
    int bounces = s.maxBounces;
    if (ImGui::DragInt("Bounces", &bounces, 0.2f, int(bouncesRow.min), int(bouncesRow.max)))
        act(ctx, PanelAction::withValue(PanelAction::SetMaxBounces, float(bounces)));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("path tracer: %s", bouncesRow.help.c_str());
    int spp = s.referenceSpp;
    if (ImGui::InputInt("Reference spp", &spp, 16, 64, ImGuiInputTextFlags_EnterReturnsTrue))
        act(ctx, PanelAction::withValue(PanelAction::SetReferenceSpp, float(std::clamp(spp, int(sppRow.min), int(sppRow.max)))));
}

void displayControls(PanelContext& ctx) {
    const ViewState& s = ctx.state;
    combo("Tone mapper", s.tonemap == Tonemapper::Aces ? "aces" : "linear", {"aces", "linear"},
          [&](const std::string& n) { act(ctx, PanelAction::tonemapper(n)); });
    float ev = s.exposureEV;
    if (ImGui::SliderFloat("Exposure (EV)", &ev, -10.0f, 10.0f, "%.2f")) act(ctx, PanelAction::exposure(ev));
    glm::vec3 ambient = s.ambient;
    if (ImGui::ColorEdit3("Ambient (none)", &ambient[0], ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
        act(ctx, PanelAction::withVec(PanelAction::SetAmbient, glm::max(ambient, glm::vec3(0.0f))));
    environmentControls(ctx);
    bool shadows = s.shadows;
    if (ImGui::Checkbox("Shadows", &shadows)) act(ctx, PanelAction::withFlag(PanelAction::SetShadows, shadows));
    referenceControls(ctx);
}

void settingsControls(PanelContext& ctx) {
    ImGui::InputText("##settings", &ctx.settingsPath);
    ImGui::SameLine();
    if (ImGui::Button("Save")) {
        if (ctx.session.saveSettings(ctx.state, ctx.settingsPath)) ctx.message = "saved " + ctx.settingsPath;
    }
    ImGui::SameLine();
    if (ImGui::Button("Load")) {
        if (ctx.session.loadSettings(ctx.state, ctx.settingsPath)) ctx.message = "loaded " + ctx.settingsPath;
    }
    if (ImGui::Button("Screenshot (F12)")) ctx.screenshotRequested = true;
}

// A collapsing section of the panel, its header's top recorded (PanelContext::sectionTops).
bool section(PanelContext& ctx, const char* title, ImGuiTreeNodeFlags flags = 0) {
    ctx.sectionTops.emplace_back(title, ImGui::GetCursorScreenPos().y);
    return ImGui::CollapsingHeader(title, flags);
}

}  // namespace

void drawPanel(PanelContext& ctx, float x, float y, float width, float height) {
    ImGui::SetNextWindowPos(ImVec2(x, y));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("gisandbox", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                     ImGuiWindowFlags_NoSavedSettings);
    ImGui::PushItemWidth(-labelColumn(ctx));
    ctx.sectionTops.clear();
    messageLines(ctx);
    const ImGuiTreeNodeFlags open = ImGuiTreeNodeFlags_DefaultOpen;
    if (section(ctx, "Scene", open)) sceneControls(ctx);
    if (section(ctx, "View", open)) viewControls(ctx);
    // A single pane's section starts open; with two or four they start closed (their titles differ
    // per mode), or they would push the timings below a 720-pixel window.
    const ImGuiTreeNodeFlags paneOpen = ctx.state.mode == ViewMode::Single ? open : 0;
    for (int i = 0; i < paneCount(ctx.state.mode); ++i)
        if (section(ctx, paneTitle(ctx.state.mode, i), paneOpen)) paneControls(ctx, i);
    // Right after the panes it times, so it is on screen at the default 720-pixel height.
    if (section(ctx, "Timings and memory", open)) timingControls(ctx);
    if (section(ctx, "Display and lighting", open)) displayControls(ctx);
    if (section(ctx, "Lights")) lightControls(ctx);
    if (section(ctx, "BRDF lobe")) lobePlot(ctx);
    if (section(ctx, "Settings and screenshots", open)) settingsControls(ctx);
    ImGui::PopItemWidth();
    ImGui::End();
}

void drawPixelInspector(const ViewState& state, const ViewSession& session, float mx, float my, float w, float h) {
    if (mx < 0.0f || my < 0.0f || mx >= w || my >= h || session.visiblePanes() == 0) return;
    // Which panes sit under the cursor (both halves of a split: they share a frame), and where in
    // each pane's render pixels (the render scale may make those fewer than window pixels).
    const std::vector<PaneRect> rects = paneRects(state.mode, int(w), int(h));
    const glm::ivec2 size = session.paneSize();
    std::string text;
    for (int i = 0; i < session.visiblePanes() && i < int(rects.size()); ++i) {
        const PaneRect& r = rects[size_t(i)];
        if (mx < float(r.x) || my < float(r.y) || mx >= float(r.x + r.w) || my >= float(r.y + r.h)) continue;
        const glm::ivec2 pixel(int((mx - float(r.x)) / float(r.w) * float(size.x)),
                               int((my - float(r.y)) / float(r.h) * float(size.y)));
        const auto readout = session.inspectPixel(state, i, pixel);
        if (!readout) continue;
        char line[256];
        const glm::vec3 c = readout->radiance;
        std::snprintf(line, sizeof line, "%s  (%d, %d)\n  radiance   %.4f %.4f %.4f\n", paneLabel(state, i).c_str(),
                      pixel.x, pixel.y, c.r, c.g, c.b);
        text += line;
        if (readout->hasReference) {
            const glm::vec3 ref = readout->reference, err = c - ref;
            std::snprintf(line, sizeof line, "  reference  %.4f %.4f %.4f\n  error      %+.4f %+.4f %+.4f\n", ref.r, ref.g,
                          ref.b, err.r, err.g, err.b);
            text += line;
        } else {
            text += "  reference  (shown once a heatmap's reference has converged)\n";
        }
    }
    if (!text.empty()) ImGui::SetTooltip("%s", text.c_str());
}

void drawViewOverlay(const ViewState& state, const ViewSession& session, float x, float y, float w, float h) {
    ImDrawList* dl = ImGui::GetBackgroundDrawList();
    auto label = [&](int pane, float lx, float ly, bool alignRight) {
        std::string text = paneLabel(state, pane);
        const PaneView& p = session.pane(pane);
        if (!p.status.empty()) text += "  " + p.status;
        if (p.heatmapReady) text += "  " + p.metricName + " " + formatPaneMetric(p.metricValue);
        const ImVec2 size = ImGui::CalcTextSize(text.c_str());
        const float x0 = alignRight ? lx - size.x - 8.0f : lx;
        dl->AddRectFilled(ImVec2(x0, ly), ImVec2(x0 + size.x + 8.0f, ly + size.y + 4.0f), IM_COL32(0, 0, 0, 170));
        dl->AddText(ImVec2(x0 + 4.0f, ly + 2.0f), IM_COL32(255, 255, 255, 255), text.c_str());
    };
    const int count = session.visiblePanes();
    if (count == 0) return;
    if (state.mode == ViewMode::Split && count == 2) {
        const float dx = x + std::round(state.divider * w);
        dl->AddLine(ImVec2(dx, y), ImVec2(dx, y + h), IM_COL32(255, 255, 255, 230), 2.0f);
        dl->AddCircleFilled(ImVec2(dx, y + h * 0.5f), 7.0f, IM_COL32(255, 255, 255, 230));
        label(0, x, y, false);
        label(1, x + w, y, true);
    } else if (state.mode == ViewMode::Grid) {
        const std::vector<PaneRect> rects = paneRects(ViewMode::Grid, int(w), int(h));
        for (int i = 0; i < count; ++i) label(i, x + rects[i].x, y + rects[i].y, false);
    } else {
        label(0, x, y, false);
    }
}

}  // namespace gis::view
