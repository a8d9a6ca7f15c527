#include "emitters/emitter_lights.h"

#include <algorithm>

#include "emitters/emitter_uniforms.h"
#include "gl/bind.h"
#include "gl/dispatch.h"

namespace gis {

using namespace emitters;

namespace {
const ProgramDesc kCandidatesProgram{"emitters-candidates", {"emitters/restir.comp"}, {{"RESTIR_STAGE", "0"}}};
const ProgramDesc kSpatialProgram{"emitters-spatial", {"emitters/restir.comp"}, {{"RESTIR_STAGE", "1"}}};
}  // namespace

std::vector<ProgramDesc> EmitterLightPass::programs() { return {kCandidatesProgram, kSpatialProgram}; }

namespace {
// The formats of a reservoir set's sample, surface and normal (restir.comp's image layouts), and
// of the still view's accumulation: what the pass allocates and the memory estimate counts.
constexpr GLenum kReservoirFormats[3] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F};
constexpr GLenum kAccumulationFormat = GL_RGBA32F;
constexpr int kReservoirSets = 2;  // this frame's and the history
}  // namespace

uint64_t EmitterLightPass::targetBytes(int width, int height, bool environmentLight) {
    uint64_t perPixel = uint64_t(gl::bytesPerTexel(kAccumulationFormat)) * (environmentLight ? 2 : 1);
    for (GLenum f : kReservoirFormats) perPixel += uint64_t(kReservoirSets) * uint64_t(gl::bytesPerTexel(f));
    return perPixel * uint64_t(std::max(width, 0)) * uint64_t(std::max(height, 0));
}

EmitterLightPass::EmitterLightPass(RayScene& rays, const RenderSettings& settings, bool environmentLight,
                                   gl::MemoryLedger& ledger)
    : rays_(rays), reuse_(gl::MemoryScope{&ledger, name()}), environmentLight_(environmentLight) {
    const gl::MemoryScope scope{&ledger, name()};
    const int w = settings.width, h = settings.height;
    static_assert(kReservoirSets == 2, "temporal_ and history_");
    for (Reservoirs* r : {&temporal_, &history_}) {
        r->sample = gl::createTexture2D(scope, kReservoirFormats[0], w, h);
        r->surface = gl::createTexture2D(scope, kReservoirFormats[1], w, h);
        r->normal = gl::createTexture2D(scope, kReservoirFormats[2], w, h);
    }
    accumulation_ = gl::createTexture2D(scope, kAccumulationFormat, w, h);
    if (environmentLight_) environmentAccumulation_ = gl::createTexture2D(scope, kAccumulationFormat, w, h);
    candidates_ = buildProgram(kCandidatesProgram);
    spatial_ = buildProgram(kSpatialProgram);
    target_ = emitterLightSettings(settings).accumulate;
}

std::vector<std::string> EmitterLightPass::inputs() const {
    return {resource::kGbufferDepth, resource::kGbufferBaseColor, resource::kGbufferNormal, resource::kGbufferMaterial};
}

std::vector<std::string> EmitterLightPass::stats() const {
    std::string lights = std::to_string(rays_.emitterCount) + " emissive triangles";
    return {lights + (environmentLight_ ? " and the environment" : "") + " as ReSTIR lights"};
}

std::vector<DebugViewDesc> EmitterLightPass::debugViews() const {
    if (!environmentLight_) return {};
    return {{"emitters.environment", "radiance of the environment's direct light (emitters.environment), with its "
                                     "shadows: the part of the direct view the environment gives"}};
}

// The environment's running mean, written as it is (a radiance view, as the lighting pass's terms).
void EmitterLightPass::drawDebugView(const std::string&, const Frame& frame, GLuint target) {
    if (!readFbo_) readFbo_ = gl::createFramebuffer(), drawFbo_ = gl::createFramebuffer();
    glNamedFramebufferTexture(readFbo_.id(), GL_COLOR_ATTACHMENT0, environmentAccumulation_.id(), 0);
    glNamedFramebufferTexture(drawFbo_.id(), GL_COLOR_ATTACHMENT0, target, 0);
    const int w = frame.settings.width, h = frame.settings.height;
    glBlitNamedFramebuffer(readFbo_.id(), drawFbo_.id(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void EmitterLightPass::invalidate(Changes c) {
    accumulated_ = 0;  // every change alters the image; the camera keeps the (reprojected) history
    if (c & ~Changes(ChangeCamera | ChangeLiveParams)) historyValid_ = false;
}

void EmitterLightPass::bindCommon(GLuint p, const Frame& frame, const EmitterLightSettings& s) {
    glUseProgram(p);
    rays_.bind();
    frame.bindEnvironment();
    gl::bindTextures({{emitters::TE_DEPTH, frame.texture(resource::kGbufferDepth)},
                      {emitters::TE_BASE_COLOR, frame.texture(resource::kGbufferBaseColor)},
                      {emitters::TE_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {emitters::TE_MATERIAL, frame.texture(resource::kGbufferMaterial)}});
    glProgramUniformMatrix4fv(p, UE_VIEW_PROJ, 1, GL_FALSE, &frame.camera.viewProj[0][0]);
    glProgramUniformMatrix4fv(p, UE_PREV_VIEW_PROJ, 1, GL_FALSE, &previousViewProj_[0][0]);
    glProgramUniformMatrix4fv(p, UE_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UE_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, UE_EMITTER_COUNT, int(rays_.emitterCount));
    glProgramUniform2i(p, UE_BRDF_MODELS, int(frame.settings.diffuse), int(frame.settings.specular));
    glProgramUniform2ui(p, UE_FRAME, frames_, frame.settings.seed);
    emitters::RestirBlock reuse;
    reuse.candidates = s.candidates;
    reuse.bsdfCandidates = s.bsdfCandidates;
    reuse.environmentCandidates = environmentLight_ ? s.environmentCandidates : 0;
    reuse.temporal = s.temporal ? 1 : 0;
    reuse.spatial = s.spatial;
    reuse.unbiased = s.unbiased ? 1 : 0;
    reuse.historyValid = historyValid_ ? 1 : 0;
    const int drawn = (rays_.emitterCount > 0 ? s.candidates : 0) + reuse.environmentCandidates;
    reuse.maxM = float(s.maxHistory * drawn);
    reuse.radius = s.radius;
    reuse.framesAveraged = float(accumulated_);
    reuse.prevCameraPos = glm::vec4(previousCameraPos_, 0.0f);
    reuse_.set(reuse);
}

void EmitterLightPass::bindReservoirs(const Reservoirs& in, const Reservoirs& out) {
    using namespace emitters;
    gl::bindImages({{IE_SAMPLE_IN, in.sample.id()}, {IE_SURFACE_IN, in.surface.id()}, {IE_NORMAL_IN, in.normal.id()},
                    {IE_SAMPLE_OUT, out.sample.id()}, {IE_SURFACE_OUT, out.surface.id()}, {IE_NORMAL_OUT, out.normal.id()}});
}

void EmitterLightPass::execute(Frame& frame) {
    const EmitterLightSettings s = emitterLightSettings(frame.settings);
    if (s.accumulate != target_) {
        if (s.accumulate < accumulated_ || s.accumulate == 0) accumulated_ = 0;
        target_ = s.accumulate;
    }
    frame.put(resource::kEmittersDirect, accumulation_);
    idle_ = target_ > 0 && accumulated_ >= target_;
    if (idle_) return;  // the still view's average is complete
    const int w = accumulation_.width, h = accumulation_.height;
    const GLuint groupsX = GLuint((w + 7) / 8), groupsY = GLuint((h + 7) / 8);
    {
        // Candidates, their visibility, and the temporal reuse: history -> temporal.
        auto step = frame.step("candidates");
        bindCommon(candidates_.id(), frame, s);
        bindReservoirs(history_, temporal_);
        gl::dispatchCompute(groupsX, groupsY, 1, "emitters candidates");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    {
        // Spatial reuse and shading: temporal -> history (the next frame's), and the average.
        auto step = frame.step("spatial");
        bindCommon(spatial_.id(), frame, s);
        bindReservoirs(temporal_, history_);
        // Without the environment as a light its part is never written: the unit holds the sum.
        const GLuint environmentPart = environmentLight_ ? environmentAccumulation_.id() : accumulation_.id();
        gl::bindImages({{emitters::IE_ACCUMULATION, accumulation_.id()},
                        {emitters::IE_ENVIRONMENT_ACCUMULATION, environmentPart}});
        gl::dispatchCompute(groupsX, groupsY, 1, "emitters spatial");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    previousViewProj_ = frame.camera.viewProj;
    previousCameraPos_ = frame.camera.position;
    historyValid_ = true;
    ++frames_;
    accumulated_ = target_ > 0 ? accumulated_ + 1 : 0;
}

}  // namespace gis
