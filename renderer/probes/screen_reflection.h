// A probe field's specular term on the screen (issue #40: mirrors were black under probe GI and
// HDDAGI, which fell back to the constant ambient): per full-resolution pixel below a roughness
// cut-off, rays drawn from the GGX lobe are walked through the field's tracer and shaded as the
// probes' own rays are (shaders/probes/probe_hit_light.glsl), averaged over the frames of a still
// view, and blended towards the diffuse gather as the lobe widens; into "indirect.specular".
// Probe GI, HDDAGI and SDF GI (with its probes) reflect this way. For probe GI and HDDAGI, whose
// gather leaves a point no probe sees black (issue #39: the far end of a building's corridor, in a
// cascade whose probes are all behind its walls), cosine rays light such a pixel the same way, into
// the gather's "indirect.diffuse".
#pragma once

#include <string>

#include "frame.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "probes/probe_field.h"
#include "probes/probe_uniforms.h"

namespace gis::probes {

// What reflects and how: the members the METHOD.reflection* rows bind (probe_params.h,
// addReflectionRows), with their defaults, declared once; each probe method's settings derive
// from it (live parameters).
enum class Reflection { Environment = 0, Rays = 1 };
struct ReflectionSettings {
    int reflection = int(Reflection::Rays);  // METHOD.reflection: environment | rays
    float reflectionRoughness = 0.6f;        // rays below it, blended towards the diffuse gather over its last quarter
    int reflectionRays = 4;                  // per pixel per frame (one at a mirror)
    int reflectionFrames = 16;               // still frames averaged before the view counts as settled
    Reflection mode() const { return Reflection(reflection); }
};

class ScreenReflection {
public:
    ScreenReflection(const gl::MemoryScope& scope, int width, int height, Tracer tracer);
    // Traces this frame's rays for `field` (bound as its update `live` shades hits) and folds them
    // into the mean, which restarts when `changed` (the pass was invalidated: the view, the light,
    // a parameter), when the probes updated this frame or when `s` differs from the last frame's.
    // `unseenIntensity` > 0: `diffuse`'s alpha is the share of its light probes gave (ScreenGather),
    // and the rest is traced here, scaled by it (the gather's METHOD.intensity), and added into it
    // (with rays only).
    void run(const Frame& frame, const ProbeField& field, const FieldSettings& live, const gl::Texture& diffuse,
             const ReflectionSettings& s, bool changed, float unseenIntensity);
    const gl::Texture& result() const { return specular_; }
    // The mean holds the frames the last run's settings ask for (at once without rays).
    bool settled() const;
    // The pass's progress: the field's updates, then (once it has converged) the frames averaged.
    Pass::Progress progress(Pass::Progress field, bool fieldConverged) const;
    std::string describe() const;  // "reflection: rays below roughness 0.6, 4 per pixel, 16 of 16 frames averaged"
    static std::vector<ProgramDesc> programs();
    static int64_t bytes(int width, int height);

private:
    gl::Texture mean_, specular_, unseenMean_;
    gl::Object program_, environmentProgram_;
    gl::UniformBuffer<ProbeReflectBlock> block_;
    ReflectionSettings live_;
    int framesAveraged_ = 0, frame_ = 0;
};

}  // namespace gis::probes
