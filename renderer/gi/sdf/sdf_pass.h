// SDF GI (`--gi sdf`): the scene volume (renderer/volume: voxels, their direct light and emission,
// a signed distance field jump-flooded from its surface voxels) and, as Godot's SDFGI, a grid of
// probes per cascade kept by the shared probe pipeline (renderer/probes/probe_field.h: rays
// sphere-traced through the field within a ray budget, every bounce through the probes' own
// irradiance); per pixel the lighting contract's indirect.diffuse gathered from the 8 probes
// around it, reflection rays walked and shaded as the probes' own rays (indirect.specular, the
// shared probes/screen_reflection.h), and near-field soft occlusion from the field (ao).
// With sdf.diffuse=rays the diffuse term is instead a few cosine rays per traced pixel,
// accumulated over frames with reprojection and filtered edge-aware (the method before SDFGI, kept
// to compare), and the specular term a mirror ray below sdf.reflection-roughness, shaded by the
// voxels' light alone.
//
// Cascades (renderer/volume/volume_cascades.h): a scene whose cube is larger than
// sdf.cascade-extent gets up to four nested volumes around the camera, each with its own voxels,
// light and a layer of the field; a small scene (the Cornell box) gets one, the scene's cube. The
// volume rebuilds what changed (renderer/volume/scene_volume.h); a shifted cascade is rebuilt whole
// (voxelize, seed, every flood pass, inject): see renderer/gi/sdf/README.md for why. A camera move within the
// snap costs the trace, temporal and filter steps only.
#pragma once

#include <memory>

#include "gi/sdf/sdf_gi_uniforms.h"
#include "gi/sdf/sdf_settings.h"
#include "probes/probe_field.h"
#include "probes/screen_reflection.h"
#include "frame.h"
#include "gl/shader.h"
#include "volume/sdf_uniforms.h"
#include "volume/volume_pass.h"

namespace gis {

struct SceneServices;

class SdfGiPass final : public VolumePass {
public:
    SdfGiPass(SceneServices& services, const RenderSettings& settings);
    const char* name() const override { return "sdf"; }
    std::vector<std::string> ownInputs() const override {
        return {resource::kGbufferDepth, resource::kGbufferNormal, resource::kGbufferMaterial};
    }
    std::vector<std::string> outputs() const override {
        return {resource::kIndirectDiffuse, resource::kIndirectSpecular, resource::kAo};
    }
    void run(Frame& frame) override;
    bool settled() const override;
    Progress progress() const override;
    std::optional<RayCounts> raysTraced() const override;
    void invalidate(Changes c) override;
    bool writesImagesOrBuffers() const override { return true; }
    std::vector<std::string> stats() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // GPU bytes the pass will hold at these settings (the memory budget asks before allocating).
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const Scene& scene,
                                                                        const RenderSettings& settings);

    const DistanceField& field() const { return volume_->field(); }
    const CascadeLayout& layout() const { return volume_->layout(); }
    int cascadeCount() const { return volume_->cascadeCount(); }
    // Builds of each cascade's field (voxelize + seed + flood + resolve) and radiance (inject), and
    // of all cascades together.
    int fieldBuilds(int cascade = -1) const { return volume_->builds(cascade).fields; }
    int radianceBuilds(int cascade = -1) const { return volume_->builds(cascade).injections; }
    glm::ivec3 cascadeOffset(int cascade) const { return volume_->offset(cascade); }
    const probes::ProbeField* probeField() const { return field_.get(); }  // null with sdf.diffuse=rays

private:
    void trace(const Frame& frame, const SdfGiSettings& s);
    void accumulate(const Frame& frame, const SdfGiSettings& s);
    void filter(const Frame& frame, const SdfGiSettings& s);
    void setCommonUniforms(GLuint program, const Frame& frame) const;

    SdfGiSettings built_;
    gl::MemoryScope scope_;
    Aabb sceneBounds_;
    std::unique_ptr<probes::ProbeField> field_;   // sdf.diffuse=probes: a grid per cascade
    std::unique_ptr<probes::ScreenReflection> screenReflection_;  // with field_: indirect.specular
    int scale_ = 1;  // full-resolution pixels per traced pixel
    // Traced resolution: this frame's diffuse, mirror ray, occlusion, debug data; the history
    // and each history pixel's distance from its camera, ping-ponged.
    gl::Texture raw_, reflection_, occlusion_, info_, history_[2], historyDistance_[2];
    // Full resolution: the lighting contract's terms.
    gl::Texture diffuse_, specular_, ao_;
    gl::Object traceProgram_, temporalProgram_, filterProgram_, debugProgram_;
    gl::UniformBuffer<sdf::SdfMarchBlock> march_;
    gl::UniformBuffer<sdfgi::SdfDebugBlock> debug_;
    gl::UniformBuffer<sdfgi::SdfTraceBlock> traceBlock_;
    gl::UniformBuffer<sdfgi::SdfTemporalBlock> temporalBlock_;
    glm::mat4 prevViewProj_{1.0f};
    glm::vec3 prevCameraPos_{0.0f};
    int current_ = 0;
    int historyFrames_ = 0;      // frames accumulated into the history since it restarted
    float temporal_ = 0.0f;      // the live sdf.temporal the history was accumulated with
    bool hasHistory_ = false;
    bool changed_ = true;        // something arrived through invalidate() since the last execute
};

}  // namespace gis
