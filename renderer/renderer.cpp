#include "renderer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "debug_view.h"
#include "emitter_settings.h"
#include "emitters/emitter_lights.h"
#include "environment_gpu.h"
#include "gi/method.h"
#include "gi/memory_budget.h"
#include "passes/gbuffer_pass.h"
#include "passes/lighting_pass.h"
#include "passes/shadow_pass.h"
#include "services/scene_services.h"

namespace gis {

namespace {
// The barrier after a pass that wrote through image stores or storage buffers: its outputs may be
// read next as textures (sampled, loaded as images, attached, read back) or as buffers (storage or
// uniform blocks, read back), so those bits for the kinds it outputs, and no others.
GLbitfield barrierBitsFor(const Pass& pass, const Frame& frame) {
    GLbitfield bits = 0;
    for (const std::string& name : pass.outputs()) {
        const auto it = frame.resources.find(name);
        if (it == frame.resources.end()) continue;
        bits |= it->second.kind == ResourceKind::Buffer
                    ? GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT
                    : GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                          GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT;
    }
    return bits;
}
}  // namespace

namespace {
void checkSettings(const RenderSettings& s) {
    auto range = [](const char* what, int v, int lo, int hi) {
        if (v < lo || v > hi)
            throw Error(std::string(what) + " " + std::to_string(v) + " is out of range [" + std::to_string(lo) +
                        ", " + std::to_string(hi) + "]");
    };
    range("image width", s.width, 1, 16384);
    range("image height", s.height, 1, 16384);
    range("shadow map size", s.shadowMapSize, 16, 16384);
    range("shadow cube size", s.shadowCubeSize, 16, 8192);
    if (!std::isfinite(s.exposureEV) || std::abs(s.exposureEV) > 64.0f)
        throw Error("exposure " + std::to_string(s.exposureEV) + " EV is out of range [-64, 64]");
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(s.ambient[c]) || s.ambient[c] < 0.0f)
            throw Error("ambient radiance must be finite and non-negative");
    if (s.background)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite((*s.background)[c]) || (*s.background)[c] < 0.0f)
                throw Error("background radiance must be finite and non-negative");
    checkEnvironmentChoice(s.background.has_value(), s.environment);
    checkEnvironmentRotation(s.environmentRotation, s.environment);
    range("samples per frame", s.samplesPerFrame, 1, 1 << 16);
    const GiMethod& method = giMethod(s.gi);
    if (method.physicalBrdfsOnly && !physicallyBased(s.diffuse, s.specular))
        throw Error("the " + method.name + " method takes the physically based models only: --diffuse lambert|burley, "
                    "--specular ggx|none");
    checkParams(s.params);
    checkViewOfMethod(s.gi, s.view);
    if (int(s.diffuse) < 0 || int(s.diffuse) >= kDiffuseModelCount) throw Error("diffuse BRDF model out of range");
    if (int(s.specular) < 0 || int(s.specular) >= kSpecularModelCount) throw Error("specular BRDF model out of range");
}

// A material's BRDF override must name a model or be -1 (the render's setting).
void checkMaterials(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.diffuseModel < -1 || m.diffuseModel >= kDiffuseModelCount || m.specularModel < -1 ||
            m.specularModel >= kSpecularModelCount)
            throw Error("material '" + m.name + "': BRDF model override (" + std::to_string(m.diffuseModel) + ", " +
                        std::to_string(m.specularModel) + ") is out of range");
}
}  // namespace

Renderer::Renderer(const Scene& scene, const RenderSettings& settings) : settings_(settings) {
    checkSettings(settings_);
    checkMaterials(scene);
    checkMemoryBudget(scene, settings_);  // before any allocation: refuse what cannot fit
    camera_ = cameraMatrices(scene, settings_.camera, float(settings_.width) / float(settings_.height));
    gpuScene_ = std::make_unique<GpuScene>(scene, ledger_);
    services_ = std::make_unique<SceneServices>(*gpuScene_, ledger_, camera_);
    environment_ = std::make_unique<GpuEnvironment>(settings_.environment, ledger_);
    const GiMethod& method = giMethod(settings_.gi);
    const int w = settings_.width, h = settings_.height;
    const bool deferred = method.pipeline == MethodPipeline::Deferred;
    const bool gbufferView = settings_.view.rfind("gbuffer.", 0) == 0;
    // A method that bakes the lights' direct light (lightmap.mode=all): the frame draws none itself.
    const bool lightsBaked = method.bakesDirectLight && method.bakesDirectLight(settings_);
    if (deferred) passes_.push_back(std::make_unique<ShadowPass>(*gpuScene_, settings_, !lightsBaked, ledger_));
    if (deferred || gbufferView) passes_.push_back(std::make_unique<GBufferPass>(scene, w, h, ledger_));
    // Emissive triangles and the environment as lights of the direct pass: only when there are
    // any (no cost otherwise).
    const bool environmentLight = environmentIsLight(scene, settings_);
    if (deferred && !lightsBaked &&
        ((emittersAreLights(scene, settings_) && services_->rays().emitterCount > 0) || environmentLight))
        passes_.push_back(std::make_unique<EmitterLightPass>(services_->rays(), settings_, environmentLight, ledger_));
    MethodBuild build{scene, settings_, *services_, ledger_, passes_};
    method.addPasses(build);

    // Every declared input must be the output of an earlier pass; no name has two writers.
    std::set<std::string> produced;
    auto declare = [&produced](const Pass& pass) {
        for (const std::string& in : pass.inputs())
            if (!produced.count(in))
                throw Error(std::string("internal: pass '") + pass.name() + "' reads '" + in +
                            "' before any pass writes it");
        for (const std::string& out : pass.outputs())
            if (!produced.insert(out).second)
                throw Error(std::string("internal: pass '") + pass.name() + "' writes '" + out +
                            "', which an earlier pass already writes");
    };
    for (const auto& pass : passes_) declare(*pass);
    if (deferred) {
        passes_.push_back(std::make_unique<LightingPass>(w, h, settings_.hdr32, produced, !lightsBaked, ledger_));
        declare(*passes_.back());
    }
    passes_.push_back(std::make_unique<TonemapPass>(w, h, ledger_));
    declare(*passes_.back());
    checkViewOffered(settings_.view);
    ensureDebugTarget();
    // One counter per pass and one for the debug view drawn after them.
    if (countingNonFinite())
        nonFinite_ = std::make_unique<NonFiniteCounter>(int(passes_.size()) + 1, gl::MemoryScope{&ledger_, "checks"});
    gl::checkOutOfMemory("creating the render passes");
}

Renderer::~Renderer() = default;

void Renderer::checkViewOffered(const std::string& view) const {
    const std::vector<DebugViewDesc> offered = views();  // "final" first
    std::string names;
    for (const DebugViewDesc& v : offered) {
        if (v.name == view) return;
        names += (names.empty() ? "" : ", ") + v.name;
    }
    throw Error("--view '" + view + "' is not produced by --gi " + settings_.gi + " (available: " + names + ")");
}

// The debug view's target, made for the first view that is not "final" (at build or on a switch).
void Renderer::ensureDebugTarget() {
    if (settings_.view != "final" && !debugTarget_.id())
        debugTarget_ = gl::createTexture2D({&ledger_, "debug view"}, GL_RGBA16F, settings_.width, settings_.height);
}

std::vector<DebugViewDesc> Renderer::views() const {
    std::vector<DebugViewDesc> all{{"final", "the lit, tone-mapped image"}};
    // A name two passes offer is the first's, as drawDebugView draws it: a method's own "ao" (the
    // occlusion it computed) before the lighting pass's (that times the material's occlusion).
    auto offered = [&all](const std::string& name) {
        return std::any_of(all.begin(), all.end(), [&name](const DebugViewDesc& v) { return v.name == name; });
    };
    for (const auto& pass : passes_)
        for (const DebugViewDesc& v : pass->debugViews())
            if (!offered(v.name)) all.push_back(v);
    // G-buffer displays exist for every method: methods without a G-buffer build one on request.
    if (!std::any_of(passes_.begin(), passes_.end(), [](const auto& p) { return std::string(p->name()) == "gbuffer"; }))
        for (const DebugViewDesc& v : GBufferPass::views()) all.push_back(v);
    return all;
}

int Renderer::samplesDone() const {
    for (const auto& pass : passes_)
        if (pass->progress().target > 0) return pass->progress().done;
    return 1;
}

bool Renderer::converged() const {
    for (const auto& pass : passes_) {
        const Pass::Progress p = pass->progress();
        if (p.done < p.target && !p.held) return false;
    }
    return true;
}

bool Renderer::settled() const {
    return frameIndex_ > 0 && !redrawPending_ &&
           std::all_of(passes_.begin(), passes_.end(), [](const auto& p) { return p->settled(); });
}

// A settled pass is skipped only when no pass before it executed this frame that outputs one of its
// inputs: invalidate() reaches every pass, so this is the guard for a producer that changes its
// outputs without a Change (a pass still converging, ReSTIR accumulating).
bool Renderer::canSkip(const Pass& pass, const std::set<std::string>& reproduced) const {
    if (!skipSettled_ || frameIndex_ == 0 || !pass.settled()) return false;
    for (const std::string& in : pass.inputs())
        if (reproduced.count(in)) return false;
    return true;
}

// What a skipped pass put last frame stays in the frame for its consumers; its timers record a
// frame without work, so --timings and the panel show it cached.
void Renderer::keepOutputs(Pass& pass, Frame& frame) const {
    for (const std::string& out : pass.outputs()) {
        const auto it = passResources_.find(out);
        if (it != passResources_.end()) frame.resources[out] = it->second;
    }
    pass.timer.begin();
    pass.timer.end(false);
    for (auto& step : pass.steps.steps) {
        step.second->begin();
        step.second->end(false);
    }
}

void Renderer::renderFrame() {
    Frame frame{settings_, *gpuScene_, *services_, camera_, {}, frameIndex_};
    frame.environment = environment_.get();
    std::set<std::string> reproduced;  // outputs a pass wrote anew this frame
    skipped_.assign(passes_.size(), false);
    for (size_t k = 0; k < passes_.size(); ++k) {
        Pass& pass = *passes_[k];
        if (canSkip(pass, reproduced)) {
            keepOutputs(pass, frame);
            skipped_[k] = true;
            continue;
        }
        frame.steps = &pass.steps;
        frame.pass = &pass;
        if (nonFinite_) nonFinite_->bind(int(k));
        pass.timer.begin();
        pass.execute(frame);
        pass.timer.end(!pass.reusedLastFrame());
        // Executed, even if it reused a cache: its consumers run too (conservative, and cheap:
        // a pass that runs while settled was forced by an input of its own).
        for (const std::string& out : pass.outputs()) reproduced.insert(out);
        if (pass.writesImagesOrBuffers()) glMemoryBarrier(barrierBitsFor(pass, frame));
    }
    frame.pass = nullptr;
    if (nonFinite_) nonFinite_->collect();
    ++frameIndex_;
    redrawPending_ = false;
    hdr_ = frame.texture(resource::kRadiance);
    ldr_ = frame.texture(resource::kDisplay);
    if (nonFinite_) nonFinite_->bind(int(passes_.size()));
    passResources_ = frame.resources;  // before a debug view takes "display" over
    if (settings_.view != "final") drawDebugView(frame);
    frameResources_ = frame.resources;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (const auto& pass : passes_) {
        pass->timer.collect(false);
        for (auto& step : pass->steps.steps) step.second->collect(false);
    }
    gl::checkOutOfMemory("rendering a frame");
}

std::vector<uint64_t> Renderer::nonFiniteCounts() const {
    std::vector<uint64_t> counts;
    if (nonFinite_)
        for (size_t k = 0; k <= passes_.size(); ++k) counts.push_back(nonFinite_->total(int(k)));
    return counts;
}

std::string Renderer::nonFiniteReport() const {
    std::string report;
    const std::vector<uint64_t> counts = nonFiniteCounts();
    for (size_t k = 0; k < counts.size(); ++k)
        if (counts[k] > 0)
            report += std::string(report.empty() ? "" : "; ") +
                      (k < passes_.size() ? "pass '" + std::string(passes_[k]->name()) + "'" : "the debug view") +
                      " replaced " +
                      std::to_string(counts[k]) + " NaN/Inf values by 0";
    return report;
}

// A debug view replaces both outputs: its values are written as they are (no tone mapping).
void Renderer::drawDebugView(Frame& frame) {
    for (const auto& pass : passes_)
        for (const DebugViewDesc& v : pass->debugViews())
            if (v.name == settings_.view) {
                if (!channelDisplay_) channelDisplay_ = std::make_unique<ChannelDisplay>();
                frame.channelDisplay = channelDisplay_.get();
                frame.pass = pass.get();  // its view reads only what the pass declared
                pass->drawDebugView(v.name, frame, debugTarget_.id());
                frame.pass = nullptr;
                frame.put(resource::kDisplay, debugTarget_);
                hdr_ = ldr_ = debugTarget_.id();
                return;
            }
}

void Renderer::setCamera(const CameraMatrices& camera) {
    camera_ = camera;
    invalidate(ChangeCamera);
}

void Renderer::setLiveSettings(const RenderSettings& live) {
    if (requiresRebuild(settings_, live))
        throw Error("internal: setLiveSettings with a setting that needs a new renderer");
    Changes changes = 0;
    if (live.diffuse != settings_.diffuse || live.specular != settings_.specular) changes |= ChangeBrdfModels;
    if (live.params != settings_.params || live.ambient != settings_.ambient || live.exposureEV != settings_.exposureEV ||
        live.tonemap != settings_.tonemap || live.background != settings_.background)
        changes |= ChangeLiveParams;
    if (live.view != settings_.view) {
        // Another debug view of the same passes: drawn from what they hold, nothing they
        // accumulated starts over (the probes keep converging); the next frame draws it.
        checkViewOffered(live.view);
        redrawPending_ = true;
    }
    const int camera = settings_.camera;
    settings_ = live;
    settings_.camera = camera;
    checkSettings(settings_);
    ensureDebugTarget();
    if (changes) invalidate(changes);
}

void Renderer::lightsChanged() {
    services_->lightsChanged();
    invalidate(ChangeLights);
}

void Renderer::invalidate(Changes changes) {
    services_->invalidate(changes);
    for (const auto& pass : passes_) pass->invalidate(changes);
}

bool requiresRebuild(const RenderSettings& a, const RenderSettings& b) {
    if (a.width != b.width || a.height != b.height || a.gi != b.gi || a.shadowMapSize != b.shadowMapSize ||
        a.shadowCubeSize != b.shadowCubeSize || a.shadows != b.shadows || a.hdr32 != b.hdr32 || a.seed != b.seed ||
        a.samplesPerFrame != b.samplesPerFrame || a.environment != b.environment ||
        a.environmentRotation != b.environmentRotation)
        return true;
    // A deferred method's views are drawn from its passes' outputs and its G-buffer: switching
    // between them is live. A standalone method renders its term views itself (the path tracer's
    // `direct` traces other paths), and builds a G-buffer only for a G-buffer view.
    if (a.view != b.view && giMethod(a.gi).pipeline != MethodPipeline::Deferred) return true;
    // A background that is a light of the direct pass decides whether that pass exists and lights
    // the volume: a new one rebuilds, as a new map does.
    if (a.background != b.background && (environmentLightChosen(a) || environmentLightChosen(b)))
        return true;
    // A rebuild parameter of the method or of a shared table whose value differs (defaults included).
    auto differs = [&a, &b](const std::string& prefix, const std::vector<ParamDesc>& rows) {
        for (const ParamDesc& d : rows) {
            if (d.update != ParamUpdate::Rebuild) continue;
            const std::string key = prefix + "." + d.key;
            auto ia = a.params.find(key), ib = b.params.find(key);
            const ParamValue& va = ia == a.params.end() ? d.defaultValue : ia->second;
            const ParamValue& vb = ib == b.params.end() ? d.defaultValue : ib->second;
            if (va != vb) return true;
        }
        return false;
    };
    const GiMethod& m = giMethod(a.gi);
    if (differs(m.name, m.params)) return true;
    for (const ParamGroup& g : paramGroups())
        if (differs(g.name, g.params)) return true;
    return false;
}

GLuint Renderer::frameTexture(const std::string& name) const {
    auto it = frameResources_.find(name);
    return it == frameResources_.end() ? 0 : it->second.id;
}

ImageF readTextureFloat(GLuint texture, int width, int height) {
    ImageF img;
    img.width = width;
    img.height = height;
    img.rgba.resize(size_t(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgba.size() * sizeof(float)), img.rgba.data());
    flipVertically(img);
    return img;
}

ImageU8 readTextureBytes(GLuint texture, int width, int height) {
    ImageU8 img;
    img.width = width;
    img.height = height;
    img.rgba.resize(size_t(width) * height * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(img.rgba.size()), img.rgba.data());
    flipVertically(img);
    return img;
}

ImageF Renderer::readHdr() const {
    if (!hdr_) throw Error("internal: readHdr before renderFrame");
    return readTextureFloat(hdr_, settings_.width, settings_.height);
}

ImageU8 Renderer::readLdr() const {
    if (!ldr_) throw Error("internal: readLdr before renderFrame");
    return readTextureBytes(ldr_, settings_.width, settings_.height);
}

namespace {
// Median over the frames after warm-up in which the timer's pass did work, total over all of them.
PassTiming summarize(const std::string& name, const gl::GpuTimer& timer, int warmup) {
    PassTiming t;
    t.pass = name;
    const auto& s = timer.samples;
    if (!s.empty()) t.firstMs = s.front();
    std::vector<double> steady;
    for (size_t i = 0; i < s.size(); ++i) {
        const bool worked = i >= timer.worked.size() || timer.worked[i];
        if (!worked) continue;
        t.totalMs += s[i];
        ++t.workedFrames;
        if (int(i) >= warmup) steady.push_back(s[i]);
    }
    t.medianMs = median(steady);
    t.cached = steady.empty();
    return t;
}
}  // namespace

std::vector<PassTiming> Renderer::timings(int warmup) const {
    glFinish();
    std::vector<PassTiming> out;
    warmup = std::max(warmup, 0);
    for (const auto& pass : passes_) {
        pass->timer.collect(true);
        PassTiming t = summarize(pass->name(), pass->timer, warmup);
        auto it = ledger_.bytesByOwner.find(t.pass);
        t.bytes = it == ledger_.bytesByOwner.end() ? 0 : it->second;
        const Pass::Progress progress = pass->progress();
        t.samples = progress.target > 0 ? progress.done - progress.read : 0;
        t.rays = pass->raysTraced();
        out.push_back(t);
        for (const auto& [step, timer] : pass->steps.steps) {
            timer->collect(true);
            PassTiming st = summarize(std::string(pass->name()) + "/" + step, *timer, warmup);
            st.step = true;
            // A step that ran in some frames only (e.g. re-voxelize after a change): cached when
            // its pass worked but it did not.
            out.push_back(st);
        }
    }
    return out;
}

std::vector<double> Renderer::frameGpuMs() const {
    glFinish();
    std::vector<double> ms;
    for (const auto& pass : passes_) {
        pass->timer.collect(true);
        const gl::GpuTimer& t = pass->timer;
        if (ms.size() < t.samples.size()) ms.resize(t.samples.size(), 0.0);
        for (size_t i = 0; i < t.samples.size(); ++i)
            if (i >= t.worked.size() || t.worked[i]) ms[i] += t.samples[i];
    }
    return ms;
}

ProgramDesc brdfProbeProgram() { return {"brdf_probe", {"brdf_probe.comp"}, {}}; }

std::vector<ProgramDesc> allPrograms() {
    std::vector<ProgramDesc> all;
    for (auto list : {ShadowPass::programs(), GBufferPass::programs(), LightingPass::programs(), EmitterLightPass::programs(),
                      TonemapPass::programs(), ChannelDisplay::programs(), GpuEnvironment::programs()})
        all.insert(all.end(), list.begin(), list.end());
    for (const GiMethod& m : giMethods())
        if (m.programs) {
            const auto list = m.programs();
            all.insert(all.end(), list.begin(), list.end());
        }
    all.push_back(brdfProbeProgram());
    return all;
}

}  // namespace gis
