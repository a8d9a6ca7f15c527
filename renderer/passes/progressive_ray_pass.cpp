#include "passes/progressive_ray_pass.h"

#include "uniforms.h"

namespace gis {

ProgressiveRayPass::ProgressiveRayPass(const char* name, RayScene& rays, const RenderSettings& settings,
                                       gl::MemoryLedger& ledger, const ProgramDesc& program)
    : rays_(rays), samples_({&ledger, name}, settings.width, settings.height, 1, settings.samplesPerFrame), name_(name) {
    program_ = buildProgram(program);
}

bool ProgressiveRayPass::beginFrame(Frame& frame, int spp, bool restart) {
    if (restart || spp < samples_.done) samples_.done = 0;
    liveChanged_ = false;
    samples_.target = spp;
    samples_.perFrame = frame.settings.samplesPerFrame;
    frame.put(resource::kRadiance, samples_.mean);
    reused_ = samples_.finished();
    if (reused_) return false;
    const GLuint p = program_.id();
    glUseProgram(p);
    rays_.bind();
    glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform1ui(p, U_SEED, frame.settings.seed);
    return true;
}

}  // namespace gis
