// `--gi ssao`: screen-space ambient occlusion over the G-buffer (shaders/gi/ssao/ssao.frag), a
// bilateral blur, optional half resolution and optional temporal accumulation; writes "ao", which
// the lighting pass multiplies into the ambient term only (never direct light).
#pragma once

#include "frame.h"
#include "gl/shader.h"
#include "uniforms.h"

namespace gis {

enum class SsaoKernel { Hemisphere, Gtao };

struct SsaoSettings {
    int kernel = int(SsaoKernel::Hemisphere);  // which estimator: shaders/gi/ssao/ssao.frag or gtao.frag
    int samples = 16;            // directions in the hemisphere kernel
    int slices = 4;              // GTAO: slices through the view vector
    int steps = 4;               // points tested along each direction (GTAO: per side of a slice)
    float radius = 0.0f;         // world units; 0 = 15% of the scene's bounding-box diagonal
    float bias = 0.03f;          // depth bias as a fraction of the radius
    float power = 1.0f;          // AO^power (contrast)
    bool blur = true;            // bilateral 4x4 blur
    bool halfResolution = false;
    bool temporal = false;       // reprojected accumulation with per-frame noise rotation
};
const ParamTable<SsaoSettings>& ssaoParams();

// The AO radius an automatic (0) setting stands for: 15% of the scene's diagonal. SSAO and the
// ray-traced reference use the same one, so they measure the same integral.
float resolveAoRadius(float radius, const Scene& scene);

class SsaoPass final : public Pass {
public:
    SsaoPass(const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "ssao"; }
    std::vector<std::string> inputs() const override { return {resource::kGbufferDepth, resource::kGbufferNormal}; }
    std::vector<std::string> outputs() const override { return {resource::kAo}; }
    void execute(Frame& frame) override;
    void invalidate(Changes c) override {
        if (c & (ChangeGeometry | ChangeLiveParams)) hasHistory_ = false;  // reprojection handles the camera
        if (c & (ChangeCamera | ChangeGeometry | ChangeMaterials | ChangeLiveParams)) stillFrames_ = 0;
    }
    // Executed since the last change (the G-buffer's view, the radius ...) and, with temporal
    // accumulation, for as many frames as its running mean holds.
    bool settled() const override;
    std::vector<DebugViewDesc> debugViews() const override {
        return {{"ao", "the ambient occlusion term alone (1 = unoccluded), linear"}};
    }
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // The kernel: `count` cosine-distributed unit directions around +Z (a Hammersley set lifted
    // from the disk, Malley's method), deterministic.
    static std::vector<glm::vec4> kernel(int count);

private:
    bool gtao() const { return params_.kernel == int(SsaoKernel::Gtao); }

    SsaoSettings params_;
    int width_, height_;
    gl::Texture raw_, blurred_, history_[2], noise_;
    gl::Object rawFbo_, blurFbo_, historyFbo_[2], aoProgram_, blurProgram_, temporalProgram_, vao_, sampler_;
    const gl::Texture* result_ = nullptr;
    std::vector<glm::vec4> kernel_;
    glm::mat4 prevViewProj_{1.0f};
    int current_ = 0;
    bool hasHistory_ = false;
    int stillFrames_ = 0;  // frames executed since the last change
    gl::UniformBuffer<SsaoBlock> samples_;
    gl::UniformBuffer<SsaoTemporalBlock> temporal_;
};

}  // namespace gis
