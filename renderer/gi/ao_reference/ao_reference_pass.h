// `--gi ao-reference`: the visibility integral SSAO estimates, by tracing cosine-distributed rays
// of length `radius` against the scene's triangles (shaders/gi/ao_reference/ao_reference.comp),
// accumulated progressively; its image is the AO itself. The truth SSAO is scored against.
#pragma once

#include "passes/progressive_ray_pass.h"
#include "services/scene_services.h"

namespace gis {

struct AoReferenceSettings {
    int spp = 64;          // rays per pixel to accumulate
    float radius = 0.0f;   // world units; 0 = 15% of the scene's diagonal (as SSAO)
};
const ParamTable<AoReferenceSettings>& aoReferenceParams();

class AoReferencePass final : public ProgressiveRayPass {
public:
    static constexpr const char* kName = "ao-reference";
    AoReferencePass(SceneServices& services, const RenderSettings& settings, gl::MemoryLedger& ledger);
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();
    // AO depends on geometry and camera only: lights, BRDFs and exposure leave it as it is.
    void invalidate(Changes c) override { ProgressiveRayPass::invalidate(c, ChangeCamera | ChangeGeometry); }
    std::vector<DebugViewDesc> debugViews() const override {
        return {{"ao", "the ray-traced ambient occlusion (the image itself), linear"}};
    }
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;

private:
    AoReferenceSettings params_;
};

}  // namespace gis
