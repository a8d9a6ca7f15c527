// The GL side of `gisandbox view`, without a window: the scene, a Renderer per visible pane, the
// path-traced references of the error heatmaps, debug displays, timings, screenshots. It needs a
// current GL context (any backend), so the tests drive it headless exactly as the window does.
//
// Rebuild policy: a pane's Renderer is re-created when anything it bakes into its resources
// changes (method, preset, size, shadows, ambient/background/bounces, the lights, the scene) and
// kept otherwise. BRDF models, tone mapper and exposure are uniforms read every frame
// (Renderer::setLiveSettings): switching them costs nothing, and the path tracer restarts its
// accumulation; a deferred method's debug view switches live too (nothing restarts). A camera move never rebuilds either (Renderer::setCamera). A rebuild costs what
// `gisandbox render` pays before its first frame: the scene upload, shader compilation and, for the
// path tracer, the BVH build (docs/viewer.md has llvmpipe numbers).
//
// Frame policy: a pane whose renderer is settled (Renderer::settled: nothing changed and every
// pass converged) is not rendered at all; it shows its last frame. While the pane's last full
// frame took longer than the frame budget and the camera moves (two session frames in a row with
// a new camera) or the method converges, the pane renders through a second renderer at the scale
// that fits the budget (budgetScale). Once that reduced view has settled and the camera is still,
// full-scale frames resume (the reduced image stays on show until the full one has settled).
#pragma once

#include <deque>
#include <optional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer.h"
#include "image.h"
#include "renderer.h"
#include "cli/view_state.h"

namespace gis::view {

constexpr int kHistoryFrames = 240;  // frames of GPU timings kept for the live graph

// The render scale that brings a frame of `fullFrameMs` GPU ms within `budgetMs`, a frame's cost
// following its pixels: 1, 1/2, 1/4, or 1/8 at the least. A budget of 0 or less keeps full scale.
float budgetScale(double fullFrameMs, double budgetMs);

// A render scale as the panel and the pane's status show it: "1", "1/2", ... "1/8".
std::string scaleLabel(float scale);

// A pane's heatmap figure as the panel and the pane labels show it: four decimals for every
// pane and metric, so two panes line up (significant digits gave 0.123 beside 0.0456).
std::string formatPaneMetric(double value);

// The frame budget where the view state leaves it to the machine: about 10 frames a second on a
// CPU renderer (llvmpipe, softpipe, SwiftShader), 60 on a GPU.
constexpr double kCpuFrameBudgetMs = 100.0, kGpuFrameBudgetMs = 16.0;
double defaultFrameBudgetMs(const std::string& glRenderer);

struct PassHistory {
    std::string pass;
    std::deque<float> ms;     // GPU ms per frame, oldest first
    int64_t bytes = 0;        // GPU memory the pass holds
    bool cached = false;      // the last frame reused its results
    float workedMs = 0.0f;    // GPU ms of the last frame in which it did work
};

// One visible pane: its renderer and what it shows.
struct PaneView {
    std::unique_ptr<Renderer> renderer;
    std::string failedKey;            // settings whose build failed (not retried until they change)
    CameraMatrices camera;
    bool cameraSet = false;
    gl::Texture display;              // RGBA8: debug and heatmap displays
    GLuint shown = 0;                 // the texture this pane shows this frame
    glm::ivec2 shownSize{0, 0};       // its pixels: the pane's size, less for a reduced frame
    // Over the frame budget: the same settings at budgetScale, shown instead of `renderer` while
    // the camera moves or the method converges.
    std::unique_ptr<Renderer> reduced;
    CameraMatrices reducedCamera;     // what `reduced` was last given
    float scale = 1.0f;               // of the frame shown: 1, or the reduced frame's scale
    float scaleCap = 1.0f;            // lowered when a reduced frame was over the budget anyway
    CameraMatrices lastCamera;        // the session's previous frame's camera
    int movingFrames = 0;             // session frames in a row with a new camera
    // GPU ms of a full-scale frame while the image changes: the last worked time of each pass that
    // worked in the last frame (a settled one, a shadow map or a voxel volume built once, costs a
    // camera move nothing). What the frame budget is held against.
    double fullFrameMs = 0.0;
    std::vector<PassHistory> passes;
    std::deque<float> totalMs;
    std::string status;               // "12/64 spp", "reference 5/64 spp", errors
    // Heatmap against the reference, when the pane shows one.
    bool heatmapWanted = false;
    std::string heatmapKey;
    bool heatmapReady = false;
    double metricValue = 0.0;
    double heatmapMax = 0.0;          // the colour bar's right end (the map's largest value, or 1)
    std::string metricName;
};

// What save-settings writes must load: a free camera moved or zoomed so far from the scene that
// its znear is below 1e-6 of the scene's depth (the loaders' checkCameraDepth) is refused, naming
// `path`, instead of writing a file that `render --settings` and the viewer then refuse.
void checkSavedCamera(const ViewState& state, const Aabb& bounds, const std::string& path);
// A viewer output (save-settings, capture) must not replace a file the viewer has open: the state's
// scene or environment map, or `script` (the running one; empty: none). Same file by any name
// (sameFile): the check is on the device and inode.
void checkNotAnOpenFile(const ViewState& state, const std::string& path, const std::string& script = "");

class ViewSession {
public:
    ViewSession();   // no GL until a frame is rendered or drawn: a scene can be opened before the window
    ~ViewSession();
    ViewSession(const ViewSession&) = delete;
    ViewSession& operator=(const ViewSession&) = delete;

    // Loads a scene and makes it the current one: applies state.lighting, resets `state`'s camera
    // (to the camera `camera` asks for: the file's first by default, framing when it has none)
    // and light list. On failure keeps the previous scene and state, sets lastError()
    // and returns false.
    bool openScene(ViewState& state, const std::string& spec, const CameraRequest& camera = {});
    // Loads a settings file: its scene, then everything else over it. On failure keeps the
    // previous scene and state, sets lastError() and returns false.
    bool loadSettings(ViewState& state, const std::string& path);
    // Refuses (false, lastError) a free camera the loader would refuse (checkSavedCamera) and a path
    // that is an open file (checkNotAnOpenFile).
    bool saveSettings(const ViewState& state, const std::string& path);
    const std::string& lastError() const { return lastError_; }
    void clearError() { lastError_.clear(); }
    bool hasScene() const { return scene_ != nullptr; }
    const Scene& scene() const { return *scene_; }
    const std::vector<Light>& sceneLights() const { return sceneLights_; }
    // Applies state.lighting again when what it means changed since the scene was opened: an
    // environment map set or cleared afterwards (the panel, a script, --environment over a
    // settings file) turns `auto`'s default sun and sky off or on. The light list follows unless
    // the user edited it. Call before renderFrame, as the window does every frame.
    void relight(ViewState& state);

    // One frame of every visible pane for a 3D view of viewWidth x viewHeight window pixels.
    void renderFrame(const ViewState& state, int viewWidth, int viewHeight);
    // Blits the panes into the current draw framebuffer's rectangle (x, y from the bottom-left, GL
    // convention), as the view shows them: split panes cut at the divider.
    void drawToFramebuffer(const ViewState& state, int x, int y, int width, int height) const;

    int visiblePanes() const { return visible_; }
    const PaneView& pane(int i) const { return panes_[i]; }
    glm::ivec2 paneSize() const { return paneSize_; }
    // Every visible pane finished (progressive methods converged, heatmaps computed, no reduced
    // frame waiting for its full-scale refinement).
    bool settled() const;
    // Frames the panes' renderers rendered so far (a settled pane's frames are not rendered).
    int framesRendered() const { return framesRendered_; }
    // GPU ms of the pass timings that arrived during the last renderFrame, every pane and reduced
    // renderer: the GPU share of the app's frame time.
    double gpuMsCollected() const { return gpuMsCollected_; }
    // The frame budget (GPU ms) where the state's is 0: the app sets defaultFrameBudgetMs of its
    // GL renderer; 0 (the default, for tests) keeps full scale.
    void setDefaultFrameBudget(double ms) { defaultBudgetMs_ = ms; }
    double frameBudgetMs(const ViewState& state) const {
        return state.frameBudgetMs > 0.0f ? double(state.frameBudgetMs) : defaultBudgetMs_;
    }
    ImageU8 readPane(int pane) const;             // what the pane shows, rows top to bottom
    // The pixel inspector: pane `index`'s linear radiance (or its debug view's values) at pane
    // pixel `pixel` (x right, y down, render pixels), and the path-traced reference's radiance
    // there once the reference the heatmap uses has converged. Empty outside the pane or before
    // its first frame.
    struct PixelReadout {
        glm::vec3 radiance{0.0f};
        bool hasReference = false;
        glm::vec3 reference{0.0f};
    };
    std::optional<PixelReadout> inspectPixel(const ViewState& state, int index, glm::ivec2 pixel) const;
    // What the 3D view shows, composed on the CPU at render size: the pane (single), the two
    // halves at the divider (split) or 2x2 panes (grid), each labelled when `labels`.
    ImageU8 composite(const ViewState& state, bool labels) const;
    // Writes DIR/<scene>_<method>_<time>.png and its .json sidecar (every setting, the per-pane
    // render settings, timings and heatmap metric), atomically. Returns the PNG's path.
    std::string writeScreenshot(const ViewState& state, const std::string& dir, const std::string& glRenderer) const;
    nlohmann::ordered_json timingsJson() const;

    int rebuilds() const { return rebuilds_; }    // renderers built so far (panes and references)
    int64_t gpuBytes() const;                      // everything the panes and references hold
    void releaseRenderers();                       // frees every renderer and display texture

private:
    struct Reference {
        std::unique_ptr<Renderer> renderer;
        CameraMatrices camera;
        ImageF image;            // once converged
        uint64_t lastUsed = 0;
    };
    void syncLights(const ViewState& state);
    void renderPane(const ViewState& state, int index, const CameraMatrices& camera);
    void updateHeatmap(const ViewState& state, int index, const CameraMatrices& camera);
    Reference* reference(const ViewState& state, int index, const CameraMatrices& camera);
    void collectTimings(PaneView& pane);
    bool reducedNeedsBuild(const PaneView& pane, const RenderSettings& want) const;
    Renderer& reducedRenderer(const ViewState& state, int index, const CameraMatrices& camera, float scale);
    double renderReduced(Renderer& reduced);
    void renderReducedFrame(const ViewState& state, int index, const CameraMatrices& camera, float scale,
                            double budgetMs);
    void prepareReducedFrame(const ViewState& state, int index, const CameraMatrices& camera, float scale);
    bool reducedSettled(const PaneView& pane, float scale, const CameraMatrices& camera) const;
    GLuint ensureDisplay(PaneView& pane);

    std::unique_ptr<Scene> scene_;
    std::vector<Light> sceneLights_;     // after --lighting
    std::vector<Light> fileLights_;      // as loaded, before --lighting
    LightingMode litWith_ = LightingMode::Scene;  // what --lighting meant for sceneLights_
    std::string lightsKey_;              // the lights scene_ holds now
    PaneView panes_[kMaxPanes];
    std::map<std::string, Reference> references_;
    mutable gl::Object readFbo_;  // made by the first drawToFramebuffer
    glm::ivec2 paneSize_{1, 1};
    int visible_ = 0;
    int rebuilds_ = 0;
    int framesRendered_ = 0;
    double gpuMsCollected_ = 0.0;
    double defaultBudgetMs_ = 0.0;
    uint64_t frame_ = 0;
    std::string lastError_;
};

// Key of a renderer's settings without the BRDFs and tone mapping (references, failed builds).
std::string structuralKey(const RenderSettings& settings);

}  // namespace gis::view
