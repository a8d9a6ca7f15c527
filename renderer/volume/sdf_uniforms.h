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

// Binding points of the field's programs, each block one program's: texture units (TF_), image
// units (IF_), storage buffers (SF_). The march probe is the tests' (tests/volume/test_march.cpp):
// it reads the field where DistanceField::bind puts it, the coarse level one unit above.
#define GIS_SDF_BINDINGS(X) \
    /* jfa_seed.comp */ \
    X(TF_SEED_OCCUPANCY, 0) \
    X(IF_SEED_SEEDS, 0) \
    /* jfa_step.comp */ \
    X(IF_STEP_SOURCE, 0) \
    X(IF_STEP_TARGET, 1) \
    /* sdf_resolve.comp */ \
    X(TF_RESOLVE_NORMALS, 1) \
    X(IF_RESOLVE_SEEDS, 0) \
    X(IF_RESOLVE_DISTANCE, 1) \
    /* sdf_coarse.comp */ \
    X(TF_COARSE_DISTANCE, 0) \
    X(IF_COARSE_TARGET, 0) \
    /* sdf_march_probe.comp */ \
    X(TF_MARCH_PROBE_DISTANCE, 0) \
    X(TF_MARCH_PROBE_COARSE, 1) \
    X(SF_MARCH_PROBE_RAYS, 0) \
    X(SF_MARCH_PROBE_HITS, 1)

enum SdfBinding : int { GIS_SDF_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kSdfBindings[] = {GIS_SDF_BINDINGS(GIS_BINDING_SLOT)};
static_assert(TF_MARCH_PROBE_COARSE == TF_MARCH_PROBE_DISTANCE + 1, "DistanceField::bind: the coarse level one unit above");

// How sphere tracing marches the field (shaders/volume/sdf_march.glsl's SdfMarchParams).
#define GIS_SDF_MARCH_BLOCK(M, A) \
    M(float, hitThreshold)  /* cells */ \
    M(float, relaxation)    /* over-relaxed step factor */ \
    M(int, maxSteps) \
    M(float, offset)        /* the rays' start along the normal, cells */
GIS_UNIFORM_BLOCK(SdfMarchBlock, 4, GIS_SDF_MARCH_BLOCK)
}  // namespace gis::sdf
