// `--gi ao-reference`: the visibility integral SSAO estimates, by tracing cosine-distributed rays
// of length `radius` against the scene's triangles (shaders/gi/ao_reference/ao_reference.comp),
// accumulated progressively; its image is the AO itself. The truth SSAO is scored against.
#pragma once

#include "frame.h"
#include "gl/shader.h"
#include "services/scene_services.h"

namespace gis {

struct AoReferenceSettings {
    int spp = 64;          // rays per pixel to accumulate
    float radius = 0.0f;   // world units; 0 = 15% of the scene's diagonal (as SSAO)
};
const ParamTable<AoReferenceSettings>& aoReferenceParams();

class AoReferencePass final : public Pass {
public:
    AoReferencePass(SceneServices& services, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "ao-reference"; }
    std::vector<std::string> outputs() const override { return {resource::kRadiance}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return reused_; }  // finished before the last execute()
    // Finished, and no live parameter (spp, radius) since, which execute() would compare.
    bool settled() const override { return samples_.finished() && !liveChanged_; }
    bool writesImagesOrBuffers() const override { return true; }
    static std::vector<ProgramDesc> programs();
    Progress progress() const override { return {samples_.done, samples_.target}; }
    // AO depends on geometry and camera only: lights, BRDFs and exposure leave it as it is.
    void invalidate(Changes c) override {
        if (c & (ChangeCamera | ChangeGeometry)) samples_.done = 0;
        if (c & ChangeLiveParams) liveChanged_ = true;
    }
    std::vector<DebugViewDesc> debugViews() const override {
        return {{"ao", "the ray-traced ambient occlusion (the image itself), linear"}};
    }
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;

private:
    RayScene& rays_;
    SampleAccumulator samples_;
    AoReferenceSettings params_;
    gl::Object program_;
    bool liveChanged_ = false;
    bool reused_ = false;
};

}  // namespace gis
