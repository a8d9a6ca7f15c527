// SDF GI (`--gi sdf`): the scene voxelized (renderer/voxel), its surface voxels jump-flooded into
// a signed distance field (renderer/sdf), the voxels lit by direct light and emission; then per
// pixel a few cosine-distributed rays sphere-traced through the field and shaded from the voxel
// radiance at their hits (misses: the environment), accumulated over frames with reprojection and
// filtered edge-aware into the lighting contract's indirect.diffuse; a mirror ray for smooth
// surfaces into indirect.specular; near-field soft occlusion from the field into ao.
//
// Cascades (renderer/sdf/sdf_cascades.h): a scene whose cube is larger than sdf.cascade-extent
// gets up to four nested volumes around the camera, each with its own voxels, radiance and a
// layer of the field; a small scene (the Cornell box) gets one, the scene's cube.
//
// What is cached: each cascade's voxels and field depend on geometry and on where the cascade lies,
// and are rebuilt only after invalidate(ChangeGeometry) or when the camera takes that cascade with
// it (beyond the snap distance); its radiance also after materials or lights change. A shifted
// cascade is rebuilt whole (voxelize, seed, every flood pass, inject): see the README for why. A
// camera move within the snap costs the trace, temporal and filter steps only.
#pragma once

#include <memory>

#include "gi/sdf/sdf_settings.h"
#include "renderer.h"
#include "sdf/distance_field.h"
#include "sdf/sdf_cascades.h"
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
    std::vector<std::string> stats() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // GPU bytes the pass will hold at these settings (the memory budget asks before allocating).
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const Scene& scene,
                                                                        const RenderSettings& settings);

    const DistanceField& field() const { return *field_; }
    const SdfCascadeLayout& layout() const { return layout_; }
    int cascadeCount() const { return layout_.count; }
    // Builds of each cascade's field (voxelize + seed + flood + resolve) and radiance (inject), and
    // of all cascades together.
    int fieldBuilds(int cascade) const { return cascades_.at(size_t(cascade)).fieldBuilds; }
    int radianceBuilds(int cascade) const { return cascades_.at(size_t(cascade)).radianceBuilds; }
    int fieldBuilds() const;
    int radianceBuilds() const;
    glm::ivec3 cascadeOffset(int cascade) const { return cascades_.at(size_t(cascade)).offset; }

private:
    struct Cascade {
        std::unique_ptr<Voxelizer> voxelizer;   // made where the cascade is first placed, moved after
        std::unique_ptr<VoxelRadiance> radiance;
        glm::ivec3 offset{0};                   // in the cascade's cells from the scene cube's corner
        bool placed = false, voxelsValid = false, fieldValid = false, radianceValid = false;
        const char* lastFrame = "cached";      // what refresh() did: "rebuilt" (voxels/field), "relit", "cached"
        int fieldBuilds = 0, radianceBuilds = 0;
    };
    void place(const glm::vec3& camera);
    void refresh(Frame& frame, int cascade);
    void relight(Frame& frame, int cascade, const std::string& prefix);
    std::string stepPrefix(int cascade) const;
    void trace(const Frame& frame, const SdfGiSettings& s);
    void accumulate(const Frame& frame, const SdfGiSettings& s);
    void filter(const Frame& frame, const SdfGiSettings& s);
    void setCommonUniforms(GLuint program, const Frame& frame) const;

    SdfGiSettings built_;
    gl::MemoryScope scope_;
    ConservativeMode mode_;
    SdfCascadeLayout layout_;
    std::vector<Cascade> cascades_;
    std::unique_ptr<DistanceField> field_;   // one layer per cascade
    gl::Texture radianceAtlas_;              // more than one cascade: their radiance, a layer each
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
    bool hasHistory_ = false;
};

}  // namespace gis
