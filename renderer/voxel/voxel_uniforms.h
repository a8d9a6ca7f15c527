// Explicit uniform locations of the voxel module and VCT: shaders/voxel/voxel_uniforms.glsl mirrors it.
#pragma once

namespace gis::voxel {
enum VoxelUniform : int {
    UV_WORLD_TO_VOXEL = 100,
    UV_RESOLUTION = 101,
    UV_CONSERVATIVE = 102,     // 0 off, 1 geometry-shader dilation, 2 hardware
    UV_EMISSION_SCALE = 103,   // 1 / the largest emission, so sums stay in fixed-point range
    UV_VOXEL_TO_WORLD = 104,
    UV_VOXEL_SIZE = 105,
    UV_LIGHT_COUNT = 106,
    UV_SHADOWS_ENABLED = 107,
    UV_MIP_LEVEL = 108,        // the level being written
    UV_DIRECTION = 109,        // anisotropic mip: 0..5 = +X -X +Y -Y +Z -Z
    UV_INV_VIEW_PROJ = 110,
    UV_CAMERA_POS = 111,
    UV_CONE_SET = 112,         // 0 = six cones (60 degrees), 1 = four (90), 2 = many (32 of 14)
    UV_TRACE_PARAMS = 113,     // step factor, max distance (voxels), start offset (voxels), specular scale
    UV_ENVIRONMENT = 114,
    UV_ANISOTROPIC = 115,      // 0 isotropic, 1 directional mips, 2 directional without back faces
    UV_INTENSITY = 116,
    UV_DEBUG_PARAMS = 117,     // channel, mip level, slice axis, slice position
    UV_BOUNCE = 118,
    UV_NORMAL_WEIGHT = 119,    // directional mip from level 0: 1 weigh voxels by |normal . axis|, 2 cull back faces
    UV_EMISSION_WEIGHT = 120,  // injection: 1 = emission is a light source of the volume, 0 = not (emitters.mode)
    UV_EMITTER_SAMPLES = 121,  // injection with emitter light: emitter count, samples per voxel
};
}  // namespace gis::voxel
