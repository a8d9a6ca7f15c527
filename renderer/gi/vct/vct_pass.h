// Voxel cone tracing (`--gi vct`): the scene volume (renderer/volume: voxels, their direct light
// and emission, the mip chains) traced with cones per pixel into the lighting contract's
// "indirect.diffuse" and "indirect.specular". The volume is view independent and rebuilds only
// what changed (a light edit relights without voxelizing), so a camera move costs the trace
// alone. The cones' occlusion is already
// in indirect.diffuse, so the pass does not write "ao" (the lighting pass would multiply it in a
// second time); it is the debug view "vct.ao".
// At vct.trace-scale 2 or 4 the cones run for one pixel of each 2x2 or 4x4 block, a different one
// each frame, and vct_upsample.comp gathers them at full resolution with the reprojected history.
#pragma once

#include <memory>

#include "gi/vct/vct_settings.h"
#include "frame.h"
#include "gl/shader.h"
#include "volume/volume_pass.h"
#include "volume/voxel_uniforms.h"

namespace gis {

struct SceneServices;

class VctPass final : public VolumePass {
public:
    // Rebuild parameters come from settings.params ("vct.*").
    VctPass(SceneServices& services, const RenderSettings& settings);
    const char* name() const override { return "vct"; }
    std::vector<std::string> ownInputs() const override {
        return {resource::kGbufferDepth, resource::kGbufferNormal, resource::kGbufferMaterial};
    }
    std::vector<std::string> outputs() const override {
        return {resource::kIndirectDiffuse, resource::kIndirectSpecular};
    }
    void run(Frame& frame) override;
    // Further bounces gather with the live cones at the built resolution.
    ConeSettings bounceCones(const Frame& frame) const override;
    // The trace runs every frame, so the pass as a whole never reuses its result; the volume's
    // voxelize, inject and mips steps do (they show as cached in --timings).
    bool reusedLastFrame() const override { return false; }
    // Nothing changed for as many frames as a static view takes to converge, and the bounce
    // feedback (vct.feedback) has added its last bounce.
    bool settled() const override {
        return framesUnchanged_ >= built_.framesToFullResolution() && feedbackDone();
    }
    // With vct.feedback: the bounces added since the volume was last lit, of those wanted.
    Progress progress() const override;
    // Camera moves keep the history (it is reprojected); anything else starts it over.
    void invalidate(Changes changes) override;
    bool voxelsReusedLastFrame() const { return volume_->lastUpdate(0) == SceneVolume::Update::Cached; }
    int voxelizations() const { return volume_->builds().voxelizations; }  // how often the scene was voxelized
    int injections() const { return volume_->builds().injections; }        // how often light was injected
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override {
        return {describeVolume(volume_->grid().fit, "voxels"), volume_->describeCascade(0)};
    }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

    const VctSettings& rebuildSettings() const { return built_; }

private:
    // What a reduced-resolution frame leaves for the next one: the full-resolution terms and the
    // surfaces they belong to.
    struct History {
        gl::Texture diffuse, specular, geometry;
    };
    bool feedbackDone() const { return !built_.feedback || feedbackUpdates_ >= feedbackTarget_; }
    // Restarts the feedback from the volume's injected light when that was relit, then adds one
    // bounce unless converged; true when the traced light changed.
    bool updateFeedback(Frame& frame, const ConeSettings& cones);
    void trace(const Frame& frame, const VctSettings& live, glm::ivec2 jitter);
    void upsample(const Frame& frame, glm::ivec2 jitter);
    // The sky rays' noise filtered out of a full-resolution diffuse term into skyFiltered_
    // (vct_sky_filter.comp).
    void filterSky(const Frame& frame, const gl::Texture& diffuse);
    // The diffuse term the frame shows: `diffuse` itself, or filtered where sky rays were traced.
    const gl::Texture& skyFilteredDiffuse(Frame& frame, const gl::Texture& diffuse);
    VctSettings built_;    // the rebuild parameters this pass was made with
    VctSettings live_;     // the live parameters of the last frame
    SceneServices* services_;  // its ray scene is what the sky rays trace (built on first use)
    gl::Texture diffuse_, specular_, ao_;   // what the cones traced: one texel per vct.trace-scale block
    gl::Texture skyFiltered_;               // the full-resolution diffuse term with the sky rays' noise filtered out
    History history_[2];                    // trace scale above 1: written alternately, [current_] last
    int current_ = 0;
    bool hasHistory_ = false;               // history_[current_] belongs to this scene and these settings
    bool cameraMoved_ = false;              // since the last frame
    CameraMatrices lastCamera_;
    int framesUnchanged_ = 0;               // frames executed since the last invalidate()
    uint32_t framesTraced_ = 0;             // picks the jitter phase
    // vct.feedback (the volume's feedback light, VolumeRequest::feedback): one update adds one bounce.
    int feedbackUpdates_ = 0;   // bounces added since the volume was last lit
    int feedbackTarget_ = 0;    // bounces wanted for the scene's albedo (feedbackBouncesFor)
    gl::Object traceProgram_, upsampleProgram_, debugProgram_, skyFilterProgram_;
    gl::UniformBuffer<voxel::ConeTraceBlock> cones_;
    gl::UniformBuffer<voxel::VctDebugBlock> debug_;
};

}  // namespace gis
