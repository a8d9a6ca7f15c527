// SDF GI (`--gi sdf`): the scene voxelized (renderer/voxel), its surface voxels jump-flooded into
// a signed distance field (renderer/sdf), the voxels lit by direct light and emission; then per
// pixel a few cosine-distributed rays sphere-traced through the field and shaded from the voxel
// radiance at their hits (misses: the environment), accumulated over frames with reprojection and
// filtered edge-aware into the lighting contract's indirect.diffuse; a mirror ray for smooth
// surfaces into indirect.specular; near-field soft occlusion from the field into ao.
//
// What is cached: the distance field depends on geometry alone and is rebuilt only after
// invalidate(ChangeGeometry); the voxel radiance after geometry, materials or lights change. A
// camera move costs the trace, temporal and filter steps only.
#pragma once

#include <memory>

#include "gi/sdf/sdf_settings.h"
#include "renderer.h"
#include "sdf/distance_field.h"
#include "voxel/voxel_radiance.h"

namespace gis {

class SdfGiPass final : public Pass {
public:
    SdfGiPass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return "sdf"; }
    std::vector<std::string> inputs() const override {
        return {"gbuffer.depth", "gbuffer.normal", "gbuffer.material", "lights", "shadow.maps", "shadow.cubes"};
    }
    std::vector<std::string> outputs() const override { return {"indirect.diffuse", "indirect.specular", "ao"}; }
    void execute(Frame& frame) override;
    void invalidate(Changes c) override;
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override {
        return {describeVolume(voxelizer_->grid().fit, "distance-field cells")};
    }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // GPU bytes the pass will hold at these settings (the memory budget asks before allocating).
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const RenderSettings& settings);

    const DistanceField& field() const { return *field_; }
    int fieldBuilds() const { return fieldBuilds_; }       // how often the field was rebuilt
    int radianceBuilds() const { return radianceBuilds_; }

private:
    void rebuildField(Frame& frame);
    void relight(Frame& frame);
    void trace(const Frame& frame, const SdfGiSettings& s);
    void accumulate(const Frame& frame, const SdfGiSettings& s);
    void filter(const Frame& frame, const SdfGiSettings& s);
    void setCommonUniforms(GLuint program, const Frame& frame) const;

    SdfGiSettings built_;
    std::unique_ptr<Voxelizer> voxelizer_;
    std::unique_ptr<VoxelRadiance> radiance_;
    std::unique_ptr<DistanceField> field_;
    int scale_ = 1;  // full-resolution pixels per traced pixel
    // Traced resolution: this frame's diffuse, mirror ray, occlusion, debug data; the history
    // and each history pixel's distance from its camera, ping-ponged.
    gl::Texture raw_, reflection_, occlusion_, info_, history_[2], historyDistance_[2];
    // Full resolution: the lighting contract's terms.
    gl::Texture diffuse_, specular_, ao_;
    gl::Object traceProgram_, temporalProgram_, filterProgram_, debugProgram_;
    glm::mat4 prevViewProj_{1.0f};
    glm::vec3 prevCameraPos_{0.0f};
    int current_ = 0;
    bool voxelsValid_ = false, fieldValid_ = false, radianceValid_ = false, hasHistory_ = false;
    int fieldBuilds_ = 0, radianceBuilds_ = 0;
};

}  // namespace gis
