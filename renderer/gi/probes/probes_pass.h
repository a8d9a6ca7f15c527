// Probe GI (`--gi probes`): a grid of irradiance probes per cascade of the scene volume (the
// coarsest fitted to the scene, the finer ones following the camera), kept by the shared probe
// pipeline (renderer/probes/probe_field.h: rays sphere-traced through the scene volume's
// distance field, shaded from its voxels' light plus the probes' own irradiance, blended with
// hysteresis within a per-frame ray budget). Per pixel, the 8 surrounding probes are interpolated
// with normal-facing and Chebyshev-visibility weights into "indirect.diffuse"; reflection rays
// walked and shaded as the probes' own give "indirect.specular" (probes/screen_reflection.h).
// A camera move that moves no cascade costs the shading alone; converged probes cost nothing, and a
// static view with converged probes costs nothing at all (settled()); a light change relights the
// voxels (no voxelization, no flood) and restarts the probes.
#pragma once

#include "gi/probes/probe_settings.h"
#include "probes/probe_field_pass.h"

namespace gis {

struct SceneServices;

class ProbesPass final : public probes::ProbeFieldPass {
public:
    static constexpr const char* kName = "probes";
    ProbesPass(SceneServices& services, const RenderSettings& settings);
    std::vector<std::string> stats() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

    // What tests and the bench look at: the finest grid (the only one in a scene of one cascade).
    const probes::ProbeGrid& grid() const { return field_->grids()[0]; }
    int updates() const { return field_->updates(); }   // frames with a probe update since the last restart
    bool converged() const { return field_->converged(); }
    bool updatedLastFrame() const { return field_->updatedLastFrame(); }
    float lastChange() const { return field_->lastChange(); }
    probes::ProbeField::StateCounts stateCounts() const { return field_->stateCounts(); }
    // Probe i's irradiance payload (RGB per SH coefficient or octahedral texel), read back.
    std::vector<glm::vec3> readIrradiance(int probe) const { return field_->readIrradiance(probe); }
    const ProbeSettings& rebuildSettings() const { return built_; }

private:
    ProbesPass(SceneServices& services, const RenderSettings& settings, const ProbeSettings& valid);
    probes::ProbeFieldLive live(const RenderSettings& settings) const override;
    ProbeSettings built_;
};

}  // namespace gis
