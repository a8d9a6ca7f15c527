// gisandbox view: the window, its input and the frame loop. What the panel and keys do goes
// through applyPanelAction (view_state.h); rendering is the ViewSession (view_session.h).
#include <CLI/CLI.hpp>

#include "gl/gl.h"  // glad before GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "cli/commands.h"
#include "image.h"
#include "view/panel.h"
#include "cli/settings_io.h"
#include "view/view_script.h"
#include "view/view_session.h"

namespace gis {

namespace {

using namespace gis::view;

constexpr float kPanelWidth = 420.0f;  // window pixels; less on narrow windows

// A key or mouse button going down or up, as GLFW's callbacks report it: queued until the next
// frame reads them, so a press shorter than a frame still counts.
struct InputEvent {
    bool button = false;  // a mouse button, else a key
    int code = 0;         // GLFW_KEY_* or GLFW_MOUSE_BUTTON_*
    bool press = false;
};

// The keys a script may press (`key NAME`) by the name docs/viewer.md gives them.
int scriptKey(const std::string& name) {
    static const std::pair<const char*, int> keys[] = {
        {"F12", GLFW_KEY_F12}, {"F", GLFW_KEY_F}, {"R", GLFW_KEY_R}, {"1", GLFW_KEY_1}, {"2", GLFW_KEY_2},
        {"3", GLFW_KEY_3},     {"B", GLFW_KEY_B}, {"I", GLFW_KEY_I}, {"W", GLFW_KEY_W}, {"A", GLFW_KEY_A},
        {"S", GLFW_KEY_S},     {"D", GLFW_KEY_D}, {"Q", GLFW_KEY_Q}, {"E", GLFW_KEY_E}};
    for (const auto& [n, code] : keys)
        if (name == n) return code;
    throw Error("key '" + name + "' is not one of F12 F R 1 2 3 B I W A S D Q E");
}

class ViewApp final : public ScriptHost {
public:
    explicit ViewApp(const ViewOptions& o) : options_(o), start_(std::chrono::steady_clock::now()) {}
    ~ViewApp() override;
    int run();

    // ScriptHost
    void apply(const PanelAction& a) override { applyPanelAction(state_, a); }
    void openScene(const std::string& spec) override {
        if (!session_->openScene(state_, spec))
            std::fprintf(stderr, "gisandbox: warning: %s\n", session_->lastError().c_str());
        else
            scenePath_ = spec;  // the panel's scene field shows what the script opened
    }
    void loadSettings(const std::string& path) override {
        if (!session_->loadSettings(state_, path)) throw Error(session_->lastError());
    }
    void saveSettings(const std::string& path) override {
        if (!session_->saveSettings(state_, path)) throw Error(session_->lastError());
    }
    void requestScreenshot() override { screenshot_ = true; }
    void requestCapture(const std::string& path) override { capturePath_ = path; }
    void resize(int w, int h) override {
        if (w == 0 || h == 0) glfwIconifyWindow(window_);
        else {
            glfwRestoreWindow(window_);
            glfwSetWindowSize(window_, w, h);
        }
    }
    void quit() override { quit_ = true; }
    // Down and up before the next frame reads them: a tap shorter than any frame.
    void pressKey(const std::string& name) override {
        const int key = scriptKey(name);
        onKey(window_, key, 0, GLFW_PRESS, 0);
        onKey(window_, key, 0, GLFW_RELEASE, 0);
    }
    bool settled() const override { return session_->settled(); }
    double seconds() const override {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
    static void onMouseButton(GLFWwindow* w, int button, int action, int mods);
    void handleInput(float viewW, float viewH, float dt);
    void applyKey(int key, bool fly);
    void takeScreenshot();
    void captureWindow(const std::string& path, int width, int height);
    void applyEnvironmentFlag();
    void openStartState(int width, int height);
    void openWindow(int width, int height);
    void startImGui();
    void openDroppedScene();
    void drawFrame(std::chrono::steady_clock::time_point& last, FrameTimes& times);
    void drawViewAndPanel(int fbw, int fbh, int ww, int wh, float dt, FrameTimes& times);
    void logFrame(float frameMs);

    ViewOptions options_;
    std::chrono::steady_clock::time_point start_;
    std::unique_ptr<GlContext> ctx_;
    GLFWwindow* window_ = nullptr;
    ViewState state_;
    std::unique_ptr<ViewSession> session_;
    ScriptRunner script_;
    bool imgui_ = false;
    bool quit_ = false, screenshot_ = false;
    std::string capturePath_;
    std::string message_, scenePath_, settingsPath_ = "gisandbox_view.json", environmentPath_;
    std::string droppedPath_;
    std::ofstream frameLog_;  // --frame-log
    double scroll_ = 0.0;
    std::vector<InputEvent> events_;  // since the last frame, in order
    bool inspect_ = false;  // I: the pixel inspector's tooltip follows the cursor
    enum class Drag { None, Orbit, Pan, Look, Divider } drag_ = Drag::None;
    double lastX_ = 0.0, lastY_ = 0.0;
};

ViewApp::~ViewApp() {
    session_.reset();  // GL objects go while the context lives
    if (imgui_) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
}

void ViewApp::onKey(GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_REPEAT || key < 0) return;
    static_cast<ViewApp*>(glfwGetWindowUserPointer(w))->events_.push_back({false, key, action == GLFW_PRESS});
}

void ViewApp::onMouseButton(GLFWwindow* w, int button, int action, int) {
    static_cast<ViewApp*>(glfwGetWindowUserPointer(w))->events_.push_back({true, button, action == GLFW_PRESS});
}

void ViewApp::applyKey(int key, bool fly) {
    PanelAction a;
    switch (key) {
        case GLFW_KEY_F12: screenshot_ = true; return;
        case GLFW_KEY_F:
            a.kind = PanelAction::SetCameraMode;
            a.text = fly ? "orbit" : "fly";
            break;
        case GLFW_KEY_R: a.kind = PanelAction::ResetCamera; break;
        case GLFW_KEY_1: a = PanelAction::viewMode(ViewMode::Single); break;
        case GLFW_KEY_2: a = PanelAction::viewMode(ViewMode::Split); break;
        case GLFW_KEY_3: a = PanelAction::viewMode(ViewMode::Grid); break;
        case GLFW_KEY_I: inspect_ = !inspect_; return;
        case GLFW_KEY_B: a.kind = PanelAction::SwapSides; break;  // A/B: which difference is which
        default: return;
    }
    applyPanelAction(state_, a);
}

void ViewApp::handleInput(float viewW, float viewH, float dt) {
    const ImGuiIO& io = ImGui::GetIO();
    double mx = 0.0, my = 0.0;
    glfwGetCursorPos(window_, &mx, &my);
    const double dx = mx - lastX_, dy = my - lastY_;
    lastX_ = mx;
    lastY_ = my;
    // A button or key counts as down this frame when it is down now or went down since the last.
    const std::vector<InputEvent> events = std::exchange(events_, {});
    auto pressedSince = [&](bool button, int code) {
        return std::any_of(events.begin(), events.end(),
                           [&](const InputEvent& e) { return e.press && e.button == button && e.code == code; });
    };
    auto buttonDown = [&](int b) { return glfwGetMouseButton(window_, b) == GLFW_PRESS || pressedSince(true, b); };
    const bool left = buttonDown(GLFW_MOUSE_BUTTON_LEFT);
    const bool right = buttonDown(GLFW_MOUSE_BUTTON_RIGHT) || buttonDown(GLFW_MOUSE_BUTTON_MIDDLE);
    const bool inView = mx >= 0.0 && mx < viewW && my >= 0.0 && my < viewH;
    ViewCamera& cam = state_.camera;
    const bool fly = cam.mode == CameraMode::Fly;

    if (!left && !right) drag_ = Drag::None;
    if (drag_ == Drag::None && inView && !io.WantCaptureMouse && (left || right)) {
        const float divider = state_.divider * viewW;
        if (left && state_.mode == ViewMode::Split && std::abs(mx - divider) < 8.0) drag_ = Drag::Divider;
        else if (fly) drag_ = Drag::Look;
        else drag_ = left ? Drag::Orbit : Drag::Pan;
    }
    const float turn = 0.005f;  // radians per pixel
    switch (drag_) {
        case Drag::Divider: applyPanelAction(state_, PanelAction::dividerAt(float(mx / viewW))); break;
        case Drag::Orbit:
            if (dx != 0.0 || dy != 0.0) applyPanelAction(state_, PanelAction::orbit(-float(dx) * turn, float(dy) * turn));
            break;
        case Drag::Look:
            if (dx != 0.0 || dy != 0.0) applyPanelAction(state_, PanelAction::look(float(dx) * turn, -float(dy) * turn));
            break;
        case Drag::Pan:
            if (dx != 0.0 || dy != 0.0) {
                const float perPixel = 2.0f * std::tan(0.5f * cam.yfov) / std::max(viewH, 1.0f);
                applyPanelAction(state_, PanelAction::pan(-float(dx) * perPixel, float(dy) * perPixel));
            }
            break;
        case Drag::None: break;
    }
    if (scroll_ != 0.0 && inView && !io.WantCaptureMouse) {
        if (fly) cam.speed = std::clamp(cam.speed * std::pow(1.2f, float(scroll_)), 1e-6f, 1e7f);
        else applyPanelAction(state_, PanelAction::zoom(std::pow(0.9f, float(scroll_))));
    }
    scroll_ = 0.0;

    if (io.WantCaptureKeyboard) return;  // typed into a panel field: ImGui had its own events
    for (const InputEvent& e : events)  // every press in order: two taps within a frame are two
        if (!e.button && e.press) applyKey(e.code, state_.camera.mode == CameraMode::Fly);
    if (fly) {
        auto down = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS || pressedSince(false, k) ? 1.0f : 0.0f; };
        const glm::vec3 dir(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                            down(GLFW_KEY_W) - down(GLFW_KEY_S));
        if (dir != glm::vec3(0.0f)) {
            const float boost = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ? 4.0f : 1.0f;
            applyPanelAction(state_, PanelAction::move(dir * cam.speed * boost * std::min(dt, 0.25f)));
        }
    }
}

void ViewApp::takeScreenshot() {
    try {
        const std::string path = session_->writeScreenshot(state_, options_.screenshotDir, ctx_->renderer);
        message_ = "wrote " + path;
        std::printf("wrote %s\n", path.c_str());
        std::fflush(stdout);
    } catch (const Error& e) {
        message_ = e.what();
        if (script_.active()) throw;
    }
}

void ViewApp::captureWindow(const std::string& path, int width, int height) {
    ImageU8 img;
    img.width = width;
    img.height = height;
    img.rgba.resize(size_t(width) * height * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    flipVertically(img);
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
    writePng(path, img);
    std::printf("wrote %s\n", path.c_str());
    std::fflush(stdout);
}

// --environment and --environment-rotation through the script's own checks (one message), before
// the scene opens (--lighting auto reads the map) and again over a settings file's.
void ViewApp::applyEnvironmentFlag() {
    if (!options_.given) return;
    if (options_.given("--environment"))
        applyPanelAction(state_, PanelAction::withText(PanelAction::SetEnvironment, options_.environment));
    if (options_.given("--environment-rotation"))
        applyPanelAction(state_, PanelAction::withValue(PanelAction::SetEnvironmentRotation, options_.environmentRotation));
}

// The scene (CPU only) before the window, so the script is checked against the view it will drive.
void ViewApp::openStartState(int width, int height) {
    session_ = std::make_unique<ViewSession>();
    state_.viewWidth = std::max(1, width - int(kPanelWidth));
    state_.viewHeight = height;
    state_.lighting = lightingModeName(parseLightingMode(options_.setup.lighting));
    applyEnvironmentFlag();
    if (!options_.settings.empty()) {
        if (!session_->loadSettings(state_, options_.settings)) throw Error(session_->lastError());
        applyEnvironmentFlag();
        if (options_.given && options_.given("--scene") && !session_->openScene(state_, options_.scene))
            throw Error(session_->lastError());
    } else if (!session_->openScene(state_, options_.scene, cameraRequest(options_.setup))) {
        throw Error(session_->lastError());
    }
    scenePath_ = state_.scene;
    if (!options_.setup.emitters.empty()) {  // --emitters: emitters.mode of every pane
        RenderSettings parsed;
        setParam(parsed, "emitters.mode", options_.setup.emitters);
        for (PaneState& pane : state_.panes) pane.params["emitters.mode"] = parsed.params["emitters.mode"];
    }
    if (!options_.script.empty()) {
        std::vector<ScriptStep> steps = loadScript(options_.script);
        checkScriptInContext(steps, state_, options_.script, &session_->scene().bounds);
        script_ = ScriptRunner(std::move(steps), options_.script);
    }
}

void ViewApp::openWindow(int width, int height) {
    ContextOptions co;
    co.backend = Backend::Glfw;
    co.window = true;
    co.visible = true;
    co.width = width;
    co.height = height;
    co.debug = options_.glDebug;
    co.title = "gisandbox";
    try {
        ctx_ = createContext(co);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) +
                    " (the sandbox needs a display: run it under `xvfb-run -a`, or render headless with `gisandbox render`)");
    }
    window_ = ctx_->window();
    session_->setDefaultFrameBudget(defaultFrameBudgetMs(ctx_->renderer));
    if (options_.verbose)
        std::fprintf(stderr, "backend: glfw (%s)\nGL_RENDERER: %s\nGL_VERSION: %s\n", ctx_->detail.c_str(),
                     ctx_->renderer.c_str(), ctx_->version.c_str());
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    // Before ImGui installs its callbacks, which chain to these.
    glfwSetKeyCallback(window_, &ViewApp::onKey);
    glfwSetMouseButtonCallback(window_, &ViewApp::onMouseButton);
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double y) {
        static_cast<ViewApp*>(glfwGetWindowUserPointer(w))->scroll_ += y;
    });
    glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
        if (count > 0) static_cast<ViewApp*>(glfwGetWindowUserPointer(w))->droppedPath_ = paths[0];
    });
}

void ViewApp::startImGui() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForOpenGL(window_, true) || !ImGui_ImplOpenGL3_Init("#version 450"))
        throw Error("cannot initialise the ImGui GLFW/OpenGL3 backends");
    imgui_ = true;
}

void ViewApp::openDroppedScene() {
    if (droppedPath_.empty()) return;
    const std::string path = std::exchange(droppedPath_, std::string());
    if (session_->openScene(state_, path)) {
        message_ = "opened " + path;
        scenePath_ = path;
    }
}

// The 3D view, the panel and the overlay into the window's framebuffer (fbw x fbh pixels; ww x wh
// window coordinates), then the screenshot or capture asked for.
void ViewApp::drawViewAndPanel(int fbw, int fbh, int ww, int wh, float dt, FrameTimes& times) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // Window coordinates for ImGui and the mouse; framebuffer pixels for GL (HiDPI).
    const float panelW = std::min(kPanelWidth, 0.5f * float(ww));
    const float viewW = std::max(1.0f, float(ww) - panelW), viewH = float(wh);
    const float sx = float(fbw) / float(ww);
    handleInput(viewW, viewH, dt);
    const int viewPixelsW = std::max(1, int(std::lround(viewW * sx))), viewPixelsH = fbh;
    state_.viewWidth = viewPixelsW;
    state_.viewHeight = viewPixelsH;
    session_->relight(state_);
    session_->renderFrame(state_, viewPixelsW, viewPixelsH);
    // Panel and overlay after the frame: both show the frame on screen (the same "5/16 spp"),
    // and what the panel changes is rendered from the next frame on.
    drawViewOverlay(state_, *session_, 0.0f, 0.0f, viewW, viewH);
    if (inspect_ && !ImGui::GetIO().WantCaptureMouse)
        drawPixelInspector(state_, *session_, float(lastX_), float(lastY_), viewW, viewH);
    view::PanelContext panel{state_, *session_, message_, scenePath_, settingsPath_, environmentPath_, ctx_->renderer, times, false, {}};
    drawPanel(panel, viewW, 0.0f, float(ww) - viewW, viewH);
    if (panel.screenshotRequested) screenshot_ = true;
    ImGui::Render();

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    session_->drawToFramebuffer(state_, 0, 0, viewPixelsW, viewPixelsH);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    if (screenshot_) {
        screenshot_ = false;
        takeScreenshot();
    }
    if (!capturePath_.empty()) captureWindow(std::exchange(capturePath_, std::string()), fbw, fbh);
}

// One turn of the window's loop (a minimised window only runs the script).
void ViewApp::drawFrame(std::chrono::steady_clock::time_point& last, FrameTimes& times) {
    // Nothing moving and nothing accumulating: wait for input instead of spinning.
    if (!script_.active() && drag_ == Drag::None && state_.camera.mode == CameraMode::Orbit && session_->settled())
        glfwWaitEventsTimeout(0.1);
    else
        glfwPollEvents();
    int fbw = 0, fbh = 0, ww = 0, wh = 0;
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    glfwGetWindowSize(window_, &ww, &wh);
    if (fbw <= 0 || fbh <= 0 || ww <= 0 || wh <= 0) {  // minimised: nothing to draw into
        if (script_.active()) script_.frame(*this);
        glfwWaitEventsTimeout(0.1);
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    const float dt = std::chrono::duration<float>(now - last).count();
    last = now;
    openDroppedScene();
    if (script_.active()) script_.frame(*this);
    drawViewAndPanel(fbw, fbh, ww, wh, dt, times);
    glfwSwapBuffers(window_);
    // From after the event wait to after the swap, smoothed alike so the parts still add up.
    const float frameMs = 1000.0f * std::chrono::duration<float>(std::chrono::steady_clock::now() - now).count();
    // Smoothed from the first frame's own figures, not from 0: the line agrees with the pane graph
    // from the start.
    const bool first = times.frameMs == 0.0f;
    times.frameMs = first ? frameMs : 0.9f * times.frameMs + 0.1f * frameMs;
    times.gpuMs = first ? float(session_->gpuMsCollected()) : 0.9f * times.gpuMs + 0.1f * float(session_->gpuMsCollected());
    if (frameLog_.is_open()) logFrame(frameMs);
}

// --frame-log: the frame's wall ms (event wait excluded, swap included), the GPU ms of the
// timings that arrived in it, and per visible pane its render scale, the GPU ms of its last full
// frame (what the frame budget is held against), whether its camera moved and its status.
void ViewApp::logFrame(float frameMs) {
    frameLog_ << std::fixed << std::setprecision(2) << seconds() << '\t' << frameMs << '\t'
              << session_->gpuMsCollected();
    for (int i = 0; i < session_->visiblePanes(); ++i)
        frameLog_ << '\t' << session_->pane(i).scale << '\t' << session_->pane(i).fullFrameMs << '\t'
                  << (session_->pane(i).movingFrames > 0) << '\t' << session_->pane(i).status;
    frameLog_ << '\n';
    if (!frameLog_) throw Error("cannot write the frame log " + options_.frameLog + " (disk full?)");
}

int ViewApp::run() {
    int width = 0, height = 0;
    parseRenderSize(options_.size, width, height);
    openStartState(width, height);
    if (!options_.frameLog.empty()) {
        checkNotAnOpenFile(state_, options_.frameLog, options_.script);  // as save-settings and capture do
        frameLog_.open(options_.frameLog);
        if (!frameLog_) throw Error("cannot write the frame log '" + options_.frameLog + "' (--frame-log)");
        frameLog_ << "seconds\tframe_ms\tgpu_ms\tper pane: scale, full_frame_gpu_ms, moving, status\n";
    }
    openWindow(width, height);
    startImGui();
    auto last = std::chrono::steady_clock::now();
    FrameTimes times;
    while (!quit_ && !glfwWindowShouldClose(window_)) drawFrame(last, times);
    return 0;
}

}  // namespace

void addViewOptions(CLI::App& cmd, ViewOptions& o) {
    cmd.add_option("--scene", o.scene, "glTF file (.gltf/.glb) or builtin:NAME to open")->capture_default_str();
    cmd.add_option("--settings", o.settings, "Start from a settings file (saved by the panel, or a screenshot's .json)");
    cmd.add_option("--size", o.size, "Window size WIDTHxHEIGHT (the panel takes 420 pixels of it)")
        ->capture_default_str();
    addSceneSetupOptions(cmd, o.setup);
    cmd.add_option("--script", o.script, "Run timed actions from FILE (see docs/viewer.md)");
    addEnvironmentOptions(cmd, o.environment, o.environmentRotation);
    cmd.add_option("--screenshot-dir", o.screenshotDir, "Where screenshots (F12) go")->capture_default_str();
    cmd.add_option("--frame-log", o.frameLog,
                   "Write a line per window frame to FILE: seconds, wall ms, GPU ms, each pane's render scale, full "
                   "frame GPU ms, whether its camera moved and its status (what a scripted orbit costs: scripts/viewer-budget-table.sh)");
    cmd.add_flag("--gl-debug", o.glDebug, "Debug context; print KHR_debug messages");
    cmd.add_flag("-v,--verbose", o.verbose, "Print the backend, GL_RENDERER and GL_VERSION");
    o.given = [&cmd](const std::string& flag) { return cmd.count(flag) > 0; };
}

int runView(const ViewOptions& o) {
    ViewApp app(o);
    return app.run();
}

}  // namespace gis
