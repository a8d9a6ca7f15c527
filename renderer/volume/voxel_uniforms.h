// Explicit uniform locations and uniform blocks of the voxel module and VCT (gl/uniform_table.h,
// gl/uniform_block.h: emitted into every shader; the shader-constants test checks no two tables
// overlap and that GL lays each block out as C++ does).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"

namespace gis::voxel {
#define GIS_VOXEL_UNIFORMS(X) \
    X(UV_WORLD_TO_VOXEL, 100, 1) \
    X(UV_RESOLUTION, 101, 1) \
    X(UV_CONSERVATIVE, 102, 1) /* 0 off, 1 geometry-shader dilation, 2 hardware */ \
    X(UV_EMISSION_SCALE, 103, 1) /* 1 / the largest emission, so sums stay in fixed-point range */ \
    X(UV_VOXEL_TO_WORLD, 104, 1) \
    X(UV_VOXEL_SIZE, 105, 1) \
    X(UV_LIGHT_COUNT, 106, 1) \
    X(UV_SHADOWS_ENABLED, 107, 1) \
    X(UV_MIP_LEVEL, 108, 1) /* the level being written */ \
    X(UV_DIRECTION, 109, 1) /* anisotropic mip: 0..5 = +X -X +Y -Y +Z -Z */ \
    X(UV_INV_VIEW_PROJ, 110, 1) \
    X(UV_CAMERA_POS, 111, 1) \
    X(UV_CONE_SET, 112, 1) /* 0 = six cones (60 degrees), 1 = four (90), 2 = many (32 of 14) */ \
    X(UV_ANISOTROPIC, 115, 1) /* 0 isotropic, 1 directional mips, 2 directional without back faces */ \
    X(UV_INTENSITY, 116, 1) \
    X(UV_NORMAL_WEIGHT, 119, 1) /* directional mip from level 0: 1 weigh voxels by |normal . axis|, 2 cull back faces */ \
    X(UV_EMISSION_WEIGHT, 120, 1) /* injection: 1 = emission is a light source of the volume, 0 = not (emitters.mode) */ \
    X(UV_EMITTER_SAMPLES, 121, 1) /* injection with emitter light: emitter count, samples per voxel */ \
    X(UV_ENVIRONMENT_SAMPLES, 131, 1) /* injection with environment light: directions per voxel, 0 none */ \
    X(UV_TRACE_JITTER, 122, 1) /* VCT: full pixels per traced texel, the full pixel a texel traces this frame */ \
    X(UV_SPECULAR_ROUGHNESS, 123, 1) /* VCT: above it the specular term is the diffuse cones' */ \
    X(UV_PREV_VIEW_PROJ, 124, 1) \
    X(UV_PREV_CAMERA_POS, 125, 1) \
    X(UV_HISTORY, 126, 1) /* VCT upsample: history valid (0/1), camera moved (0/1) */ \
    X(UV_CASCADE, 127, 1) /* occupancy build: the cascade written */ \
    X(UV_KEEP_LO, 128, 1) /* scrolled voxelization: voxels in [lo, hi) were kept (moved), not voxelized again */ \
    X(UV_KEEP_HI, 129, 1) \
    X(UV_EXTERIOR_STEP, 130, 1) /* exterior.comp: seed 0 / cull 2 and environment lit, or the sweep's axis */

enum VoxelUniform : int { GIS_VOXEL_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kVoxelUniforms[] = {GIS_VOXEL_UNIFORMS(GIS_UNIFORM_SLOT)};

// Binding points of the voxel module's programs, each block one program's: its texture units (TV_),
// image units (IV_) and storage buffers (SV_). A program that traces (bounce.comp with rays,
// inject.comp lighting by the direct pass's lights) samples the ray scene's textures at its own
// unit, above the ones it reads the grid through.
#define GIS_VOXEL_BINDINGS(X) \
    /* voxel_resolve.comp: the grid it writes */ \
    X(IV_RESOLVE_ALBEDO, 0) \
    X(IV_RESOLVE_NORMAL, 1) \
    X(IV_RESOLVE_EMISSION, 2) \
    /* inject.comp */ \
    X(TV_INJECT_ALBEDO, 0) \
    X(TV_INJECT_NORMAL, 1) \
    X(TV_INJECT_EMISSION, 2) \
    X(TV_INJECT_SHADOW_MAPS, 5) \
    X(TV_INJECT_SHADOW_CUBES, 6) \
    X(TV_INJECT_RAY_SCENE, 7) \
    X(IV_INJECT_RADIANCE, 0) \
    X(IV_INJECT_SIDES, 1) \
    X(IV_INJECT_PUNCTUAL, 2) \
    /* exterior.comp (the seed, the sweeps, the cull) */ \
    X(TV_EXTERIOR_ALBEDO, 0) \
    X(TV_EXTERIOR_NORMAL, 1) \
    X(TV_EXTERIOR_RADIANCE, 2) \
    X(IV_EXTERIOR_REACH, 0) \
    X(IV_EXTERIOR_RADIANCE, 1) \
    X(SV_EXTERIOR_CHANGED, 0) \
    /* voxel_mip.comp */ \
    X(TV_MIP_SOURCE, 0) \
    X(TV_MIP_NORMAL, 1) \
    X(TV_MIP_SIDES, 2) \
    X(IV_MIP_TARGET, 0) \
    /* bounce.comp (the volume's own units above these: SceneVolume's slots) */ \
    X(TV_BOUNCE_ALBEDO, 0) \
    X(TV_BOUNCE_NORMAL, 1) \
    X(TV_BOUNCE_DIRECT, 2) \
    X(TV_BOUNCE_DIRECT_SIDES, 3) \
    X(TV_BOUNCE_RAY_SCENE, 4) \
    X(IV_BOUNCE_RADIANCE, 0) \
    X(IV_BOUNCE_SIDES, 1) \
    /* occupancy_build.comp */ \
    X(TV_OCCUPANCY_ALBEDO, 0) \
    /* hdda_probe.comp: the tests' walk through the occupancy (tests/volume/test_hdda.cpp) */ \
    X(SV_HDDA_PROBE_RAYS, 0) \
    X(SV_HDDA_PROBE_HITS, 1) \
    X(SV_HDDA_PROBE_POSITIONS, 2)

enum VoxelBinding : int { GIS_VOXEL_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kVoxelBindings[] = {GIS_VOXEL_BINDINGS(GIS_BINDING_SLOT)};

// How cones march the voxel radiance (shaders/volume/cone_trace.glsl): the bounces' gather and VCT's.
#define GIS_CONE_TRACE_BLOCK(M, A) \
    M(float, stepFactor)   /* each step's length over the cone's diameter there */ \
    M(float, maxDistance)  /* voxels */ \
    M(float, offset)       /* the cones' start along the normal, voxels */ \
    M(int, specular)       /* VCT: 1 traces the specular cone */ \
    M(int, skyRays)        /* VCT: rays per cone deciding its environment term (vct.sky-rays); 0 the cone's transmittance */
GIS_UNIFORM_BLOCK(ConeTraceBlock, 2, GIS_CONE_TRACE_BLOCK)

// What VCT's debug views show (vct.voxels and vct.slice).
#define GIS_VCT_DEBUG_BLOCK(M, A) \
    M(int, channel)        /* 0 albedo, 1 emission, 2 radiance, 3 occupancy */ \
    M(int, level)          /* mip level */ \
    M(int, sliceAxis)      /* 0..2; -1: march rays from the camera instead of a slice */ \
    M(float, slicePosition) /* 0..1 along the axis */
GIS_UNIFORM_BLOCK(VctDebugBlock, 3, GIS_VCT_DEBUG_BLOCK)
}  // namespace gis::voxel
