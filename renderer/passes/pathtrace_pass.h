// `--gi pathtrace`: the ground truth every method is scored against. A GPU path tracer in a
// compute shader over a BVH of the scene's triangles (renderer/bvh.h), accumulating one sample
// per pixel per dispatch into a float image until `spp` samples are done. The scene is uploaded
// and the BVH built once; later frames only add samples.
#pragma once

#include "bvh.h"
#include "renderer.h"

namespace gis {

class PathTracePass final : public Pass {
public:
    PathTracePass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "pathtrace"; }
    std::vector<std::string> outputs() const override { return {"radiance"}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return done(); }
    static std::vector<ProgramDesc> programs();

    int samplesDone() const { return samplesDone_; }
    bool done() const { return samplesDone_ >= targetSamples_; }
    void restart() { samplesDone_ = 0; }  // the next frame overwrites the accumulation
    const Bvh& bvh() const { return bvh_; }
    size_t emitterCount() const { return emitterCount_; }

private:
    Bvh bvh_;
    gl::Buffer lights_, nodes_, triangles_, attributes_, materials_, emitters_;
    gl::Texture textures_, accumulation_, output_;
    gl::Object program_, sampler_;
    size_t emitterCount_ = 0;
    int samplesDone_ = 0, targetSamples_ = 0, samplesPerFrame_ = 1;
};

}  // namespace gis
