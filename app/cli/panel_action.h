// Actions: every change to a ViewState. The panel's widgets, the keys, the mouse, script lines and
// settings files build one and call applyPanelAction, so what the widgets do is testable without a
// window. No GL here.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cli/view_state.h"

namespace gis::view {

// Every action, declared once; this table makes the enum, the script parser and the applier.
// Columns: the kind; what it edits (the pane or the light `index` names, else the view); the
// words that name it on a script line ('#': any word, the light's index; 'a|b': either word);
// its usage, the help a wrong line prints (docs/viewer.md lists them too); how its arguments
// are read (panel_action.cpp); how it changes the state. A line takes the first row whose
// words it starts with.
#define GIS_PANEL_ACTIONS(X)                                                                                            \
    X(SetMethod, Pane, "method", "method PANE NAME (gisandbox methods)", readPaneText, applyMethod)                     \
    X(SetPreset, Pane, "preset", "preset PANE low|medium|high", readPaneText, applyPreset)                              \
    X(SetDiffuse, Pane, "diffuse", "diffuse PANE NAME", readPaneText, applyDiffuse)                                     \
    X(SetSpecular, Pane, "specular", "specular PANE NAME", readPaneText, applySpecular)                                 \
    X(SetDisplay, Pane, "display", "display PANE lit|heatmap|depth|normal|basecolor|material|emissive|ao|VIEW",         \
      readPaneText, applyDisplay)                                                                                       \
    X(SetDirectOnly, Pane, "direct-only", "direct-only PANE on|off", readPaneFlag, applyDirectOnly)                     \
    X(SetParam, Pane, "set", "set PANE METHOD.KEY VALUE", readParam, applyParam)                                        \
    X(ResetParams, Pane, "reset-params", "reset-params PANE", readIndex, applyResetParams)                              \
    X(SetMode, View, "mode", "mode single|split|grid", readText, applyMode)                                             \
    X(SetDivider, View, "divider", "divider FRACTION", readNumber, applyDivider)                                        \
    X(SetExposure, View, "exposure", "exposure EV", readNumber, applyExposure)                                          \
    X(SetTonemap, View, "tonemap", "tonemap aces|linear", readText, applyTonemap)                                       \
    X(SetAmbient, View, "ambient", "ambient V | ambient R G B", readAmbient, applyAmbient)                              \
    X(SetShadows, View, "shadows", "shadows on|off", readFlag, applyShadows)                                            \
    X(SetBackground, View, "background", "background R G B | background off", readBackground, applyBackground)          \
    X(SetEnvironment, View, "environment", "environment FILE.hdr | environment off", readEnvironment, applyEnvironment) \
    X(SetEnvironmentRotation, View, "environment-rotation", "environment-rotation DEGREES (about +Y)", readNumber,    \
      applyEnvironmentRotation)                                                                                       \
    X(SetMaxBounces, View, "max-bounces", "max-bounces N", readNumber, applyMaxBounces)                                 \
    X(SetRenderScale, View, "render-scale", "render-scale S", readNumber, applyRenderScale)                             \
    X(SetFrameBudget, View, "frame-budget", "frame-budget MS (0: the renderer's default)", readNumber, applyFrameBudget) \
    X(SetHeatmapMetric, View, "metric", "metric flip|rmse|relmse|ssim", readText, applyHeatmapMetric)                   \
    X(SetReferenceSpp, View, "reference-spp", "reference-spp N", readNumber, applyReferenceSpp)                         \
    X(SetCameraMode, View, "camera mode", "camera mode orbit|fly", readText, applyCameraMode)                           \
    X(OrbitCamera, View, "camera orbit", "camera orbit DYAW DPITCH (degrees)", readTurn, applyOrbit)                    \
    X(PanCamera, View, "camera pan", "camera pan DX DY (fractions of the orbit distance)", readPair, applyPan)          \
    X(ZoomCamera, View, "camera zoom", "camera zoom FACTOR", readNumber, applyZoom)                                     \
    X(MoveCamera, View, "camera move", "camera move RIGHT UP FORWARD (scene units)", readVec3, applyMove)               \
    X(LookCamera, View, "camera look", "camera look DYAW DPITCH (degrees)", readTurn, applyLook)                        \
    X(ResetCamera, View, "camera reset", "camera reset", readNothing, applyResetCamera)                                 \
    X(AddLight, View, "light add", "light add point|spot|directional", readText, applyAddLight)                         \
    X(RemoveLight, Light, "light remove", "light remove I", readIndex, applyRemoveLight)                                \
    X(SetLightEnabled, Light, "light # on|off", "light I on|off", readLightSwitch, applyLightEnabled)                   \
    X(SetLightIntensity, Light, "light # intensity", "light I intensity V", readLightNumber, applyLightIntensity)       \
    X(SetLightColor, Light, "light # color", "light I color R G B", readLightVec3, applyLightColor)                     \
    X(SetLightPosition, Light, "light # position", "light I position X Y Z", readLightVec3, applyLightPosition)         \
    X(SetLightDirection, Light, "light # direction", "light I direction X Y Z", readLightVec3, applyLightDirection)     \
    X(ResetLights, View, "lights reset", "lights reset", readNothing, applyResetLights)                                 \
    X(SetPlotPane, View, "plot pane", "plot pane P", readIndex, applyPlotPane)                                          \
    X(SetPlotMaterial, View, "plot material", "plot material R G B METALLIC ROUGHNESS SPECULAR", readPlotMaterial,      \
      applyPlotMaterial)                                                                                                \
    X(SetPlotViewAngle, View, "plot view-angle", "plot view-angle DEGREES", readDegrees, applyPlotViewAngle)            \
    X(SetPlotLog, View, "plot log", "plot log on|off", readFlag, applyPlotLog)                                          \
    X(SwapSides, View, "swap", "swap (panes 0 and 1 trade places: the split's A/B)", readNothing, applySwapSides)

struct PanelAction {
#define GIS_PANEL_ACTION_KIND(kind, edits, words, usage, read, apply) kind,
    enum Kind { GIS_PANEL_ACTIONS(GIS_PANEL_ACTION_KIND) };
#undef GIS_PANEL_ACTION_KIND
    enum class Edits { Pane, Light, View };  // the table's second column
    Kind kind = SetMethod;
    int index = 0;            // pane or light
    std::string text;
    std::string valueText;    // SetParam
    bool flag = false;
    float value = 0.0f;
    glm::vec3 vec{0.0f};
    glm::vec4 vec4{0.0f};

    // An action of `kind` with the one field it reads set.
    static PanelAction of(Kind kind);
    static PanelAction withIndex(Kind kind, int index);
    static PanelAction withText(Kind kind, std::string text);
    static PanelAction withValue(Kind kind, float value);
    static PanelAction withFlag(Kind kind, bool flag);
    static PanelAction withVec(Kind kind, glm::vec3 vec);
    static PanelAction paneText(Kind kind, int pane, std::string text);

    static PanelAction method(int pane, std::string gi);
    static PanelAction preset(int pane, std::string name);
    static PanelAction diffuse(int pane, std::string name);
    static PanelAction specular(int pane, std::string name);
    static PanelAction display(int pane, PaneDisplay d);
    static PanelAction display(int pane, std::string name);   // a fixed display or a method's view
    static PanelAction param(int pane, std::string fullKey, std::string value);
    static PanelAction directOnly(int pane, bool on);
    static PanelAction viewMode(ViewMode m);
    static PanelAction dividerAt(float fraction);
    static PanelAction exposure(float ev);
    static PanelAction tonemapper(std::string name);
    static PanelAction orbit(float dyaw, float dpitch);       // radians
    static PanelAction pan(float dx, float dy);               // in units of the orbit distance
    static PanelAction zoom(float factor);                    // distance *= factor
    static PanelAction move(glm::vec3 local);                 // fly: right, up, forward, scene units
    static PanelAction look(float dyaw, float dpitch);        // fly: turn in place
};

// What an action of `kind` edits: a script's lines are checked against the view they will find by it.
PanelAction::Edits actionEdits(PanelAction::Kind kind);

// A SetParam's pane, key and value on their own (the row's range), without the pane's other values.
ParamValue parsePaneParam(const PanelAction& action);

// Validates and applies. Throws gis::Error (one line) for unknown names or out-of-range values and
// leaves `state` unchanged then.
void applyPanelAction(ViewState& state, const PanelAction& action);

// A script line / command in words, e.g. "method 1 pathtrace", "camera orbit 10 0" (degrees),
// "light 0 intensity 2". Throws gis::Error naming the problem. See docs/viewer.md.
PanelAction parsePanelAction(const std::vector<std::string>& words);
std::vector<std::string> splitWords(const std::string& line);

}  // namespace gis::view
