#include "passes/pathtrace_pass.h"

#include <algorithm>

#include "uniforms.h"

namespace gis {

std::vector<ProgramDesc> PathTracePass::programs() { return {{"pathtrace", {"pathtrace.comp"}, {}}}; }

PathTracePass::PathTracePass(const GpuScene& gpuScene, const RenderSettings& settings, gl::MemoryLedger& ledger)
    : rays_(gpuScene, ledger, name()), targetSamples_(settings.spp),
      samplesPerFrame_(std::max(1, settings.samplesPerFrame)) {
    const gl::MemoryScope scope{&ledger, name()};
    accumulation_ = gl::createTexture2D(scope, GL_RGBA32F, settings.width, settings.height);
    output_ = gl::createTexture2D(scope, GL_RGBA32F, settings.width, settings.height);
    program_ = buildProgram(programs()[0]);
}

void PathTracePass::execute(Frame& frame) {
    frame.textures["radiance"] = output_.id();
    if (done()) return;  // converged to the requested sample count: nothing changes
    const RenderSettings& s = frame.settings;
    const GLuint p = program_.id();
    glUseProgram(p);
    rays_.bind();
    glBindImageTexture(0, accumulation_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(1, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const glm::vec3 background = s.background.value_or(frame.scene.cpu.background);
    glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform1i(p, U_LIGHT_COUNT, int(frame.scene.cpu.lights.size()));
    glProgramUniform3fv(p, U_BACKGROUND, 1, &background[0]);
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1ui(p, U_SEED, s.seed);
    glProgramUniform1i(p, U_MAX_BOUNCES, s.maxBounces);
    glProgramUniform1i(p, U_EMITTER_COUNT, int(rays_.emitterCount));
    glProgramUniform1i(p, U_RR_START, s.russianRouletteStart);
    const GLuint groupsX = GLuint((output_.width + 7) / 8), groupsY = GLuint((output_.height + 7) / 8);
    const int batch = std::min(samplesPerFrame_, targetSamples_ - samplesDone_);
    for (int i = 0; i < batch; ++i) {
        glProgramUniform1ui(p, U_SAMPLE_INDEX, GLuint(samplesDone_));
        glDispatchCompute(groupsX, groupsY, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        ++samplesDone_;
    }
}

}  // namespace gis
