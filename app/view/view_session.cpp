#include "view/view_session.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "metrics.h"
#include "plot.h"
#include "scene/atomic_file.h"
#include "cli/settings_io.h"

namespace gis::view {

namespace {

namespace fs = std::filesystem;

bool sameCamera(const CameraMatrices& a, const CameraMatrices& b) {
    return a.viewProj == b.viewProj && a.position == b.position;
}

std::string lightsKey(const std::vector<Light>& lights) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const Light& l : lights) j.push_back(lightToJson(l));
    return j.dump();
}

std::string fileSafe(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return s.empty() ? std::string("scene") : s;
}

float median(std::deque<float> v) {
    if (v.empty()) return 0.0f;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

template <typename T>
void push(std::deque<T>& d, T v) {
    d.push_back(v);
    while (d.size() > size_t(kHistoryFrames)) d.pop_front();
}

// "12/64 spp" (or "updates") for a progressive method, "64 spp" once converged, "" for the others;
// a stale result (a bake from before an edit, shown while the next one runs) says so first.
std::string progressText(const Renderer& r) {
    for (const auto& pass : r.passes()) {
        const Pass::Progress pr = pass->progress();
        if (pr.target <= 0) continue;
        const char* stale = pr.held    ? "stale since an edit, the last result shown, its redo held: "
                            : pr.stale ? "stale since an edit, the last result shown while it redoes it: "
                                       : "";
        return std::string(stale) +
               (pr.done >= pr.target ? "" : std::to_string(pr.done) + "/") + std::to_string(pr.target) + " " + pr.unit;
    }
    return "";
}

// Nearest-neighbour resampling: a reduced frame read back at the pane's size.
ImageU8 resizeNearest(const ImageU8& src, int width, int height) {
    ImageU8 out;
    out.width = width;
    out.height = height;
    out.rgba.resize(size_t(width) * height * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const int sx = std::min(src.width - 1, x * src.width / width), sy = std::min(src.height - 1, y * src.height / height);
            std::copy_n(&src.rgba[(size_t(sy) * src.width + sx) * 4], 4, &out.rgba[(size_t(y) * width + x) * 4]);
        }
    return out;
}

std::string describe(const std::exception& e) {
    return dynamic_cast<const std::bad_alloc*>(&e) ? std::string("out of memory") : std::string(e.what());
}

// --lighting as the scene is lit under state's environment (a map replaces auto's default sky).
LightingMode lightingFor(const ViewState& state) {
    return lightingUnderEnvironment(parseLightingMode(state.lighting), !state.environment.empty());
}

}  // namespace

float budgetScale(double fullFrameMs, double budgetMs) {
    float scale = 1.0f;
    while (budgetMs > 0.0 && scale > 0.125f && fullFrameMs * scale * scale > budgetMs) scale *= 0.5f;
    return scale;
}

std::string scaleLabel(float scale) {
    return scale >= 1.0f ? "1" : "1/" + std::to_string(int(std::lround(1.0f / scale)));
}

std::string formatPaneMetric(double value) {
    if (!std::isfinite(value)) return formatMetric(value);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4f", value);
    return buf;
}

double defaultFrameBudgetMs(const std::string& glRenderer) {
    for (const char* cpu : {"llvmpipe", "softpipe", "SwiftShader", "swrast"})
        if (glRenderer.find(cpu) != std::string::npos) return kCpuFrameBudgetMs;
    return kGpuFrameBudgetMs;
}

std::string structuralKey(const RenderSettings& settings) {
    nlohmann::ordered_json j = renderSettingsToJson(settings);
    for (const char* live : {"diffuse", "specular", "tonemap", "exposure"}) j.erase(live);
    return j.dump();
}

ViewSession::ViewSession() = default;

ViewSession::~ViewSession() { releaseRenderers(); }

bool ViewSession::openScene(ViewState& state, const std::string& spec, const CameraRequest& request) {
    try {
        auto scene = std::make_unique<Scene>(loadScene(spec));
        ViewState s = state;
        s.scene = spec;
        const LightingMode lighting = lightingFor(state);
        std::vector<Light> fileLights = scene->lights;
        if (applyLighting(*scene, lighting)) s.ambient = glm::vec3(kDefaultSkyRadiance);
        const int camera =
            resolveCamera(*scene, request, float(std::max(s.viewWidth, 1)) / float(std::max(s.viewHeight, 1)));
        resetCamera(s, *scene, camera);
        resetLights(s, scene->lights);
        releaseRenderers();
        scene_ = std::move(scene);
        sceneLights_ = scene_->lights;
        fileLights_ = std::move(fileLights);
        litWith_ = lighting;
        lightsKey_ = lightsKey(sceneLights_);
        state = std::move(s);
        lastError_.clear();
        return true;
    } catch (const std::exception& e) {
        // The loader's messages already name the file; say it once.
        const std::string why = describe(e);
        const std::string name = spec.substr(spec.find_last_of("/:") + 1);
        lastError_ = why.find(name) != std::string::npos ? "cannot open: " + why : "cannot open " + spec + ": " + why;
        return false;
    }
}

bool ViewSession::loadSettings(ViewState& state, const std::string& path) {
    try {
        const ViewState loaded = loadViewSettings(path);
        ViewState s = loaded;
        CameraRequest request;
        request.index = loaded.camera.sceneCamera;
        if (!openScene(s, loaded.scene, request)) return false;  // lastError_ is set
        // openScene reset camera and lights from the scene (and set what "reset" returns to):
        // now the file's own.
        s.camera = loaded.camera;
        if (s.camera.free) {  // the glTF loader's depth-range check, for the file's own camera
            const std::string warning = checkCameraDepth(scene().bounds, s.camera.position, s.camera.znear, path + ": camera");
            if (!warning.empty()) std::fprintf(stderr, "gisandbox: warning: %s\n", warning.c_str());
        }
        if (loaded.lightsEdited) {
            s.lights = loaded.lights;
            s.lightsEdited = true;
        }
        state = std::move(s);
        return true;
    } catch (const std::exception& e) {
        lastError_ = describe(e);
        return false;
    }
}

void checkSavedCamera(const ViewState& state, const Aabb& bounds, const std::string& path) {
    if (!state.camera.free) return;
    try {
        checkCameraDepth(bounds, state.camera.position, state.camera.znear, path + ": camera");
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + ": not saved, the file would not load; move the camera back toward the scene");
    }
}

void checkNotAnOpenFile(const ViewState& state, const std::string& path, const std::string& script) {
    for (const auto& [what, open] : {std::pair<const char*, const std::string&>{"the open scene", state.scene},
                                     {"the environment map", state.environment},
                                     {"the running script", script}})
        if (!open.empty() && sameFile(path, open))
            throw Error(path + " is " + what + " (" + open + "): not overwritten; write to another file");
}

bool ViewSession::saveSettings(const ViewState& state, const std::string& path) {
    try {
        checkNotAnOpenFile(state, path);
        if (scene_) checkSavedCamera(state, scene_->bounds, path);
        saveViewSettings(path, state);
        return true;
    } catch (const std::exception& e) {
        lastError_ = describe(e);
        return false;
    }
}

void ViewSession::releaseRenderers() {
    for (PaneView& p : panes_) p = PaneView{};
    references_.clear();
    visible_ = 0;
}

void ViewSession::relight(ViewState& state) {
    const LightingMode lighting = lightingFor(state);
    if (!scene_ || lighting == litWith_) return;
    // applyLighting reads the scene's own lights and emission; syncLights then hands the result to
    // the renderers as it does a light edit.
    const std::vector<Light> current = std::move(scene_->lights);
    scene_->lights = fileLights_;
    if (applyLighting(*scene_, lighting)) state.ambient = glm::vec3(kDefaultSkyRadiance);
    sceneLights_ = std::move(scene_->lights);
    scene_->lights = current;
    litWith_ = lighting;
    if (state.lightsEdited) state.sceneLights = sceneLights_;  // what "reset" returns to; the edited list stays
    else resetLights(state, sceneLights_);
}

void ViewSession::syncLights(const ViewState& state) {
    const std::vector<Light> lights = effectiveLights(state, sceneLights_);
    const std::string key = lightsKey(lights);
    if (key == lightsKey_) return;
    // The renderers survive: each pass that holds lights (shadow maps, the path tracer's buffers)
    // takes them again, and progressive passes start over.
    scene_->lights = lights;
    lightsKey_ = key;
    for (PaneView& p : panes_) {
        if (p.renderer) p.renderer->lightsChanged();
        if (p.reduced) p.reduced->lightsChanged();
    }
    for (auto& [refKey, ref] : references_) {
        ref.renderer->lightsChanged();
        ref.image = ImageF{};
    }
}

void ViewSession::renderFrame(const ViewState& state, int viewWidth, int viewHeight) {
    gpuMsCollected_ = 0.0;
    if (!scene_) return;
    ++frame_;
    syncLights(state);
    const int count = paneCount(state.mode);
    for (int i = count; i < kMaxPanes; ++i) panes_[i] = PaneView{};  // hidden panes hold nothing
    visible_ = count;
    paneSize_ = paneRenderSize(state, viewWidth, viewHeight);
    CameraMatrices camera;
    try {
        camera = viewCameraMatrices(state, *scene_, float(paneSize_.x) / float(paneSize_.y));
    } catch (const std::exception& e) {
        lastError_ = describe(e);
        for (int i = 0; i < count; ++i) panes_[i].shown = 0;
        return;
    }
    for (int i = 0; i < count; ++i) renderPane(state, i, camera);
    // References: the ones in use stay; at most four others are kept for coming back to.
    while (references_.size() > size_t(kMaxPanes)) {
        auto oldest = references_.begin();
        for (auto it = references_.begin(); it != references_.end(); ++it)
            if (it->second.lastUsed < oldest->second.lastUsed) oldest = it;
        if (oldest->second.lastUsed == frame_) break;
        references_.erase(oldest);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ViewSession::renderPane(const ViewState& state, int index, const CameraMatrices& camera) {
    PaneView& p = panes_[index];
    const RenderSettings want = paneSettings(state, index, paneSize_);
    const std::string key = structuralKey(want);
    if (!p.renderer || requiresRebuild(p.renderer->settings(), want)) {
        if (key == p.failedKey) {
            p.shown = 0;
            return;
        }
        p = PaneView{};  // the old renderer goes first: never two of one pane in GPU memory
        try {
            p.renderer = std::make_unique<Renderer>(*scene_, want);
            ++rebuilds_;
        } catch (const std::exception& e) {
            p.renderer.reset();
            p.failedKey = key;
            p.status = describe(e);
            lastError_ = "pane " + std::to_string(index) + ": " + p.status;
            return;
        }
    }
    Renderer& r = *p.renderer;
    try {
        const PaneDisplay display = state.panes[index].display;
        p.movingFrames = p.cameraSet && !sameCamera(p.lastCamera, camera) ? p.movingFrames + 1 : 0;
        p.lastCamera = camera;
        r.setLiveSettings(want);
        if (!p.cameraSet || !sameCamera(p.camera, camera)) {
            r.setCamera(camera);
            p.camera = camera;
            p.cameraSet = true;
        }
        // Heatmaps compare full frames only.
        const float scale =
            display == PaneDisplay::Heatmap ? 1.0f : std::min(budgetScale(p.fullFrameMs, frameBudgetMs(state)), p.scaleCap);
        const bool moving = p.movingFrames > 0, converging = !r.settled();
        if (scale < 1.0f && (moving || (converging && !reducedSettled(p, scale, camera)))) {
            renderReducedFrame(state, index, camera, scale, frameBudgetMs(state));
            return;
        }
        if (!r.settled()) {  // a settled renderer would reproduce the frame it shows
            r.renderFrame();
            ++framesRendered_;
        }
        collectTimings(p);
        p.status = progressText(r);
        p.heatmapWanted = display == PaneDisplay::Heatmap;
        if (display == PaneDisplay::Heatmap) {
            p.scale = 1.0f;
            p.shownSize = paneSize_;
            updateHeatmap(state, index, camera);
        } else if (scale < 1.0f && !r.settled() && reducedSettled(p, scale, camera)) {
            // Refining: the settled reduced image stays on show until the full one has settled.
            p.shown = p.reduced->frameTexture("display");
            p.shownSize = glm::ivec2(p.reduced->settings().width, p.reduced->settings().height);
            p.scale = scale;
            p.status = "refining at full scale" + (p.status.empty() ? "" : ": " + p.status);
        } else {
            p.scale = 1.0f;
            p.shownSize = paneSize_;
            p.shown = r.frameTexture("display");
            if (scale < 1.0f && r.settled()) prepareReducedFrame(state, index, camera, scale);
        }
    } catch (const std::exception& e) {
        PaneView failed;
        failed.failedKey = key;
        failed.status = describe(e);
        lastError_ = "pane " + std::to_string(index) + ": " + failed.status;
        p = std::move(failed);
    }
}

// Whether the pane's reduced renderer holds a finished image of this camera at this scale.
bool ViewSession::reducedSettled(const PaneView& p, float scale, const CameraMatrices& camera) const {
    if (!p.reduced || !sameCamera(p.reducedCamera, camera)) return false;
    const glm::ivec2 size = scaledSize(paneSize_, scale);
    return p.reduced->settings().width == size.x && p.reduced->settings().height == size.y && p.reduced->settled();
}

// Whether the pane's reduced renderer is missing or was built for other settings than `want`.
bool ViewSession::reducedNeedsBuild(const PaneView& p, const RenderSettings& want) const {
    return !p.reduced || requiresRebuild(p.reduced->settings(), want);
}

// The pane's reduced renderer at `scale` of its size (built on first use or at another scale,
// kept for the next), given the camera.
Renderer& ViewSession::reducedRenderer(const ViewState& state, int index, const CameraMatrices& camera, float scale) {
    PaneView& p = panes_[index];
    const RenderSettings want = paneSettings(state, index, scaledSize(paneSize_, scale));
    if (reducedNeedsBuild(p, want)) {
        p.reduced.reset();  // never two reduced renderers of one pane in GPU memory
        p.reduced = std::make_unique<Renderer>(*scene_, want);
        p.reducedCamera = CameraMatrices{};
        ++rebuilds_;
    }
    Renderer& m = *p.reduced;
    m.setLiveSettings(want);
    if (!sameCamera(p.reducedCamera, camera)) {  // a camera set again would restart its convergence
        m.setCamera(camera);
        p.reducedCamera = camera;
    }
    return m;
}

// One frame of the reduced renderer unless it has settled; its timings count in the frame's GPU
// time, not in the pass table. Returns the GPU ms per frame of the timings that arrived (0: none).
double ViewSession::renderReduced(Renderer& m) {
    if (!m.settled()) {
        m.renderFrame();
        ++framesRendered_;
    }
    double frames = 0.0, ms = 0.0;  // the reduced frames whose timings arrived now, and their GPU ms
    for (const auto& pass : m.passes()) {
        frames = std::max(frames, double(pass->timer.samples.size()));
        for (double t : pass->timer.samples) ms += t;
        pass->timer.clear();
    }
    gpuMsCollected_ += ms;
    return frames > 0.0 ? ms / frames : 0.0;
}

// The pane's settings at `scale` of its size, through its reduced renderer, shown.
void ViewSession::renderReducedFrame(const ViewState& state, int index, const CameraMatrices& camera, float scale,
                                     double budgetMs) {
    PaneView& p = panes_[index];
    Renderer& m = reducedRenderer(state, index, camera, scale);
    const double frameMs = renderReduced(m);
    // Part of a frame does not shrink with its pixels (probe updates, a volume's light): a reduced
    // frame still over the budget lowers the scale the pane may use, down to an eighth.
    if (frameMs > budgetMs && budgetMs > 0.0) p.scaleCap = std::max(0.125f, 0.5f * scale);
    p.shown = m.frameTexture("display");
    p.shownSize = scaledSize(paneSize_, scale);
    p.scale = scale;
    const std::string progress = progressText(m);
    p.status = scaleLabel(scale) + " scale (" + (p.movingFrames > 0 ? "moving" : "converging") + ")" +
               (progress.empty() ? "" : ": " + progress);
}

// A pane at rest over the budget gets its reduced renderer, and that renderer its first frame (vct
// voxelizes in it), before the first move: the move then starts within the budget. Once per scale.
void ViewSession::prepareReducedFrame(const ViewState& state, int index, const CameraMatrices& camera, float scale) {
    if (!reducedNeedsBuild(panes_[index], paneSettings(state, index, scaledSize(paneSize_, scale)))) return;
    renderReduced(reducedRenderer(state, index, camera, scale));
}

void ViewSession::collectTimings(PaneView& p) {
    const auto& passes = p.renderer->passes();
    if (p.passes.size() != passes.size()) {
        p.passes.assign(passes.size(), PassHistory{});
        for (size_t k = 0; k < passes.size(); ++k) p.passes[k].pass = passes[k]->name();
    }
    bool fresh = false;
    float total = 0.0f;
    double working = 0.0;  // the passes that worked in the last frame: what the next one costs
    const auto& owners = p.renderer->memory().bytesByOwner;
    for (size_t k = 0; k < passes.size(); ++k) {
        gl::GpuTimer& timer = passes[k]->timer;  // read and cleared: bounded memory
        for (size_t i = 0; i < timer.samples.size(); ++i) {
            push(p.passes[k].ms, float(timer.samples[i]));
            gpuMsCollected_ += timer.samples[i];
            if (i >= timer.worked.size() || timer.worked[i]) p.passes[k].workedMs = timer.samples[i];
        }
        fresh = fresh || !timer.samples.empty();
        timer.clear();
        for (auto& step : passes[k]->steps.steps) step.second->clear();
        if (!p.passes[k].ms.empty()) total += p.passes[k].ms.back();
        auto it = owners.find(p.passes[k].pass);
        p.passes[k].bytes = it == owners.end() ? 0 : it->second;
        p.passes[k].cached = p.renderer->skippedLastFrame()[k] || passes[k]->reusedLastFrame();
        if (!p.passes[k].cached) working += p.passes[k].workedMs;
    }
    if (fresh) {
        push(p.totalMs, total);
        p.fullFrameMs = working;
    }
}

GLuint ViewSession::ensureDisplay(PaneView& p) {
    if (!p.display.id() || p.display.width != paneSize_.x || p.display.height != paneSize_.y)
        p.display = gl::createTexture2D({nullptr, "view"}, GL_RGBA8, paneSize_.x, paneSize_.y);
    return p.display.id();
}

namespace {
// References are shared by every pane that compares against the same path-traced image.
std::string referenceKey(const RenderSettings& rs) {
    return structuralKey(rs) + "|" + std::to_string(int(rs.diffuse)) + "|" + std::to_string(int(rs.specular));
}
}  // namespace

ViewSession::Reference* ViewSession::reference(const ViewState& state, int index, const CameraMatrices& camera) {
    const RenderSettings rs = referenceSettings(state, index, paneSize_);
    const std::string key = referenceKey(rs);
    auto it = references_.find(key);
    if (it == references_.end()) {
        Reference ref;
        ref.renderer = std::make_unique<Renderer>(*scene_, rs);
        ++rebuilds_;
        ref.renderer->setCamera(camera);
        ref.camera = camera;
        it = references_.emplace(key, std::move(ref)).first;
    }
    Reference& ref = it->second;
    if (!sameCamera(ref.camera, camera)) {
        ref.renderer->setCamera(camera);
        ref.camera = camera;
        ref.image = ImageF{};
    }
    if (ref.image.rgba.empty() && ref.lastUsed != frame_) {  // a sample per frame, however many panes use it
        ref.renderer->renderFrame();
        for (const auto& pass : ref.renderer->passes()) {
            for (double ms : pass->timer.samples) gpuMsCollected_ += ms;
            pass->timer.clear();
        }
        if (ref.renderer->converged()) ref.image = ref.renderer->readHdr();
    }
    ref.lastUsed = frame_;
    return &ref;
}

void ViewSession::updateHeatmap(const ViewState& state, int index, const CameraMatrices& camera) {
    PaneView& p = panes_[index];
    Renderer& r = *p.renderer;
    p.shown = r.frameTexture("display");  // until the heatmap exists
    const PaneState& pane = state.panes[index];
    if (!physicallyBased(pane.diffuse, pane.specular)) {  // the image stays; the pane says why
        p.heatmapReady = false;
        p.heatmapWanted = false;  // nothing to wait for: the pane is settled
        p.status = "no heatmap: the path-traced reference renders physically based BRDFs only "
                   "(Lambert or Burley diffuse, GGX or no specular)";
        return;
    }
    Reference* ref = reference(state, index, camera);
    if (ref->image.rgba.empty()) {
        p.status = "reference " + std::to_string(ref->renderer->samplesDone()) + "/" +
                   std::to_string(state.referenceSpp) + " spp";
        p.heatmapReady = false;
        return;
    }
    if (!r.converged()) {
        p.heatmapReady = false;
        return;  // status says how far the pane is
    }
    char cam[64];
    std::snprintf(cam, sizeof cam, "%a,%a,%a", camera.position.x, camera.position.y, camera.position.z);
    const std::string key = structuralKey(r.settings()) + "|" + std::to_string(int(state.panes[index].diffuse)) + "|" +
                            std::to_string(int(state.panes[index].specular)) + "|" + std::to_string(int(state.tonemap)) +
                            "|" + std::to_string(state.exposureEV) + "|" + errorMetricName(state.heatmapMetric) + "|" +
                            cam + "|" + std::to_string(reinterpret_cast<uintptr_t>(ref));
    if (key != p.heatmapKey) {
        const ImageF test = r.readHdr();
        MetricOptions options;
        options.display = DisplaySettings{state.tonemap, state.exposureEV};
        const ErrorMap map = errorMap(test, ref->image, state.heatmapMetric, options);
        double sum = 0.0, sumSquares = 0.0;
        float largest = 0.0f;
        for (float v : map.values) {
            sum += v;
            sumSquares += double(v) * v;
            largest = std::max(largest, v);
        }
        const double n = double(std::max<size_t>(map.values.size(), 1));
        switch (state.heatmapMetric) {
            case ErrorMetric::Flip: p.metricValue = sum / n; p.metricName = "FLIP"; break;
            case ErrorMetric::Rmse: p.metricValue = std::sqrt(sumSquares / n); p.metricName = "RMSE"; break;
            case ErrorMetric::RelMse: p.metricValue = sum / n; p.metricName = "relMSE"; break;
            case ErrorMetric::Ssim: p.metricValue = 1.0 - sum / n; p.metricName = "SSIM"; break;
        }
        const bool unitRange = state.heatmapMetric == ErrorMetric::Flip || state.heatmapMetric == ErrorMetric::Ssim;
        p.heatmapMax = unitRange ? 1.0f : std::max(largest, 1e-12f);
        ImageU8 heat = heatmapImage(map, float(p.heatmapMax));
        overlayColorBar(heat);  // 0 at the left to heatmapMax at the right (the panel says the number)
        const GLuint tex = ensureDisplay(p);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        const size_t row = size_t(heat.width) * 4;
        for (int y = 0; y < heat.height; ++y)  // rows top to bottom -> GL's bottom-up
            glTextureSubImage2D(tex, 0, 0, heat.height - 1 - y, heat.width, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                                heat.rgba.data() + row * y);
        p.heatmapKey = key;
        p.heatmapReady = true;
    }
    p.shown = p.display.id();
}

void ViewSession::drawToFramebuffer(const ViewState& state, int x, int y, int w, int h) const {
    if (visible_ == 0 || w <= 0 || h <= 0) return;
    const int sw = paneSize_.x, sh = paneSize_.y;
    // Source rectangles in pane pixels; a reduced frame's texture is smaller by its scale.
    if (!readFbo_) readFbo_ = gl::createFramebuffer();  // not in the constructor: a session opens its scene before GL
    auto blit = [&](const PaneView& p, int sx0, int sy0, int sx1, int sy1, int dx0, int dy0, int dx1, int dy1) {
        if (!p.shown || sx1 <= sx0 || dx1 <= dx0) return;
        const glm::dvec2 k = glm::dvec2(p.shownSize) / glm::dvec2(sw, sh);
        glNamedFramebufferTexture(readFbo_.id(), GL_COLOR_ATTACHMENT0, p.shown, 0);
        glBlitNamedFramebuffer(readFbo_.id(), 0, int(std::lround(sx0 * k.x)), int(std::lround(sy0 * k.y)),
                               int(std::lround(sx1 * k.x)), int(std::lround(sy1 * k.y)), dx0, dy0, dx1, dy1,
                               GL_COLOR_BUFFER_BIT, GL_LINEAR);
    };
    glDisable(GL_SCISSOR_TEST);
    if (state.mode == ViewMode::Single || visible_ == 1) {
        blit(panes_[0], 0, 0, sw, sh, x, y, x + w, y + h);
    } else if (state.mode == ViewMode::Split) {
        const int sx = int(std::lround(state.divider * sw)), dx = int(std::lround(state.divider * w));
        blit(panes_[0], 0, 0, sx, sh, x, y, x + dx, y + h);
        blit(panes_[1], sx, 0, sw, sh, x + dx, y, x + w, y + h);
    } else {
        const std::vector<PaneRect> rects = paneRects(ViewMode::Grid, w, h);
        for (int i = 0; i < visible_ && i < int(rects.size()); ++i) {
            const PaneRect& r = rects[i];
            const int y0 = y + (h - r.y - r.h);
            blit(panes_[i], 0, 0, sw, sh, x + r.x, y0, x + r.x + r.w, y0 + r.h);
        }
    }
    glNamedFramebufferTexture(readFbo_.id(), GL_COLOR_ATTACHMENT0, 0, 0);
}

bool ViewSession::settled() const {
    for (int i = 0; i < visible_; ++i) {
        const PaneView& p = panes_[i];
        if (!p.renderer) continue;  // failed: nothing more will happen
        if (!p.renderer->converged() || (p.heatmapWanted && !p.heatmapReady) || p.scale < 1.0f) return false;
    }
    return true;
}

std::optional<ViewSession::PixelReadout> ViewSession::inspectPixel(const ViewState& state, int index,
                                                                   glm::ivec2 pixel) const {
    if (index < 0 || index >= visible_ || !panes_[index].renderer) return std::nullopt;
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= paneSize_.x || pixel.y >= paneSize_.y) return std::nullopt;
    const ImageF image = panes_[index].renderer->readHdr();
    if (image.width != paneSize_.x || image.height != paneSize_.y) return std::nullopt;
    PixelReadout out;
    out.radiance = glm::make_vec3(image.at(pixel.x, pixel.y));
    const auto ref = references_.find(referenceKey(referenceSettings(state, index, paneSize_)));
    if (ref != references_.end() && ref->second.image.width == paneSize_.x && ref->second.image.height == paneSize_.y &&
        sameCamera(ref->second.camera, panes_[index].camera)) {
        out.hasReference = true;
        out.reference = glm::make_vec3(ref->second.image.at(pixel.x, pixel.y));
    }
    return out;
}

ImageU8 ViewSession::readPane(int index) const {
    const GLuint tex = index < visible_ ? panes_[index].shown : 0;
    if (tex) {
        const glm::ivec2 shown = panes_[index].shownSize;
        const ImageU8 img = readTextureBytes(tex, shown.x, shown.y);
        return shown == paneSize_ ? img : resizeNearest(img, paneSize_.x, paneSize_.y);  // a reduced frame
    }
    ImageU8 img;  // a pane with nothing shown yet: opaque black
    img.width = paneSize_.x;
    img.height = paneSize_.y;
    img.rgba.assign(size_t(img.width) * img.height * 4, 0);
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
    return img;
}

ImageU8 ViewSession::composite(const ViewState& state, bool labels) const {
    const int w = paneSize_.x, h = paneSize_.y;
    auto label = [&](Canvas& c, int pane, int x, int y, bool alignRight) {
        if (!labels) return;
        std::string text = paneLabel(state, pane);
        const PaneView& p = panes_[pane];
        if (p.heatmapReady) text += "  " + p.metricName + " " + formatPaneMetric(p.metricValue);
        // Twice the font size where it fits in the pane's share of the width.
        const int room = state.mode == ViewMode::Split ? w / 2 : w;
        const int scale = Canvas::textWidth(text, 2) + 8 <= room ? 2 : 1;
        const int tw = Canvas::textWidth(text, scale) + 8, th = 8 * scale + 6;
        const int x0 = alignRight ? x - tw : x;
        c.fillRect(x0, y, x0 + tw, y + th, Rgba{0, 0, 0, 255});
        c.text(x0 + 4, y + 3, text, Rgba{255, 255, 255, 255}, scale);
    };
    if (state.mode == ViewMode::Single || visible_ <= 1) {
        Canvas c(w, h, Rgba{0, 0, 0, 255});
        c.blit(readPane(0), 0, 0);
        label(c, 0, 0, 0, false);
        return c.image;
    }
    if (state.mode == ViewMode::Split) {
        Canvas c(w, h, Rgba{0, 0, 0, 255});
        const ImageU8 left = readPane(0), right = readPane(1);
        const int split = int(std::lround(state.divider * w));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const ImageU8& src = x < split ? left : right;
                std::copy_n(&src.rgba[(size_t(y) * w + x) * 4], 4, &c.image.rgba[(size_t(y) * w + x) * 4]);
            }
        c.fillRect(split - 1, 0, split + 1, h, Rgba{255, 255, 255, 255});
        label(c, 0, 0, 0, false);
        label(c, 1, w, 0, true);
        return c.image;
    }
    Canvas c(2 * w, 2 * h, Rgba{0, 0, 0, 255});
    for (int i = 0; i < visible_; ++i) {
        const int x = (i % 2) * w, y = (i / 2) * h;
        c.blit(readPane(i), x, y);
        label(c, i, x, y, false);
    }
    return c.image;
}

nlohmann::ordered_json ViewSession::timingsJson() const {
    nlohmann::ordered_json panes = nlohmann::ordered_json::array();
    for (int i = 0; i < visible_; ++i) {
        const PaneView& p = panes_[i];
        nlohmann::ordered_json j;
        j["status"] = p.status;
        if (p.renderer) {
            j["samples"] = p.renderer->samplesDone();
            j["converged"] = p.renderer->converged();
            j["gpu_bytes_total"] = p.renderer->memory().total();
        }
        j["gpu_ms_median"] = median(p.totalMs);
        for (const PassHistory& h : p.passes)
            j["passes"].push_back({{"pass", h.pass},
                                   {"gpu_ms_last", h.ms.empty() ? 0.0f : h.ms.back()},
                                   {"gpu_ms_median", median(h.ms)},
                                   {"frames", h.ms.size()},
                                   {"gpu_bytes", h.bytes},
                                   {"cached", h.cached}});
        if (p.heatmapReady) j["error_vs_reference"] = {{"metric", p.metricName}, {"value", p.metricValue}};
        panes.push_back(j);
    }
    return panes;
}

std::string ViewSession::writeScreenshot(const ViewState& state, const std::string& dir,
                                         const std::string& glRenderer) const {
    if (!scene_ || visible_ == 0) throw Error("screenshot: nothing rendered yet");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir)) throw Error("screenshot: cannot create directory '" + dir + "'");
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
    std::string method = state.panes[0].gi;
    if (state.mode == ViewMode::Split) method += "-vs-" + state.panes[1].gi;
    if (state.mode == ViewMode::Grid) method = "grid";
    const std::string sceneName = fileSafe(scene_->name.empty() ? state.scene : scene_->name);
    std::string stem = (fs::path(dir) / (sceneName + "_" + fileSafe(method) + "_" + stamp)).string();
    for (int n = 2; fs::exists(stem + ".png") || fs::exists(stem + ".json"); ++n)
        stem = (fs::path(dir) / (sceneName + "_" + fileSafe(method) + "_" + stamp + "_" + std::to_string(n))).string();

    const ImageU8 image = composite(state, state.mode != ViewMode::Single);
    nlohmann::ordered_json side;
    side["image"] = fs::path(stem + ".png").filename().string();
    side["gl_renderer"] = glRenderer;
    side["render_size"] = {paneSize_.x, paneSize_.y};
    side["settings"] = viewStateToJson(state);  // loadable: gisandbox view/render --settings
    nlohmann::ordered_json panes = timingsJson();
    for (int i = 0; i < visible_; ++i) {
        panes[i]["label"] = paneLabel(state, i);
        panes[i]["render_settings"] = renderSettingsToJson(paneSettings(state, i, paneSize_));
    }
    side["panes"] = panes;
    // The image and its sidecar together or not at all.
    writeFilesAtomically({{stem + ".png", encodePng(image)}, {stem + ".json", side.dump(2) + "\n"}});
    return stem + ".png";
}

int64_t ViewSession::gpuBytes() const {
    int64_t sum = 0;
    for (const PaneView& p : panes_) {
        if (p.renderer) sum += p.renderer->memory().total();
        if (p.reduced) sum += p.reduced->memory().total();
        if (p.display.id()) sum += int64_t(p.display.width) * p.display.height * 4;
    }
    for (const auto& [key, ref] : references_) sum += ref.renderer->memory().total();
    return sum;
}

}  // namespace gis::view
