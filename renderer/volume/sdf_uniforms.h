// Explicit uniform locations and the march block of the distance-field module (gl/uniform_table.h,
// gl/uniform_block.h: emitted into every shader; the shader-constants test checks no two tables
// overlap, since the SDF method's trace shader uses this, the voxel and the core tables together,
// and that GL lays the block out as C++ does).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"

namespace gis::sdf {
// Sphere tracing's default hit threshold, in cells of the cascade marched in (SDF_HIT_THRESHOLD in
// GLSL, sdf_march.glsl's sdfDefaultParams): the probe gathers' path test keeps it, the rays of SDF
// GI's pixels and probes take `sdf.hit-threshold` (its default).
inline constexpr float kDefaultHitThreshold = 0.5f;

#define GIS_SDF_UNIFORMS(X) \
    X(US_RESOLUTION, 400, 1) /* cells per edge */ \
    X(US_JFA_STEP, 401, 1) /* the jump of this flood pass, in cells */ \
    X(US_CELL_SIZE, 403, 1) /* world edge of one cell */ \
    X(US_FAR, 404, 1) /* the value of cells no seed reaches */ \
    X(US_HAS_NORMALS, 405, 1) /* 1: sign from the seeds' normals; 0: unsigned */ \
    X(US_COARSE_FACTOR, 406, 1) /* fine cells per coarse cell along an edge */ \
    X(US_LAYER, 407, 1) /* the layer (cascade) of a layered field written by this dispatch */

enum SdfUniform : int { GIS_SDF_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kSdfUniforms[] = {GIS_SDF_UNIFORMS(GIS_UNIFORM_SLOT)};

// How sphere tracing marches the field (shaders/volume/sdf_march.glsl's SdfMarchParams).
#define GIS_SDF_MARCH_BLOCK(M, A) \
    M(float, hitThreshold)  /* cells */ \
    M(float, relaxation)    /* over-relaxed step factor */ \
    M(int, maxSteps) \
    M(float, offset)        /* the rays' start along the normal, cells */
GIS_UNIFORM_BLOCK(SdfMarchBlock, 4, GIS_SDF_MARCH_BLOCK)
}  // namespace gis::sdf
