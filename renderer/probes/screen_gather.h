// A probe field's light on the screen: per pixel, the 8 probes around its surface point (in the
// finest grid that holds it; shaders/probes/screen_gather.glsl) into "indirect.diffuse"-shaped
// E / pi. At a gather scale of 2 or 4 only each block's first pixel gathers, and a joint bilateral
// upsampling spreads it to the others (pixels on an edge gather their own). Probe GI and HDDAGI
// gather this way; SDF GI gathers inside its own trace.
#pragma once

#include "frame.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "probes/probe_field.h"
#include "probes/probe_uniforms.h"

namespace gis::probes {

struct GatherSettings {
    float normalBias = 0.1f;   // along the normal and towards the eye, x the smallest probe step
    float intensity = 1.0f;
    bool visibility = true;    // Chebyshev visibility from the distance moments
    bool pathTest = false;     // with visibility: a probe counts only along a clear straight path
};

class ScreenGather {
public:
    // `scale`: full-resolution pixels per gathered pixel along each axis (1, 2 or 4); `tracer`: the
    // volume the gathered field walks, through which each probe's path to a pixel is tested.
    ScreenGather(const gl::MemoryScope& scope, int width, int height, int scale, Tracer tracer);
    // Gathers `field` for the frame's G-buffer into result().
    void run(const Frame& frame, const ProbeField& field, const GatherSettings& s);
    const gl::Texture& result() const { return diffuse_; }
    int scale() const { return scale_; }
    static std::vector<ProgramDesc> programs();
    static int64_t bytes(int width, int height, int scale);

private:
    void dispatch(const Frame& frame, const ProbeField& field, const GatherSettings& s, GLuint program,
                  const gl::Texture& out) const;
    int scale_;
    gl::Texture diffuse_, gathered_;   // gathered_: at 1/scale, when above 1
    gl::Object gatherProgram_, upsampleProgram_;
    gl::UniformBuffer<ProbeGatherBlock> block_;
};

}  // namespace gis::probes
