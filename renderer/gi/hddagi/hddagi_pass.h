// HDDAGI (`--gi hddagi`): SDF GI's successor as Godot's open pull request describes it, on the
// shared modules. The scene volume (renderer/volume/) keeps nested cascades of voxels around the
// camera, with no distance field: an occupancy hierarchy instead (64-bit masks per 4^3 block, a bit
// per 8^3 region), and cascades that scroll, voxelizing only the cells they gained. The shared
// probe pipeline (renderer/probes/) keeps one probe grid per cascade, walks its rays through the
// occupancy by hierarchical DDA (shaders/volume/hdda.glsl), shades hits from the voxels' light
// plus the probes' own irradiance (every bounce), and the screen gather reads them per pixel (at
// half resolution by default) into "indirect.diffuse", with SDFGI's Chebyshev occlusion; reflection
// rays walked and shaded as the probes' own give "indirect.specular" (probes/screen_reflection.h).
// A static view with converged probes costs nothing (settled()); a light edit relights the voxels
// and restarts the probes; a camera move scrolls what left the snap distance.
#pragma once

#include <memory>

#include "gi/hddagi/hddagi_settings.h"
#include "gi/hddagi/hddagi_uniforms.h"
#include "probes/probe_field.h"
#include "probes/screen_gather.h"
#include "probes/screen_reflection.h"
#include "frame.h"
#include "gl/shader.h"
#include "volume/volume_pass.h"

namespace gis {

struct SceneServices;

class HddagiPass final : public VolumePass {
public:
    HddagiPass(SceneServices& services, const RenderSettings& settings);
    const char* name() const override { return "hddagi"; }
    std::vector<std::string> ownInputs() const override {
        return {resource::kGbufferDepth, resource::kGbufferNormal, resource::kGbufferMaterial};
    }
    std::vector<std::string> outputs() const override { return {resource::kIndirectDiffuse, resource::kIndirectSpecular}; }
    void run(Frame& frame) override;
    bool settled() const override { return field_->converged() && !changed_ && reflection_->settled(); }
    Progress progress() const override { return reflection_->progress(field_->progress(), field_->converged()); }
    void invalidate(Changes c) override;
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override;
    std::optional<RayCounts> raysTraced() const override { return field_->raysTraced(); }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const Scene& scene, const RenderSettings& s);

    // What tests and the bench look at.
    const probes::ProbeField& field() const { return *field_; }
    const HddagiSettings& rebuildSettings() const { return built_; }

private:
    HddagiSettings built_;
    Aabb sceneBounds_;
    std::unique_ptr<probes::ProbeField> field_;
    std::unique_ptr<probes::ScreenGather> gather_;
    std::unique_ptr<probes::ScreenReflection> reflection_;
    gl::Object debugProgram_;
    bool changed_ = true;             // something arrived through invalidate() since the last execute
    gl::UniformBuffer<hddagi::HddagiSliceBlock> slice_;
};

}  // namespace gis
