// The light the voxels send out: direct light from every punctual light through its shadow map
// plus emission, injected per voxel (Lambertian), optionally further bounces gathered by cone
// tracing in voxel space, and the mip chains cones read (isotropic, and six directional ones).
// Probe GI and the SDF method shade their ray hits from the same radiance.
#pragma once

#include <functional>

#include <string>

#include "ray_scene.h"
#include "frame.h"
#include "gl/shader.h"
#include "volume/voxel_uniforms.h"
#include "volume/voxelizer.h"

namespace gis {

struct ConeSettings {
    int coneSet = 0;             // 0: 6 cones of 60 degrees (Godot's set), 1: 4 of 90 degrees, 2: 32 of 14
    float stepFactor = 0.5f;     // step as a fraction of the cone diameter
    float maxDistance = 0.0f;    // voxels; 0 = the volume's diagonal
    float offset = 1.0f;         // self-occlusion offset along the normal, voxels
    // Rays per diffuse cone through the scene's triangles in place of the cones' march
    // (vct.sky-rays; shaders/volume/cone_rays.glsl); 0: the cones march.
    int rays = 0;
    bool operator==(const ConeSettings& o) const {
        return coneSet == o.coneSet && stepFactor == o.stepFactor && maxDistance == o.maxDistance && offset == o.offset &&
               rays == o.rays;
    }
};

// Bytes of the radiance chains at this resolution (for the budget check before allocating).
// unlitOutsides: with the reach grid cullUnlitOutsides() floods (one byte a voxel).
// hitLights: level 0's punctual share (punctual()).
int64_t voxelRadianceBytes(int resolution, bool anisotropic, int bounces, bool unlitOutsides = false, bool hitLights = false);
// Bytes of a feedback volume (VoxelRadiance::feedbackBounce) at this resolution: its chains, its
// direct light and its scratch level, each with its slab sides.
int64_t voxelFeedbackBytes(int resolution, bool anisotropic, bool hitLights = false);

class VoxelRadiance {
public:
    // cullBackfaces: the directional chains leave out the voxels a cone meets from behind, so a
    // cone never sees the surface it leaves (only with anisotropic). cullUnlitOutsides: inject()
    // leaves out the surfaces that face air no light reaches (shaders/volume/exterior.comp).
    // hitLights: level 0 keeps its punctual share for tracers whose hits light themselves.
    VoxelRadiance(int resolution, bool anisotropic, int bounces, const gl::MemoryScope& scope,
                  bool cullBackfaces = false, bool cullUnlitOutsides = false, bool hitLights = false);
    struct Lights {
        GLuint buffer = 0, shadowMaps = 0, shadowCubes = 0;
        int count = 0;
        bool shadows = true;
        // 0 when the emitters are lights of the direct pass (emitters.mode=lights or off): the
        // volume then holds no emission, so no method counts an emitter's light twice.
        float emission = 1.0f;
        // The lights of the direct pass, traced through `rays` (inject.comp's TRACED_LIGHT; null:
        // none): with emitters.mode=lights its emissive triangles, `emitterSamples` points per voxel;
        // with emitters.environment the environment, `environmentSamples` directions per voxel
        // (the caller binds the environment).
        const RayScene* rays = nullptr;
        int emitterSamples = 0, environmentSamples = 0;
        // The environment sends light in from the volume's bounds (a map, or a background above 0).
        bool environmentLit = false;
    };
    // Direct light + emission into level 0.
    void inject(const VoxelGrid& grid, const Lights& lights);
    // The mip chains from level 0 (and the directional chains when anisotropic, which read the
    // grid's normals).
    void buildMips(const VoxelGrid& grid);
    // bounces - 1 more bounces, each followed by new mips. Needs inject() and buildMips() first.
    // Cones that leave the volume see the environment the caller bound (Frame::bindEnvironment).
    // With cones.rays, `rays` is the scene they are traced through.
    void bounce(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays = nullptr);
    // Bounce feedback (vct.feedback; needs bounces > 1 for the direct-light volume): level 0 and
    // the sides of `injected` (another volume's direct light and emission) become this one's direct
    // light and its starting radiance, followed by its mips.
    void restartFeedback(const VoxelGrid& grid, const VoxelRadiance& injected);
    // One bounce more than the last call: radiance = direct + albedo * the diffuse cones' gather
    // from the previous result, then new mips. Repeated, it sums the bounce series (the voxel
    // counterpart of DDGI's recursive irradiance); it cannot diverge for albedo < 1, as each term
    // is the previous one scaled by albedo times the gathered fraction (at most 1).
    void feedbackBounce(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays = nullptr);
    // At kVolumeRadianceUnit and the units after it (shaders/volume/cone_trace.glsl's layout), and
    // the hits' lights (bindHitLights).
    void bind() const;
    // What shaders/volume/hit_light.glsl reads: the punctual share at kVolumePunctualUnit, and the
    // lights and shadow maps of the last inject() (volume_slots.h).
    void bindHitLights() const;
    const gl::Texture& radiance() const { return radiance_; }
    // Level 0's slab voxels (walls thinner than a voxel, shaders/volume/inject.comp): rgb half the
    // difference of their two faces' light, a the slab's axis (1, 2, 3; 0: not a slab).
    const gl::Texture& sides() const { return sides_; }
    // Level 0's share of the punctual lights (rgb, premultiplied; a = occupancy), which a ray's hit
    // takes out to light itself (shaders/volume/hit_light.glsl); with hitLights only (else no texture,
    // and injection's stores to it do nothing).
    const gl::Texture& punctual() const { return punctual_; }
    bool anisotropic() const { return anisotropic_; }
    // UV_ANISOTROPIC for shaders/volume/cone_trace.glsl's makeConeTracer (VOXEL_ISOTROPIC ...).
    int mipMode() const { return !anisotropic_ ? 0 : cullBackfaces_ ? 2 : 1; }
    int resolution() const { return radiance_.width; }
    static std::vector<ProgramDesc> programs();

private:
    // The bounce program for these cones (with rays: the variant that traces them through `rays`),
    // bound, with its uniforms set.
    GLuint useBounceProgram(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays);
    // exterior.comp's three steps on `target` (level 0 as injected): seed, flood, cull.
    void cullUnlitOutsides(const VoxelGrid& grid, const gl::Texture& target, bool environmentLit);
    // A bounce's results, written while the cones read the chain and the sides.
    struct Scratch {
        gl::Texture radiance, sides;
    };
    Scratch makeScratch() const;
    // One gather of the current chain into `scratch`, copied over level 0 and the sides, then new mips.
    void gatherOnce(const VoxelGrid& grid, const Scratch& scratch, GLuint program);
    // The direct light (and its sides) as the radiance to bounce from.
    void copyDirectLight();
    void downsample(const gl::Texture& source, int sourceLevel, const gl::Texture& target, int targetLevel, int direction,
                    GLuint normals = 0);
    gl::Texture radiance_, direct_, sides_, punctual_;
    Lights hitLights_;  // the last inject()'s, for bindHitLights
    gl::Texture directSides_;  // with bounces: the sides of the direct light, which each bounce adds to
    Scratch feedbackScratch_;  // feedbackBounce()'s target, kept between updates (made on first need)
    gl::Texture directional_[6];
    gl::Object injectProgram_, mipProgram_, bounceProgram_;
    gl::Object bounceRaysProgram_;  // built on first need
    gl::Object tracedInjectProgram_;  // built on first need
    gl::Object exteriorProgram_, sweepProgram_;  // with cullUnlitOutsides
    gl::Texture reach_;                          // R8UI: air that light reaches
    gl::Buffer changed_;                         // voxels a sweep round reached
    gl::UniformBuffer<voxel::ConeTraceBlock> coneBlock_;  // the bounces' cones
    gl::MemoryScope scope_;
    bool anisotropic_, cullBackfaces_;
    int bounces_;
};

// The scene volume's first two steps (renderer/volume/scene_volume.h): voxelize the scene, and
// inject the frame's punctual lights (through the shadow pass's maps) and emission, timed as the
// executing pass's `prefix` + "voxelize" and `prefix` + "inject" steps.
void voxelizeFrame(Frame& frame, Voxelizer& voxelizer, const std::string& prefix = "");
// Emitters that are lights are sampled from the scene's ray scene, which `rays` builds on first use.
using RaySceneSource = std::function<RayScene&()>;
void injectFrameLights(Frame& frame, const VoxelGrid& grid, VoxelRadiance& radiance, const RaySceneSource& rays,
                       const std::string& prefix = "");

}  // namespace gis
