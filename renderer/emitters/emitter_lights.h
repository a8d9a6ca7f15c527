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
// With emitters.environment the environment (a map or a constant) is a light of the pass too:
// candidates drawn from it join the emitters' in the same reservoirs, each with its visibility.
//
// The pass writes "emitters.direct" (linear RGB radiance, averaged over frames while the view
// stands still), which the lighting pass adds. It exists only when it has lights
// (directPassHasLights): otherwise nothing runs and the lighting program is compiled without it.
#pragma once

#include "emitter_settings.h"
#include "emitters/emitter_uniforms.h"
#include "frame.h"
#include "gl/shader.h"
#include "ray_scene.h"

namespace gis {

class EmitterLightPass final : public Pass {
public:
    // `environmentLight`: the environment is one of its lights (environmentIsLight).
    EmitterLightPass(RayScene& rays, const RenderSettings& settings, bool environmentLight, gl::MemoryLedger& ledger);
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
    // "emitters.environment": the environment's part of the direct light (with emitters.environment).
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // GPU bytes of the targets the pass allocates at width x height (the memory budget's estimate).
    static uint64_t targetBytes(int width, int height, bool environmentLight);

private:
    struct Reservoirs {
        gl::Texture sample, surface, normal;  // restir.comp's layout
    };
    void bindCommon(GLuint program, const Frame& frame, const EmitterLightSettings& s);
    static void bindReservoirs(const Reservoirs& in, const Reservoirs& out);
    RayScene& rays_;
    Reservoirs temporal_, history_;
    gl::Texture accumulation_, environmentAccumulation_;  // the second with emitters.environment only
    gl::Object readFbo_, drawFbo_;  // the environment view's copy
    gl::Object candidates_, spatial_;
    gl::UniformBuffer<emitters::RestirBlock> reuse_;
    glm::mat4 previousViewProj_{1.0f};
    glm::vec3 previousCameraPos_{0.0f};
    bool environmentLight_ = false;
    bool historyValid_ = false, idle_ = false;
    int accumulated_ = 0, target_ = 0;
    uint32_t frames_ = 0;
};

}  // namespace gis
