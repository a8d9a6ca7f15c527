// What the progressive ray tracers (`--gi pathtrace`, `--gi ao-reference`) share as a pass: the
// scene's rays (the ray scene the method asks SceneServices for), one compute program dispatched one sample per pixel at a
// time into a SampleAccumulator whose mean is "radiance", until the target sample count is in.
// Settled once it is and no live parameter changed since; what alters the image restarts it.
#pragma once

#include "frame.h"
#include "gl/shader.h"
#include "ray_scene.h"

namespace gis {

class ProgressiveRayPass : public Pass {
public:
    const char* name() const override { return name_; }
    std::vector<std::string> outputs() const override { return {resource::kRadiance}; }
    bool reusedLastFrame() const override { return reused_; }  // finished before the last execute()
    // Finished, and no live parameter since, which execute() would compare.
    bool settled() const override { return samples_.finished() && !liveChanged_; }
    bool writesImagesOrBuffers() const override { return true; }
    Progress progress() const override { return {samples_.done, samples_.target}; }
    // GPU bytes of the accumulation (sum and mean, RGBA32F) at the settings' size.
    static uint64_t accumulationBytes(const RenderSettings& s) { return uint64_t(s.width) * uint64_t(s.height) * 32; }

protected:
    // `name` is the pass's and its method's (its GPU memory is booked under it).
    ProgressiveRayPass(const char* name, RayScene& rays, const RenderSettings& settings, gl::MemoryLedger& ledger,
                       const ProgramDesc& program);
    // Puts the image so far as "radiance" and aims at `spp` samples, from the first when `restart`
    // or when fewer are asked than are done. True when this frame adds samples: the program is
    // bound with the ray scene, the camera and the seed; set the rest and runBatch().
    bool beginFrame(Frame& frame, int spp, bool restart);
    void runBatch() { samples_.runBatch(program_.id()); }
    GLuint program() const { return program_.id(); }
    // Changes in `restartOn` start the image over; a live parameter is compared in execute().
    void invalidate(Changes c, Changes restartOn) {
        if (c & restartOn) samples_.done = 0;
        if (c & ChangeLiveParams) liveChanged_ = true;
    }

    RayScene& rays_;
    SampleAccumulator samples_;

private:
    const char* name_;
    gl::Object program_;
    bool liveChanged_ = false;
    bool reused_ = false;
};

}  // namespace gis
