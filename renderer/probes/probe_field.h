// The probe pipeline that probe GI (`--gi probes`), SDF GI (`--gi sdf`) and HDDAGI share: grids of
// irradiance probes (one per cascade of the scene volume, cascadeProbeGrids) that
// trace rays through the scene volume's distance field (cascades handed over outwards), shade their
// hits from the voxels' light plus the probes' own irradiance (every bounce, DDGI's recursion), and
// blend them into SH or octahedral irradiance and distance moments with hysteresis. Each method
// adds its own gather (shaders/probes/probe_common.glsl: sampleProbes).
//
// Cost is a ray budget, as DDGI's (Majercik et al. 2019) optional per-frame budget: each frame
// updates as many probes as the budget's rays pay for, the least updated first (a round gives every
// probe one update), and among those the ones the camera sees, then the most changed; a restarted
// grid (its cascade moved) has the fewest updates and goes first. When a whole round changed no
// probe by the threshold the field has converged and costs nothing until something changes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "frame.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "probes/probe_math.h"
#include "probes/probe_uniforms.h"
#include "volume/sdf_uniforms.h"

namespace gis {

class SceneVolume;
struct CascadeLayout;
struct DebugViewDesc;

namespace probes {

// How probe rays find the scene: sphere-traced through the volume's distance field, or walked
// through its occupancy hierarchy by HDDA (volume/occupancy.h; no field).
enum class Tracer { DistanceField, Occupancy };

// What the field is built with (changing one rebuilds it) and what it reads live each frame.
struct FieldSettings {
    Tracer tracer = Tracer::DistanceField;
    Storage storage = Storage::Sh2;
    int rays = 128;           // per probe per update
    int rayBudget = 0;        // rays per frame over every probe, 0 = every due probe each frame
    bool relocate = true;     // probes inside geometry: pushed out, else switched off
    bool visibility = true;   // live: Chebyshev visibility from the distance moments
    bool pathTest = false;    // live: with visibility, a probe counts only along a clear straight path (kPathTestHelp)
    bool bounces = true;      // live: ray hits add the probes' own irradiance
    float hysteresis = 0.98f; // live: weight of the old value once warmed up
    float threshold = 0.01f;  // live: relative change below which a probe has converged
    int maxUpdates = 100;     // live: updates per probe after which it stops anyway
    float normalBias = 0.1f;  // live: gather offset along the normal and view, x the probe step
    float hitThreshold = sdf::kDefaultHitThreshold; // rays through a distance field: |distance| below this many cells is a hit
    int debugProbe = -1;      // live: the probe whose rays probes.rays draws, -1 the middle one
};

// The gather's visibility as the shaders read it (probe_common.glsl, sampleProbeGrid): 0 none,
// 1 the distance moments, 2 the moments and the straight path through the tracer's volume.
inline int visibilityMode(bool visibility, bool pathTest) { return visibility ? (pathTest ? 2 : 1) : 0; }

// GPU bytes of `probes` probes (irradiance, distance moments, state) and of the ray buffer and
// batch list for the probes a frame can update.
int64_t fieldStorageBytes(const FieldSettings& s, int probes);
int64_t fieldRayBytes(const FieldSettings& s, int probes);
// The probes one frame updates at most.
int batchCapacity(const FieldSettings& s, int probes);
// One grid per cascade of the volume (SDFGI's layout): cells of `spacing` x the cascade's extent.
// The coarsest cascade (which never moves) is fitted to the scene's bounds, so no probe sits on its
// outer walls, with a layer outside each face the volume gives air (fitProbeGrid); a finer one to
// its cube, so its probes move with it and their counts stay the same.
ProbeGrid cascadeProbeGrid(const SceneVolume& volume, const Aabb& sceneBounds, float spacing, int cascade);
std::vector<ProbeGrid> cascadeProbeGrids(const SceneVolume& volume, const Aabb& sceneBounds, float spacing);
int cascadeProbeCount(const Aabb& sceneBounds, const CascadeLayout& layout, float spacing);

// Throws gis::Error naming `budgetKey` for a budget that pays for no probe.
void checkFieldSettings(const FieldSettings& s, const std::string& budgetKey, const std::string& raysKey);

class ProbeField {
public:
    // `grids`: at most kMaxGrids, finest first; their probe counts are fixed from here on (place()
    // may move them). The volume must hold what `built.tracer` walks (a distance field or the
    // occupancy hierarchy), with one cascade per grid or one.
    ProbeField(const gl::MemoryScope& scope, SceneVolume& volume, std::vector<ProbeGrid> grids,
               const FieldSettings& built);
    ProbeField(const ProbeField&) = delete;
    ProbeField& operator=(const ProbeField&) = delete;

    // Moves grid g (same counts); a grid that moved is classified again and its probes restart.
    void place(int g, const ProbeGrid& grid);
    // Geometry, materials or lights changed: every probe restarts.
    void invalidate(Changes c);
    // Classifies what needs it, reads the last update back and updates this frame's due probes
    // within the budget (steps "probe classify", "probe trace", "probe blend irradiance", "probe blend
    // distance").
    void update(Frame& frame, const FieldSettings& live);

    // Grid uniforms and the probe buffers for a gather program (shaders/probes/probe_common.glsl).
    void bindForGather(GLuint program) const;
    // And the volume its tracer walks, for a gather that tests each probe's path to the surface
    // (shaders/probes/probe_tracer.glsl: the screen gather built for tracer()).
    void bindForScreenGather(GLuint program) const;
    // Everything a program that walks and shades rays as the probes do needs
    // (shaders/probes/probe_hit_light.glsl): the gather's inputs, the voxels' light and albedo, the
    // update block of `live`. releaseHitLight() unbinds the samplers it set.
    void bindForHitLight(GLuint program, const FieldSettings& live) const;
    void releaseHitLight() const;
    Tracer tracer() const { return built_.tracer; }
    const std::vector<ProbeGrid>& grids() const { return grids_; }
    int count() const { return count_; }
    const FieldSettings& built() const { return built_; }

    bool converged() const { return converged_; }
    bool updatedLastFrame() const { return updatedLastFrame_; }
    int updates() const { return updates_; }            // frames with an update since the last restart
    // Update frames as a pass's progress: done = read back, target = the most there can be, both
    // the updates done once converged (so `--timings` divides by those).
    Pass::Progress progress() const;
    float lastChange() const { return lastChange_; }    // largest relative change of the last batch read back
    int lastBatch() const { return lastBatch_; }        // probes the last update traced
    uint64_t lastBatchRays() const { return lastRays_; }  // rays it traced, counted on the GPU
    RayCounts raysTraced() const { return rays_total_; }  // every probe ray since construction (as bounce rays)
    struct StateCounts {
        int active = 0, relocated = 0, off = 0;
    };
    StateCounts stateCounts() const;                    // reads the state buffer back
    std::vector<glm::vec3> readIrradiance(int probe) const;

    // "PREFIX.spheres", "PREFIX.state", "PREFIX.rays" (of `debugProbe`: which probe that draws).
    std::vector<DebugViewDesc> debugViews(const std::string& prefix, const std::string& debugProbe) const;
    // `view` without the prefix: "spheres", "state" or "rays".
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target, const FieldSettings& live);
    std::string describe() const;   // "probes 5x5x5 = 125, sh2 storage, ..."

private:
    int maxUpdates() const;   // the most update frames there can be
    void classify(int grid);
    void readBack(const FieldSettings& live);
    std::vector<int> schedule(const Frame& frame, const FieldSettings& live) const;
    void trace(const Frame& frame, const FieldSettings& live, int batch);
    void blend(int mode, const FieldSettings& live, int batch);
    void setGridUniforms(GLuint program) const;
    void setFieldUniforms(GLuint program) const;
    void setUpdateBlock(const FieldSettings& live) const;
    void bindTracer() const;   // the field's textures or the occupancy buffers
    void bindBuffers() const;
    void dispatchDebugDraw(const Frame& frame, GLuint target);
    void restart();

    FieldSettings built_;
    SceneVolume* volume_;
    std::vector<ProbeGrid> grids_;
    std::vector<bool> needClassify_;
    int count_ = 0, capacity_ = 1;
    gl::Buffer irradiance_, distance_, state_, rays_, change_, batch_;
    gl::Object classifyProgram_, traceProgram_, blendProgram_, debugProgram_, raysProgram_, sampler_;
    glm::mat3 rotation_{1.0f};
    // The CPU's copy of each probe's update count and last change (read back one frame late).
    std::vector<float> probeUpdates_, probeChange_;
    std::vector<bool> probeOff_;
    float roundStart_ = 0.0f, roundChange_ = 0.0f;  // fewest updates when this round began; its largest change
    std::vector<int> lastBatchProbes_;
    int updates_ = 0, finished_ = 0, lastBatch_ = 0, maxUpdates_ = 100;
    // A probe's first updates replace its value instead of averaging it: each adds one bounce (the
    // rays' hits read the probes' irradiance), so the remainder falls as albedo^n; averaging from
    // the first update (weights 2/(n+2)) slows that to n^(-2 (1 - albedo)), and an albedo-0.9
    // furnace converged to 0.55 of its infinite-bounce radiance. How many: feedbackBouncesFor
    // (scene/scene_lighting.h); 0 = not yet worked out.
    int bounceUpdates_ = 0;
    uint64_t lastRays_ = 0;
    RayCounts rays_total_;
    float lastChange_ = 0.0f;
    bool converged_ = false, updatedLastFrame_ = false, pending_ = false, warnedAllOff_ = false;
    gl::UniformBuffer<ProbeUpdateBlock> update_;
};

// For a field built from cascadeProbeGrids: each grid follows its cascade (a grid whose cascade
// moved is classified again and its probes restart).
void followCascades(ProbeField& field, const SceneVolume& volume, const Aabb& sceneBounds, float spacing);

std::vector<ProgramDesc> fieldPrograms();   // both tracers' variants

}  // namespace probes
}  // namespace gis
