// Probe GI (`--gi probes`): a grid of irradiance probes fitted to the scene. Each update, every
// probe of the frame's batch shoots rays sphere-traced through the scene volume's distance field,
// shaded from its voxels' light (renderer/volume: direct light and emission) plus the probes' own
// irradiance (multi-bounce); the rays are blended into SH L1/L2 or an octahedral irradiance map and
// an octahedral map of distance moments, with hysteresis. Per pixel, the 8 surrounding probes are
// interpolated with normal-facing and Chebyshev-visibility weights into "indirect.diffuse".
// Volume and probes are view independent: a camera move costs the shading alone, and once the
// updates stop changing the probes (a static scene converged) they stop; a light change relights
// the voxels (no voxelization, no flood) and restarts them.
#pragma once

#include <memory>

#include "gi/probes/probe_math.h"
#include "gi/probes/probe_settings.h"
#include "renderer.h"
#include "volume/scene_volume.h"

namespace gis {

struct SceneServices;

// GPU bytes of the probes themselves (irradiance, distance moments, state) and of the ray buffer.
int64_t probeStorageBytes(const ProbeSettings& s, int probes);
int64_t probeRayBytes(const ProbeSettings& s, int probes);

class ProbesPass final : public Pass {
public:
    ProbesPass(SceneServices& services, const RenderSettings& settings);
    const char* name() const override { return "probes"; }
    std::vector<std::string> inputs() const override {
        return withVolumeInputs({resource::kGbufferDepth, resource::kGbufferNormal});
    }
    std::vector<std::string> outputs() const override { return {resource::kIndirectDiffuse}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return false; }  // the shading runs every frame
    // Updates as progress, so `render` (and the sandbox's "converge") renders until the probes
    // have converged: done = updates read back, target = the most updates there can be, and both
    // the updates done once the stopping rule ends them earlier.
    Progress progress() const override;
    void invalidate(Changes c) override;
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

    // What tests and the bench look at.
    const probes::ProbeGrid& grid() const { return grid_; }
    int updates() const { return updates_; }           // probe updates since the last restart (batches)
    bool converged() const { return converged_; }
    bool updatedLastFrame() const { return updatedLastFrame_; }
    float lastChange() const { return lastChange_; }   // largest relative change of the last update read back
    struct StateCounts {
        int active = 0, relocated = 0, off = 0;
    };
    StateCounts stateCounts() const;                   // reads the state buffer back
    // Probe i's irradiance payload (RGB per SH coefficient or octahedral texel), read back.
    std::vector<glm::vec3> readIrradiance(int probe) const;
    const ProbeSettings& rebuildSettings() const { return built_; }
    const SceneVolume& volume() const { return *volume_; }

private:
    void classify();
    void update(Frame& frame, const ProbeSettings& live);
    void finishUpdate(const ProbeSettings& live);
    void trace(const Frame& frame, const ProbeSettings& live, int first, int batch);
    void blend(int mode, const ProbeSettings& live, int first, int batch);
    void shade(const Frame& frame, const ProbeSettings& live);
    void setGridUniforms(GLuint program) const;
    void setVolumeUniforms(GLuint program) const;
    void bindProbeBuffers() const;
    ProbeSettings built_;
    probes::ProbeGrid grid_;
    SceneVolume* volume_ = nullptr;   // the renderer's, shared (SceneServices)
    VolumeFit fit_;                   // the volume's cube
    gl::Buffer irradiance_, distance_, state_, rays_, change_;
    gl::Texture diffuse_;
    gl::Object traceProgram_, blendProgram_, classifyProgram_, shadeProgram_, debugProgram_, raysProgram_, sampler_;
    glm::mat3 rotation_{1.0f};
    int batch_ = 1, firstProbe_ = 0, updates_ = 0, finished_ = 0, maxUpdates_ = 1;
    int lastFirst_ = -1;  // first probe of the last update's batch (-1: none yet), for probes.rays
    void drawRays(const Frame& frame, GLuint target);
    void dispatchDebugDraw(const Frame& frame, GLuint target);
    float cycleChange_ = 0.0f, lastChange_ = 0.0f;
    bool needClassify_ = true, converged_ = false, updatedLastFrame_ = false,
         pendingChange_ = false, warnedAllOff_ = false;
};

}  // namespace gis
