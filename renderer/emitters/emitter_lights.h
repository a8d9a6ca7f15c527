// Emissive triangles as lights of the direct (lighting) pass, for every deferred method: ReSTIR
// DI (Bitterli et al. 2020, "Spatiotemporal reservoir resampling for real-time ray tracing with
// dynamic direct lighting"). Per pixel, M candidates drawn from the ray scene's emitter table in
// proportion to power, resampled against the unshadowed contribution f * L * G; one visibility
// ray for the survivor; temporal reuse of the reprojected reservoir (disocclusion rejection, an M
// cap); spatial reuse of k neighbours with similar depth and normal; then the surviving sample is
// shaded with a visibility ray. Reservoirs are combined with bounded MIS weights (generalized RIS,
// Lin et al. 2022: a balance heuristic in time, pairwise MIS in space); the biased mode weighs
// other pixels' domains by their unshadowed target, the unbiased one by their target with
// visibility, at one ray per reused reservoir.
//
// The pass writes "emitters.direct" (linear RGB radiance, averaged over frames while the view
// stands still), which the lighting pass adds. It exists only with `emitters.mode=lights` and a
// scene that has emitters: otherwise nothing runs and the lighting program is compiled without it.
#pragma once

#include "emitters/emitter_uniforms.h"
#include "frame.h"
#include "gl/shader.h"
#include "ray_scene.h"

namespace gis {

// How emissive surfaces light the scene (emitters.mode).
enum class EmitterMode {
    Lights = 0,  // direct light by ReSTIR; the GI volume holds no emission (nothing counted twice)
    Gi = 1,      // only through the GI method (voxel emission), as before this module
    Off = 2,     // only the visible emission
    Auto = 3,    // Lights when the scene's emission is bright enough to light it (emissionLightsScene), else Off
};

struct EmitterLightSettings {
    int mode = int(EmitterMode::Auto);  // lights measured closer to Cycles than gi (README)
    int candidates = 8;       // M: initial candidates per pixel, drawn by power
    int bsdfCandidates = 1;   // initial candidates per pixel along BSDF directions (a ray each)
    bool temporal = true;     // reuse the reprojected reservoir of the last frame
    int spatial = 3;          // k: neighbours reused
    float radius = 16.0f;     // pixels: the spatial neighbourhood
    bool unbiased = true;     // 1/Z with visibility (one ray per reused reservoir) instead of 1/sum M
    int maxHistory = 20;      // the temporal M cap, in multiples of M
    int accumulate = 64;      // frames a still view averages (0: every frame shows its own estimate)
    int volumeSamples = 16;   // emitter points per voxel lighting the GI volume (voxel light injection)
};
const ParamTable<EmitterLightSettings>& emitterLightParams();
EmitterLightSettings emitterLightSettings(const RenderSettings& settings);

// True when some draw's material emits (before building any GPU resource).
bool sceneHasEmitters(const Scene& scene);
// Emissive triangles are lights here: some draw emits and emitters.mode is `lights`, or `auto` and
// the emission is bright enough to light the scene (the judgement --lighting auto makes; below
// it, emission is a surface detail and ReSTIR would spend its frames for nothing). The direct
// pass then runs ReSTIR and the voxel methods light their volume with the emitters.
bool emittersAreLights(const Scene& scene, const RenderSettings& settings);

class EmitterLightPass final : public Pass {
public:
    EmitterLightPass(RayScene& rays, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "emitters"; }
    std::vector<std::string> inputs() const override;
    std::vector<std::string> outputs() const override { return {resource::kEmittersDirect}; }
    void execute(Frame& frame) override;
    bool writesImagesOrBuffers() const override { return true; }
    bool reusedLastFrame() const override { return idle_; }
    // The still view's average is complete (every change restarts it).
    bool settled() const override { return target_ > 0 && accumulated_ >= target_; }
    void invalidate(Changes c) override;
    Progress progress() const override { return {accumulated_, target_, "frames"}; }
    std::vector<std::string> stats() const override;
    static std::vector<ProgramDesc> programs();
    // GPU bytes of the targets the pass allocates at width x height (the memory budget's estimate).
    static uint64_t targetBytes(int width, int height);

private:
    struct Reservoirs {
        gl::Texture sample, surface, normal;  // restir.comp's layout
    };
    void bindCommon(GLuint program, const Frame& frame, const EmitterLightSettings& s);
    static void bindReservoirs(const Reservoirs& in, const Reservoirs& out);
    RayScene& rays_;
    Reservoirs temporal_, history_;
    gl::Texture accumulation_;
    gl::Object candidates_, spatial_;
    gl::UniformBuffer<emitters::RestirBlock> reuse_;
    glm::mat4 previousViewProj_{1.0f};
    glm::vec3 previousCameraPos_{0.0f};
    bool historyValid_ = false, idle_ = false;
    int accumulated_ = 0, target_ = 0;
    uint32_t frames_ = 0;
};

}  // namespace gis
