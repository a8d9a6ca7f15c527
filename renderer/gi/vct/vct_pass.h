// Voxel cone tracing (`--gi vct`): voxelize the scene (renderer/voxel), inject direct light and
// emission, build the mip chains, then trace cones per pixel into the lighting contract's
// "indirect.diffuse" and "indirect.specular". Voxels, injection and mips are view independent:
// the voxels are rebuilt only after invalidate() with geometry or materials, injection and mips
// also after a light edit, so a camera move costs the trace alone. The cones' occlusion is already
// in indirect.diffuse, so the pass does not write "ao" (the lighting pass would multiply it in a
// second time); it is the debug view "vct.ao".
#pragma once

#include <memory>

#include "gi/vct/vct_settings.h"
#include "renderer.h"
#include "voxel/voxel_radiance.h"

namespace gis {

class VctPass final : public Pass {
public:
    // Rebuild parameters come from settings.params ("vct.*").
    VctPass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "vct"; }
    std::vector<std::string> inputs() const override {
        return {"gbuffer.depth", "gbuffer.normal", "gbuffer.material", "lights", "shadow.maps", "shadow.cubes"};
    }
    std::vector<std::string> outputs() const override {
        return {"indirect.diffuse", "indirect.specular", "voxel.radiance"};
    }
    void execute(Frame& frame) override;
    // The trace runs every frame, so the pass as a whole never reuses its result; its voxelize,
    // inject and mips steps do (they show as cached in --timings).
    bool reusedLastFrame() const override { return false; }
    bool voxelsReusedLastFrame() const { return reused_; }
    // Geometry and materials change the voxels (occupancy, albedo, emission); a light edit only the
    // light injected into them (and the mips and bounces built from it).
    void invalidate(Changes c) override {
        if (c & (ChangeGeometry | ChangeMaterials)) voxelsValid_ = false;
        if (c & (ChangeGeometry | ChangeMaterials | ChangeLights)) radianceValid_ = false;
    }
    int voxelizations() const { return voxelizations_; }  // how often the scene was voxelized
    int injections() const { return injections_; }        // how often light was injected
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override {
        return {describeVolume(voxelizer_->grid().fit, "voxels")};
    }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

    const Voxelizer& voxelizer() const { return *voxelizer_; }
    const VoxelRadiance& voxelRadiance() const { return *radiance_; }
    const VctSettings& rebuildSettings() const { return built_; }

private:
    void relight(Frame& frame);
    void trace(const Frame& frame, const VctSettings& live);
    VctSettings built_;    // the rebuild parameters this pass was made with
    VctSettings live_;     // the live parameters of the last frame
    std::unique_ptr<Voxelizer> voxelizer_;
    std::unique_ptr<VoxelRadiance> radiance_;
    gl::Texture diffuse_, specular_, ao_;
    gl::Object traceProgram_, debugProgram_;
    bool voxelsValid_ = false, radianceValid_ = false, reused_ = false;
    int voxelizations_ = 0, injections_ = 0;
};

}  // namespace gis
