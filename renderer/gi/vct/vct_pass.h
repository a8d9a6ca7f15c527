// Voxel cone tracing (`--gi vct`): voxelize the scene (renderer/voxel), inject direct light and
// emission, build the mip chains, then trace cones per pixel into the lighting contract's
// "indirect.diffuse", "indirect.specular" and "ao". Voxels, injection and mips are view
// independent: they are rebuilt only after invalidate() (geometry, materials or lights changed),
// so a camera move costs the trace alone.
#pragma once

#include <memory>

#include "gi/vct/vct_settings.h"
#include "renderer.h"
#include "voxel/voxel_radiance.h"

namespace gis {

class VctPass final : public Pass {
public:
    VctPass(const GpuScene& scene, const VctSettings& settings, int width, int height, gl::MemoryLedger& ledger);
    const char* name() const override { return "vct"; }
    std::vector<std::string> inputs() const override {
        return {"gbuffer.depth", "gbuffer.normal", "gbuffer.material", "lights", "shadow.maps", "shadow.cubes"};
    }
    std::vector<std::string> outputs() const override {
        return {"indirect.diffuse", "indirect.specular", "ao", "vct.voxels", "vct.slice"};
    }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return reused_; }
    // Geometry, materials or lights changed: voxelize and inject again on the next frame.
    void invalidate() { valid_ = false; }
    // Parameters read only when tracing (cone set, step, distance, offset, intensity, specular,
    // debug view).
    void setLiveSettings(const VctSettings& s);
    static std::vector<ProgramDesc> programs();

    // Sub-steps, timed separately: voxelize, inject (with further bounces), mips, trace.
    enum Step { Voxelize, Inject, Mips, Trace, StepCount };
    static const char* stepName(int step);
    gl::GpuTimer& stepTimer(int step) { return stepTimers_[step]; }
    const Voxelizer& voxelizer() const { return *voxelizer_; }
    const VoxelRadiance& voxelRadiance() const { return *radiance_; }
    const VctSettings& settings() const { return settings_; }

private:
    void rebuildVoxels(const Frame& frame);
    void trace(const Frame& frame);
    void debugView(Frame& frame);
    VctSettings settings_;
    std::unique_ptr<Voxelizer> voxelizer_;
    std::unique_ptr<VoxelRadiance> radiance_;
    gl::Texture diffuse_, specular_, ao_, debug_;
    gl::Object traceProgram_, debugProgram_;
    gl::GpuTimer stepTimers_[StepCount];
    bool valid_ = false, reused_ = false;
};

}  // namespace gis
