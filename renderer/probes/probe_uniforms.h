// Explicit uniform locations and uniform blocks of the shared probe pipeline and its gathers
// (gl/uniform_table.h, gl/uniform_block.h: emitted into every shader; the shader-constants test
// checks no two tables overlap and that GL lays each block out as C++ does). The grid arrays hold
// one entry per probe grid (a cascade's probes each: PROBE_MAX_GRIDS = SDF_MAX_CASCADES).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"
#include "volume/volume_cascades.h"

namespace gis::probes {
constexpr int kMaxGrids = kMaxCascades;
#define GIS_PROBE_UNIFORMS(X) \
    X(UP_GRID_FIRST, 500, kMaxGrids) /* per grid: world position of its probe (0, 0, 0) */ \
    X(UP_GRID_STEP, 504, kMaxGrids) /* per grid: world step between neighbours per axis */ \
    X(UP_GRID_COUNTS, 508, kMaxGrids) /* per grid: probes per axis */ \
    X(UP_GRID_COUNT, 512, 1) /* grids in use, finest first */ \
    X(UP_STORAGE, 513, 1) /* 0 sh1, 1 sh2, 2 octahedral */ \
    X(UP_RAYS, 514, 1) /* rays per probe */ \
    X(UP_ROTATION, 515, 1) /* mat3: this update's random rotation of the ray set */ \
    X(UP_CASCADES, 517, kMaxGrids) /* the distance field's cascades: origin xyz, edge; finest first */ \
    X(UP_CASCADE_COUNT, 521, 1) \
    X(UP_SDF_RESOLUTION, 522, 1) /* cells per cascade edge */ \
    X(UP_SPHERE_RADIUS, 523, 1) /* probe views: the drawn spheres' radius, world units */ \
    X(UP_INV_VIEW_PROJ, 524, 1) \
    X(UP_CAMERA_POS, 525, 1) \
    X(UP_MODE, 527, 1) /* blend: 0 irradiance, 1 distance; classify: 0 relocate, 1 off; views: mode / probe */ \
    X(UP_VIEW_PROJ, 528, 1) \
    X(UP_SLOT_OFFSET, 529, 1) /* trace/blend: batch slot of work group 0 (a batch past the group limit is split) */ \
    X(UP_BATCH_SLOT, 530, 1) /* probes.rays view: the drawn probe's slot in the last batch, -1 none */ \
    X(UP_CLASSIFY_GRID, 531, 1) /* classify: the grid whose probes are (re)classified, -1 all */ \
    X(UP_GATHER_SCALE, 532, 1) /* probe GI: full-resolution pixels per gathered pixel (1, 2, 4) */

enum ProbeUniform : int { GIS_PROBE_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kProbeUniforms[] = {GIS_PROBE_UNIFORMS(GIS_UNIFORM_SLOT)};

// Binding points of the probe pipeline's programs. Storage buffers: the probes' irradiance,
// distance moments and state (every gather), the last update's rays, its change counters and its
// batch (trace, blend, the rays view). Texture units of the programs that walk the field (the
// distance field's two levels where the tracer has one) and shade its rays
// (probes/probe_hit_light.glsl: the probes' own rays and the screen reflection's): the voxel
// radiance, the albedo (both a layer per cascade, as the volume holds them), the slab voxels' sides; the
// screen gather's and the reflection's G-buffer inputs. Image units: each program's output, the
// gathered pixels, the reflection's running mean, the gather's indirect.diffuse it blends
// towards (and fills where no probe sees a point), and that fill's running mean. All below 11,
// where the environment's units begin (volume/volume_slots.h).
#define GIS_PROBE_BINDINGS(X) \
    X(SP_IRRADIANCE, 0) \
    X(SP_DISTANCE, 1) \
    X(SP_STATE, 2) \
    X(SP_RAYS, 3) \
    X(SP_CHANGE, 4) \
    X(SP_BATCH, 5) \
    X(TP_FIELD_DISTANCE, 0) \
    X(TP_FIELD_COARSE, 1) \
    X(TP_VOXEL_RADIANCE, 2) \
    X(TP_VOXEL_ALBEDO, 3) \
    X(TP_VOXEL_SIDES, 7) \
    X(TP_GATHER_DEPTH, 4) \
    X(TP_GATHER_NORMAL, 5) \
    X(TP_GATHERED, 6) \
    X(TP_REFLECT_DEPTH, 8) \
    X(TP_REFLECT_NORMAL, 9) \
    X(TP_REFLECT_MATERIAL, 10) \
    X(IP_OUTPUT, 0) \
    X(IP_REFLECT_SPECULAR, 0) \
    X(IP_REFLECT_MEAN, 1) \
    X(IP_REFLECT_DIFFUSE, 2) \
    X(IP_UNSEEN_MEAN, 3)

enum ProbeBinding : int { GIS_PROBE_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kProbeBindings[] = {GIS_PROBE_BINDINGS(GIS_BINDING_SLOT)};

// One probe update (probe_trace.comp's rays, probe_blend.comp's blend).
#define GIS_PROBE_UPDATE_BLOCK(M, A) \
    M(float, hysteresis)        /* the moving average's floor: weight 1 - hysteresis */ \
    M(float, replacingUpdates)  /* blend: a probe's first updates replace its value (one bounce each) */ \
    M(float, missDistance)      /* what a ray that hits nothing records as its distance */ \
    M(int, multiBounce)         /* trace: 1 lights hits with the probes' irradiance (the next bounce) */ \
    M(int, visibility)          /* trace: that irradiance's visibility (probe_field.h, visibilityMode) */ \
    M(float, normalBias)        /* trace: that lookup's offset along the normal, x the smallest probe step */ \
    M(float, hitThreshold)      /* trace through the distance field: |distance| below this many cells is a hit */
GIS_UNIFORM_BLOCK(ProbeUpdateBlock, 6, GIS_PROBE_UPDATE_BLOCK)

// The screen gather (screen_gather.glsl).
#define GIS_PROBE_GATHER_BLOCK(M, A) \
    M(float, normalBias)        /* along the normal and towards the eye, x the smallest probe step */ \
    M(float, intensity) \
    M(int, visibility)          /* probe_field.h, visibilityMode: 1 distance moments, 2 and the path */
GIS_UNIFORM_BLOCK(ProbeGatherBlock, 7, GIS_PROBE_GATHER_BLOCK)

// The screen reflection (screen_reflection.comp; renderer/probes/screen_reflection.h).
#define GIS_PROBE_REFLECT_BLOCK(M, A) \
    M(float, roughness)         /* rays below this roughness; at and above it the diffuse gather */ \
    M(int, rays)                /* per pixel per frame, drawn from the GGX lobe (one at a mirror) */ \
    M(float, framesAveraged)    /* still frames already in the running mean */ \
    M(int, frame)               /* random stream */ \
    M(float, unseenIntensity)   /* > 0: pixels no probe sees trace cosine rays (as many) for their diffuse light, \
                                   scaled by it (METHOD.intensity); 0: left as the gather leaves them */
GIS_UNIFORM_BLOCK(ProbeReflectBlock, 14, GIS_PROBE_REFLECT_BLOCK)
}  // namespace gis::probes
