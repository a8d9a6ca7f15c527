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

#include "gi/hddagi/hddagi_settings.h"
#include "gi/hddagi/hddagi_uniforms.h"
#include "gl/shader.h"
#include "probes/probe_field_pass.h"

namespace gis {

struct SceneServices;

class HddagiPass final : public probes::ProbeFieldPass {
public:
    static constexpr const char* kName = "hddagi";
    HddagiPass(SceneServices& services, const RenderSettings& settings);
    std::vector<std::string> stats() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const Scene& scene, const RenderSettings& s);
    const HddagiSettings& rebuildSettings() const { return built_; }

private:
    HddagiPass(SceneServices& services, const RenderSettings& settings, const HddagiSettings& valid);
    probes::ProbeFieldLive live(const RenderSettings& settings) const override;
    HddagiSettings built_;
    gl::Object debugProgram_;
    gl::UniformBuffer<hddagi::HddagiSliceBlock> slice_;
};

}  // namespace gis
