// `--gi pathtrace`: the ground truth every method is scored against. A GPU path tracer in a
// compute shader over a BVH of the scene's triangles (renderer/bvh.h), accumulating one sample
// per pixel per dispatch into a float image until `spp` samples are done. The scene is uploaded
// and the BVH built once; later frames only add samples.
#pragma once

#include "ray_scene.h"
#include "renderer.h"

namespace gis {

class PathTracePass final : public Pass {
public:
    PathTracePass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "pathtrace"; }
    std::vector<std::string> outputs() const override { return {"radiance"}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return samples_.finished(); }
    static std::vector<ProgramDesc> programs();

    Progress progress() const override { return {samples_.done, samples_.target}; }
    void restart() override { samples_.done = 0; }  // the next frame overwrites the accumulation
    const Bvh& bvh() const { return rays_.bvh; }

private:
    RayScene rays_;
    SampleAccumulator samples_;
    gl::Object program_;
};

}  // namespace gis
