#include "renderer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "debug_view.h"
#include "memory_budget.h"
#include "passes/gbuffer_pass.h"
#include "passes/lighting_pass.h"
#include "passes/pathtrace_pass.h"
#include "passes/ssao_pass.h"
#include "passes/shadow_pass.h"

namespace gis {

namespace {
const char* const kDiffuseNames[kDiffuseModelCount] = {"lambert", "wrap", "toon", "burley"};
const char* const kSpecularNames[kSpecularModelCount] = {"ggx", "blinn", "toon", "none"};
}  // namespace

DiffuseModel parseDiffuse(const std::string& s) {
    for (int i = 0; i < kDiffuseModelCount; ++i)
        if (s == kDiffuseNames[i]) return DiffuseModel(i);
    throw Error("unknown diffuse BRDF '" + s + "' (expected lambert, wrap, toon or burley)");
}

SpecularModel parseSpecular(const std::string& s) {
    for (int i = 0; i < kSpecularModelCount; ++i)
        if (s == kSpecularNames[i]) return SpecularModel(i);
    throw Error("unknown specular BRDF '" + s + "' (expected ggx, blinn, toon or none)");
}

Tonemapper parseTonemapper(const std::string& s) {
    if (s == "aces") return Tonemapper::Aces;
    if (s == "linear") return Tonemapper::Linear;
    throw Error("unknown tonemapper '" + s + "' (expected aces or linear)");
}

std::string giMethodNames() { return "none, ssao, pathtrace, ao-reference"; }

void checkGiMethod(const std::string& s) {
    if (s != "none" && s != "ssao" && s != "pathtrace" && s != "ao-reference")
        throw Error("unknown GI method '" + s + "' (available: " + giMethodNames() + ")");
}

DebugView parseDebugView(const std::string& s) {
    if (s == "final") return DebugView::Final;
    if (s == "ao") return DebugView::AmbientOcclusion;
    throw Error("unknown view '" + s + "' (expected final or ao)");
}

CameraMatrices cameraMatrices(const Scene& scene, int cameraIndex, float aspect) {
    if (!scene.cameras.empty() && (cameraIndex < 0 || cameraIndex >= int(scene.cameras.size())))
        throw Error("camera " + std::to_string(cameraIndex) + " does not exist (the scene has " +
                    std::to_string(scene.cameras.size()) + ")");
    const Camera cam = scene.cameras.empty() ? defaultCamera(scene.bounds, aspect) : scene.cameras[cameraIndex];
    CameraMatrices m;
    m.view = glm::inverse(cam.cameraToWorld);
    m.position = glm::vec3(cam.cameraToWorld[3]);
    m.znear = cam.znear;
    m.zfar = cam.zfar;
    if (cam.orthographic) {
        // Keep the file's vertical extent; the width follows the viewport's aspect.
        m.proj = glm::ortho(-cam.ymag * aspect, cam.ymag * aspect, -cam.ymag, cam.ymag, cam.znear, cam.zfar);
    } else if (cam.zfar <= 0.0f) {
        m.proj = glm::infinitePerspective(cam.yfov, aspect, cam.znear);
    } else {
        m.proj = glm::perspective(cam.yfov, aspect, cam.znear, cam.zfar);
    }
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
    return m;
}

GLuint Frame::texture(const std::string& name) const {
    auto it = textures.find(name);
    if (it == textures.end()) throw Error("internal: no pass produced texture '" + name + "'");
    return it->second;
}

GLuint Frame::buffer(const std::string& name) const {
    auto it = buffers.find(name);
    if (it == buffers.end()) throw Error("internal: no pass produced buffer '" + name + "'");
    return it->second;
}

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
    range("samples per pixel", s.spp, 1, 1 << 20);
    range("samples per frame", s.samplesPerFrame, 1, 1 << 16);
    range("max bounces", s.maxBounces, 0, 1024);
    if (s.gi == "pathtrace" && ((s.diffuse != DiffuseModel::Lambert && s.diffuse != DiffuseModel::Burley) ||
                                (s.specular != SpecularModel::Ggx && s.specular != SpecularModel::None)))
        throw Error("the path tracer takes the physically based models only: --diffuse lambert|burley, "
                    "--specular ggx|none");
    range("AO samples", s.aoSamples, 1, 256);
    range("AO steps", s.aoSteps, 1, 64);
    if (!std::isfinite(s.aoRadius) || s.aoRadius < 0.0f || s.aoRadius > 1e30f)
        throw Error("AO radius must be finite and non-negative (0 = automatic)");
    if (!std::isfinite(s.aoBias) || s.aoBias < 0.0f || s.aoBias >= 1.0f)
        throw Error("AO bias must be in [0, 1) (a fraction of the radius)");
    if (!std::isfinite(s.aoPower) || s.aoPower <= 0.0f || s.aoPower > 64.0f)
        throw Error("AO power must be in (0, 64]");
    checkGiMethod(s.gi);
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
    if (settings_.aoRadius <= 0.0f)  // sized from the scene: 15% of its diagonal
        settings_.aoRadius = scene.bounds.empty() ? 1.0f : std::max(0.15f * glm::length(scene.bounds.extent()), 1e-6f);
    gpuScene_ = std::make_unique<GpuScene>(scene, ledger_);
    const int w = settings_.width, h = settings_.height;
    if (settings_.gi == "pathtrace") {
        passes_.push_back(std::make_unique<PathTracePass>(*gpuScene_, settings_, ledger_));
    } else if (settings_.gi == "ao-reference") {
        passes_.push_back(std::make_unique<AoReferencePass>(*gpuScene_, settings_, ledger_));
    } else {
        const bool ssao = settings_.gi == "ssao";
        passes_.push_back(std::make_unique<ShadowPass>(*gpuScene_, settings_, ledger_));
        passes_.push_back(std::make_unique<GBufferPass>(w, h, ledger_));
        if (ssao) passes_.push_back(std::make_unique<SsaoPass>(settings_, ledger_));
        passes_.push_back(
            std::make_unique<LightingPass>(w, h, int(scene.lights.size()), settings_.hdr32, ssao, ledger_));
    }
    passes_.push_back(std::make_unique<TonemapPass>(w, h, ledger_));

    // Every declared input must be the output of an earlier pass.
    std::set<std::string> produced;
    for (const auto& pass : passes_) {
        for (const std::string& in : pass->inputs())
            if (!produced.count(in))
                throw Error(std::string("internal: pass '") + pass->name() + "' reads '" + in +
                            "' before any pass writes it");
        for (const std::string& out : pass->outputs()) produced.insert(out);
    }
    gl::checkOutOfMemory("creating the render passes");
}

Renderer::~Renderer() = default;

int Renderer::samplesDone() const {
    for (const auto& pass : passes_)
        if (pass->progress().target > 0) return pass->progress().done;
    return 1;
}

bool Renderer::converged() const {
    for (const auto& pass : passes_)
        if (pass->progress().done < pass->progress().target) return false;
    return true;
}

void Renderer::renderFrame() {
    Frame frame{settings_, *gpuScene_, camera_, {}, {}, frameIndex_};
    for (const auto& pass : passes_) {
        pass->timer.begin();
        pass->execute(frame);
        pass->timer.end();
    }
    ++frameIndex_;
    hdr_ = frame.texture("radiance");
    ldr_ = frame.texture("display");
    frameTextures_ = frame.textures;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    for (const auto& pass : passes_) pass->timer.collect(false);
    gl::checkOutOfMemory("rendering a frame");
}

void Renderer::setCamera(const CameraMatrices& camera) {
    camera_ = camera;
    restartAccumulation();
}

void Renderer::setLiveSettings(DiffuseModel diffuse, SpecularModel specular, Tonemapper tonemap, float exposureEV) {
    const bool brdfChanged = diffuse != settings_.diffuse || specular != settings_.specular;
    settings_.diffuse = diffuse;
    settings_.specular = specular;
    settings_.tonemap = tonemap;
    settings_.exposureEV = exposureEV;
    checkSettings(settings_);
    if (brdfChanged) restartAccumulation();
}

void Renderer::restartAccumulation() {
    for (const auto& pass : passes_) pass->restart();
}

GLuint Renderer::frameTexture(const std::string& name) const {
    auto it = frameTextures_.find(name);
    return it == frameTextures_.end() ? 0 : it->second;
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

std::vector<PassTiming> Renderer::timings(int warmup) const {
    glFinish();
    std::vector<PassTiming> out;
    for (const auto& pass : passes_) {
        pass->timer.collect(true);
        PassTiming t;
        t.pass = pass->name();
        const auto& s = pass->timer.samples;
        if (!s.empty()) t.firstMs = s.front();
        std::vector<double> steady(s.begin() + std::min<size_t>(size_t(std::max(warmup, 0)), s.size()), s.end());
        if (!steady.empty()) {
            std::nth_element(steady.begin(), steady.begin() + steady.size() / 2, steady.end());
            t.medianMs = steady[steady.size() / 2];
        }
        auto it = ledger_.bytesByOwner.find(t.pass);
        t.bytes = it == ledger_.bytesByOwner.end() ? 0 : it->second;
        t.cached = pass->reusedLastFrame();
        out.push_back(t);
    }
    return out;
}

ProgramDesc brdfProbeProgram() { return {"brdf_probe", {"brdf_probe.comp"}, {}}; }

std::vector<ProgramDesc> allPrograms() {
    std::vector<ProgramDesc> all;
    for (auto list : {ShadowPass::programs(), GBufferPass::programs(), LightingPass::programs(),
                      TonemapPass::programs(), PathTracePass::programs(), SsaoPass::programs(),
                      AoReferencePass::programs(), GBufferVisualizer::programs()})
        all.insert(all.end(), list.begin(), list.end());
    all.push_back(brdfProbeProgram());
    return all;
}

}  // namespace gis
