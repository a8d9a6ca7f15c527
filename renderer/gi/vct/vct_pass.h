// Voxel cone tracing (`--gi vct`): the scene volume (renderer/volume: voxels, their direct light
// and emission, the mip chains) traced with cones per pixel into the lighting contract's
// "indirect.diffuse" and "indirect.specular". The volume is view independent and rebuilds only
// what changed (a light edit relights without voxelizing), so a camera move costs the trace
// alone. The cones' occlusion is already
// in indirect.diffuse, so the pass does not write "ao" (the lighting pass would multiply it in a
// second time); it is the debug view "vct.ao".
#pragma once

#include <memory>

#include "gi/vct/vct_settings.h"
#include "renderer.h"
#include "volume/scene_volume.h"

namespace gis {

struct SceneServices;

class VctPass final : public Pass {
public:
    // Rebuild parameters come from settings.params ("vct.*").
    VctPass(SceneServices& services, const RenderSettings& settings);
    const char* name() const override { return "vct"; }
    std::vector<std::string> inputs() const override {
        return withVolumeInputs({resource::kGbufferDepth, resource::kGbufferNormal, resource::kGbufferMaterial});
    }
    std::vector<std::string> outputs() const override {
        return {resource::kIndirectDiffuse, resource::kIndirectSpecular};
    }
    void execute(Frame& frame) override;
    // The trace runs every frame, so the pass as a whole never reuses its result; the volume's
    // voxelize, inject and mips steps do (they show as cached in --timings).
    bool reusedLastFrame() const override { return false; }
    bool voxelsReusedLastFrame() const { return volume_->lastUpdate(0) == SceneVolume::Update::Cached; }
    int voxelizations() const { return volume_->builds().voxelizations; }  // how often the scene was voxelized
    int injections() const { return volume_->builds().injections; }        // how often light was injected
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override {
        return {describeVolume(volume_->grid().fit, "voxels")};
    }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

    const SceneVolume& volume() const { return *volume_; }
    const VctSettings& rebuildSettings() const { return built_; }

private:
    void trace(const Frame& frame, const VctSettings& live);
    VctSettings built_;    // the rebuild parameters this pass was made with
    VctSettings live_;     // the live parameters of the last frame
    SceneVolume* volume_ = nullptr;         // the renderer's, shared (SceneServices)
    gl::Texture diffuse_, specular_, ao_;
    gl::Object traceProgram_, debugProgram_;
};

}  // namespace gis
