#include "passes/pathtrace_pass.h"

#include <algorithm>

#include "uniforms.h"

namespace gis {

std::vector<ProgramDesc> PathTracePass::programs() { return {{"pathtrace", {"pathtrace.comp"}, {}}}; }

PathTracePass::PathTracePass(const GpuScene& gpuScene, const RenderSettings& settings, gl::MemoryLedger& ledger)
    : rays_(gpuScene, ledger, name()),
      samples_({&ledger, name()}, settings.width, settings.height, settings.spp, settings.samplesPerFrame) {
    program_ = buildProgram(programs()[0]);
}

void PathTracePass::execute(Frame& frame) {
    frame.textures["radiance"] = samples_.mean.id();
    if (samples_.finished()) return;  // converged to the requested sample count: nothing changes
    const RenderSettings& s = frame.settings;
    const GLuint p = program_.id();
    glUseProgram(p);
    rays_.bind();
    const glm::vec3 background = s.background.value_or(frame.scene.cpu.background);
    glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform1i(p, U_LIGHT_COUNT, int(frame.scene.cpu.lights.size()));
    glProgramUniform3fv(p, U_BACKGROUND, 1, &background[0]);
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1ui(p, U_SEED, s.seed);
    glProgramUniform1i(p, U_MAX_BOUNCES, s.maxBounces);
    glProgramUniform1i(p, U_EMITTER_COUNT, int(rays_.emitterCount));
    glProgramUniform1i(p, U_RR_START, s.russianRouletteStart);
    samples_.runBatch(p);
}

}  // namespace gis
