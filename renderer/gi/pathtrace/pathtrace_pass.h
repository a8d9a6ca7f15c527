// `--gi pathtrace`: the ground truth every method is scored against. A GPU path tracer in a
// compute shader over the shared BVH of the scene's triangles (SceneServices::rays), accumulating
// one sample per pixel per dispatch into a float image until `spp` samples are done. Later frames
// only add samples; a camera, light or BRDF change starts over.
#pragma once

#include "passes/progressive_ray_pass.h"
#include "services/scene_services.h"

namespace gis {

struct PathTraceSettings {
    int spp = 64;                  // samples per pixel to accumulate
    int bounces = 16;              // indirect bounces; 0 = direct lighting only
    int russianRouletteStart = 3;  // bounce from which Russian roulette may end a path
    bool caustics = true;          // false: no glossy light after a diffuse bounce (Cycles' switch)
    bool environmentSampling = true;  // an environment map sampled as a light (MIS); false: BSDF samples only
};
const ParamTable<PathTraceSettings>& pathTraceParams();

class PathTracePass final : public ProgressiveRayPass {
public:
    static constexpr const char* kName = "pathtrace";
    PathTracePass(SceneServices& services, const RenderSettings& settings, gl::MemoryLedger& ledger);
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();

    // Camera, lights, scene or BRDFs alter the image; live parameters are compared in execute().
    void invalidate(Changes c) override { ProgressiveRayPass::invalidate(c, ~Changes(ChangeLiveParams)); }
    const Bvh& bvh() const { return rays_.bvh; }
    // The radiance split as the lighting pass's term views split it (direct, emission,
    // indirect.diffuse, indirect.specular) and pathtrace.indirect, the last two's sum: with --view
    // one of them the paths keep only that term.
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    std::optional<RayCounts> raysTraced() const override;

private:
    PathTraceSettings params_;
    int term_ = 0;          // pathtrace.comp's u_term: 0 = the whole radiance
    gl::Object readFbo_, drawFbo_;  // the term view's copy into the debug target
    gl::Buffer rayCounts_;  // 3 x (low, high) uint: primary, bounce, shadow rays (pathtrace.comp)
};

}  // namespace gis
