// The interactive sandbox's state: what a settings file holds and `render --settings` renders, so
// the CLI's. The only ways to change it are its actions (panel_action.h). No GL here.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gi/method.h"
#include "metrics.h"
#include "renderer.h"
#include "scene/scene.h"

namespace gis::view {

enum class ViewMode { Single, Split, Grid };          // 1 pane; 2 panes with a divider; 2x2 panes
// Ao: the ambient occlusion term alone (SSAO for --gi ssao, the image itself for ao-reference).
// Method: a debug view the pane's method offers (PaneState::methodView, e.g. "vct.slice").
enum class PaneDisplay { Lit, Heatmap, Depth, Normal, BaseColor, Material, Emissive, Ao, Method };
enum class CameraMode { Orbit, Fly };

constexpr int kMaxPanes = 4;
// The largest magnitude a number in the view state may hold, set by a panel, a script or a
// settings file alike: what is accepted when set is what saves and loads again, and a product of
// two such values (a light's colour times its intensity) is still finite in float.
constexpr double kMaxSettingMagnitude = 1e18;
constexpr float kMaxPitch = 1.5533430f;  // 89 degrees: never straight up or down (lookAt's up vector)
int paneCount(ViewMode mode);

const char* viewModeName(ViewMode m);
ViewMode parseViewMode(const std::string& s);        // single, split, grid
const char* paneDisplayName(PaneDisplay d);
PaneDisplay parsePaneDisplay(const std::string& s);  // lit, heatmap, depth, normal, basecolor, material, emissive, ao
const std::vector<PaneDisplay>& allPaneDisplays();   // the fixed ones (not Method)
bool isGBufferDisplay(PaneDisplay d);                // depth .. emissive
// The renderer's view name for a display ("final", "gbuffer.normal", "ao", a method's view).

// What one pane shows: its own GI method (with a quality preset) and BRDFs; everything else is shared.
struct PaneState {
    std::string gi = kDefaultGiMethod;
    std::string preset = "medium";
    ParamValues params;        // the panel's parameter edits, over the preset ("method.key" -> value)
    std::string methodView;    // display Method: which of the method's debug views
    DiffuseModel diffuse = DiffuseModel::Lambert;
    SpecularModel specular = SpecularModel::Ggx;
    PaneDisplay display = PaneDisplay::Lit;
    bool directOnly = false;   // none: no ambient term; pathtrace: no indirect bounce
};

// The baseline, then three methods that differ, so split and grid modes open on a comparison
// (pane 1 is split mode's other side) instead of identical panes.
std::array<PaneState, kMaxPanes> defaultPanes();

// The free camera: a position and a look direction (yaw about +Y, pitch up), with an orbit target
// `distance` ahead. While `free` is false the scene's camera `sceneCamera` is used unchanged, so
// an untouched view renders exactly what `gisandbox render --camera N` does.
struct ViewCamera {
    int sceneCamera = 0;
    bool free = false;
    CameraMode mode = CameraMode::Orbit;
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    float yaw = 0.0f, pitch = 0.0f;     // radians; yaw 0 looks along -Z
    float distance = 1.0f;              // to the orbit target
    float yfov = 0.6981317f;            // full vertical angle, radians
    float znear = 0.01f, zfar = 100.0f; // zfar 0: infinite
    float speed = 1.0f;                 // fly speed, scene units per second
};

// A light in the panel's list: the scene's lights, edited, plus any added. Disabled lights are
// left out of the scene the renderers see.
struct LightState {
    Light light;
    bool enabled = true;
};

struct ViewState {
    std::string scene = "builtin:cornell";
    std::string lighting = "auto";        // --lighting: applied when the scene is opened
    ViewMode mode = ViewMode::Single;
    std::array<PaneState, kMaxPanes> panes = defaultPanes();
    float divider = 0.5f;                 // split: left pane's share of the view width, [0.02, 0.98]

    // Shared by every pane.
    Tonemapper tonemap = Tonemapper::Aces;
    float exposureEV = 0.0f;
    glm::vec3 ambient{0.03f};
    bool shadows = true;
    std::optional<glm::vec3> background;
    std::string environment;              // an equirectangular .hdr (RenderSettings::environment), or none
    float environmentRotation = 0.0f;     // degrees about +Y (RenderSettings::environmentRotation)
    int maxBounces = 16;                  // path tracer
    float renderScale = 1.0f;             // render at this fraction of the view's pixels, [0.125, 1]
    // GPU ms a pane's full frame may take before the pane renders at a lower scale while its
    // camera moves or its method converges (ViewSession: budgetScale); 0 = the machine's default
    // (kCpuFrameBudgetMs on a CPU renderer, kGpuFrameBudgetMs on a GPU).
    float frameBudgetMs = 0.0f;

    // Error heatmap against the path-traced reference at the current camera.
    ErrorMetric heatmapMetric = ErrorMetric::Flip;
    int referenceSpp = 64;

    ViewCamera camera;
    std::vector<LightState> lights;       // what the panel lists; used when lightsEdited
    bool lightsEdited = false;            // else the scene's own lights

    // Set from the scene by resetCamera / resetLights (not saved): what "reset" returns to.
    ViewCamera homeCamera;
    std::vector<Light> sceneLights;

    // BRDF lobe plot: the material it is drawn for.
    int plotPane = 0;
    glm::vec3 plotBaseColor{0.8f};
    float plotMetallic = 0.0f, plotRoughness = 0.3f, plotSpecular = 1.0f;
    float plotViewAngle = 0.7853982f;     // radians
    bool plotLog = false;

    int viewWidth = 960, viewHeight = 720;  // the 3D view's size in window pixels (for --settings)
};

// Throws unless `pane` is one of the kMaxPanes.
void checkPane(int pane);
// Throws when pane `pane`'s display is a view its method cannot produce, told without GL
// (checkViewOfMethod: "sdf.slice" on a vct pane, "indirect.diffuse" on a pathtrace pane).
void checkPaneDisplay(const ViewState& state, int pane);

// --- From state to renderer settings.

// Scene-dependent initial state: the camera from scene camera `cameraIndex` (or the default one),
// the light list from the scene's lights, fly speed from its size.
void resetCamera(ViewState& state, const Scene& scene, int cameraIndex);
void resetLights(ViewState& state, const std::vector<Light>& sceneLights);
// The lights the renderers should see: the edited list's enabled lights, or `sceneLights` (the
// scene's own, as loaded).
std::vector<Light> effectiveLights(const ViewState& state, const std::vector<Light>& sceneLights);

// Pane rectangles in the 3D view (x, y from the top-left, w, h) and the size each pane renders at.
// Split: both panes cover the whole view (the divider picks which part of each is shown).
struct PaneRect {
    int x = 0, y = 0, w = 1, h = 1;
};
std::vector<PaneRect> paneRects(ViewMode mode, int viewWidth, int viewHeight);
glm::ivec2 paneRenderSize(const ViewState& state, int viewWidth, int viewHeight);
// `size` at `scale`, rounded, at least one pixel each way (the render scale, a reduced frame).
glm::ivec2 scaledSize(glm::ivec2 size, float scale);

// Everything a Renderer needs for pane `pane` at `size`: the shared settings, the pane's method,
// preset, parameter edits, BRDFs and debug view. In the view the path tracer adds one sample per frame.
RenderSettings paneSettings(const ViewState& state, int pane, glm::ivec2 size);
// The path-traced reference the heatmap of `pane` compares against: the same scene, camera and
// BRDFs, full global illumination at referenceSpp.
RenderSettings referenceSettings(const ViewState& state, int pane, glm::ivec2 size);

// The camera for an image of the given aspect: the scene camera while the view camera is not
// free, else a perspective camera at the free camera's pose.
CameraMatrices viewCameraMatrices(const ViewState& state, const Scene& scene, float aspect);
glm::vec3 cameraForward(const ViewCamera& camera);

// A label for a pane: "none/medium lambert+ggx", "pathtrace/high ... [heatmap]".
std::string paneLabel(const ViewState& state, int pane);
// What the panel's combos offer: every registered GI method; the fixed displays plus the debug
// views a pane's renderer offers (`views`, from Renderer::views()) that are not fixed ones.
std::vector<std::string> methodChoices();
std::vector<std::string> displayChoices(const std::vector<DebugViewDesc>& views);
// The value a pane's method parameter has: the pane's edit, else its preset's, else the default.
ParamValue paneParam(const ViewState& state, int pane, const std::string& method, const ParamDesc& desc);
// The parameter tables the panel draws for a pane, each a tree of widgets keyed "NAME.KEY": its
// method's, then the shared ones (ParamGroup, e.g. emitters.*) that a deferred method's frame reads.
struct ParamTableView {
    std::string name;                       // the key prefix: "vct", "emitters"
    const std::vector<ParamDesc>* params;
};
std::vector<ParamTableView> paneParamTables(const PaneState& pane);

}  // namespace gis::view
