// `--gi ssao`: screen-space ambient occlusion over the G-buffer (shaders/ssao.frag), a bilateral
// blur, optional half resolution and optional temporal accumulation; writes "ao", which the
// lighting pass multiplies into the ambient term only (never direct light).
// `--gi ao-reference`: the same visibility integral by tracing rays against the scene's triangles
// (shaders/ao_reference.comp), accumulated progressively; its image is the AO itself.
#pragma once

#include "ray_scene.h"
#include "renderer.h"

namespace gis {

class SsaoPass final : public Pass {
public:
    SsaoPass(const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "ssao"; }
    std::vector<std::string> inputs() const override { return {"gbuffer.depth", "gbuffer.normal"}; }
    std::vector<std::string> outputs() const override { return {"ao"}; }
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();
    // The kernel: `count` cosine-distributed unit directions around +Z (a Hammersley set lifted
    // from the disk, Malley's method), deterministic.
    static std::vector<glm::vec4> kernel(int count);

private:
    int width_, height_;
    gl::Texture raw_, blurred_, history_[2], noise_;
    gl::Object rawFbo_, blurFbo_, historyFbo_[2], ssaoProgram_, blurProgram_, temporalProgram_, vao_, sampler_;
    std::vector<glm::vec4> kernel_;
    glm::mat4 prevViewProj_{1.0f};
    int current_ = 0;
    bool hasHistory_ = false;
};

class AoReferencePass final : public Pass {
public:
    AoReferencePass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "ao-reference"; }
    std::vector<std::string> outputs() const override { return {"radiance"}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return samples_.finished(); }
    static std::vector<ProgramDesc> programs();
    Progress progress() const override { return {samples_.done, samples_.target}; }
    void restart() override { samples_.done = 0; }  // the next frame overwrites the accumulation

private:
    RayScene rays_;
    SampleAccumulator samples_;
    gl::Object program_;
};

}  // namespace gis
