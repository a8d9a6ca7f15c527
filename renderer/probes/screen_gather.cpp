#include "probes/screen_gather.h"

#include "gl/dispatch.h"
#include "probes/probe_field.h"
#include "probes/probe_uniforms.h"

namespace gis::probes {

namespace {
const ProgramDesc kGatherProgram{"probe_screen_gather", {"probes/screen_gather.comp"}, {}};
const ProgramDesc kUpsampleProgram{"probe_screen_upsample", {"probes/screen_upsample.comp"}, {}};
const ProgramDesc kGatherOccupancyProgram{"probe_screen_gather_occupancy", {"probes/screen_gather.comp"},
                                          {{"PROBE_TRACER_OCCUPANCY", "1"}}};
const ProgramDesc kUpsampleOccupancyProgram{"probe_screen_upsample_occupancy", {"probes/screen_upsample.comp"},
                                            {{"PROBE_TRACER_OCCUPANCY", "1"}}};

int reduced(int pixels, int scale) { return (pixels + scale - 1) / scale; }
}  // namespace

std::vector<ProgramDesc> ScreenGather::programs() {
    return {kGatherProgram, kUpsampleProgram, kGatherOccupancyProgram, kUpsampleOccupancyProgram};
}

int64_t ScreenGather::bytes(int width, int height, int scale) {
    const int64_t full = int64_t(width) * height * 8;
    return full + (scale > 1 ? int64_t(reduced(width, scale)) * reduced(height, scale) * 8 : 0);
}

ScreenGather::ScreenGather(const gl::MemoryScope& scope, int width, int height, int scale, Tracer tracer)
    : scale_(scale), block_(scope) {
    const bool occupancy = tracer == Tracer::Occupancy;
    diffuse_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    gatherProgram_ = buildProgram(occupancy ? kGatherOccupancyProgram : kGatherProgram);
    if (scale > 1) {
        gathered_ = gl::createTexture2D(scope, GL_RGBA16F, reduced(width, scale), reduced(height, scale));
        upsampleProgram_ = buildProgram(occupancy ? kUpsampleOccupancyProgram : kUpsampleProgram);
    }
}

void ScreenGather::dispatch(const Frame& frame, const ProbeField& field, const GatherSettings& s, GLuint p,
                            const gl::Texture& out) const {
    const GLuint gbuffer[2] = {frame.texture(resource::kGbufferDepth), frame.texture(resource::kGbufferNormal)};
    glUseProgram(p);
    field.bindForScreenGather(p);
    glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
    ProbeGatherBlock b;
    b.normalBias = s.normalBias;
    b.intensity = s.intensity;
    b.visibility = visibilityMode(s.visibility, s.pathTest);
    block_.set(b);
    glProgramUniform1i(p, UP_GATHER_SCALE, scale_);
    static_assert(TP_GATHER_NORMAL == TP_GATHER_DEPTH + 1 && TP_GATHERED == TP_GATHER_NORMAL + 1, "consecutive units");
    glBindTextures(TP_GATHER_DEPTH, 2, gbuffer);
    glBindSamplers(TP_GATHER_DEPTH, 3, nullptr);
    glBindImageTexture(IP_OUTPUT, out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(out.width, 8), gl::groupsFor(out.height, 8), 1, "probe gather");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void ScreenGather::run(const Frame& frame, const ProbeField& field, const GatherSettings& s) {
    if (scale_ == 1) {
        dispatch(frame, field, s, gatherProgram_.id(), diffuse_);
        return;
    }
    dispatch(frame, field, s, gatherProgram_.id(), gathered_);
    glBindTextureUnit(TP_GATHERED, gathered_.id());
    dispatch(frame, field, s, upsampleProgram_.id(), diffuse_);
}

}  // namespace gis::probes
