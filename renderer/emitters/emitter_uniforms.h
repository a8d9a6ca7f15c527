// Explicit uniform locations and the reuse block of the emitter-light module (gl/uniform_table.h,
// gl/uniform_block.h: emitted into every shader; the shader-constants test checks no two tables
// overlap and that GL lays the block out as C++ does).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"

namespace gis::emitters {
#define GIS_EMITTER_UNIFORMS(X) \
    X(UE_VIEW_PROJ, 200, 1) \
    X(UE_PREV_VIEW_PROJ, 201, 1) \
    X(UE_INV_VIEW_PROJ, 202, 1) \
    X(UE_CAMERA_POS, 203, 1) \
    X(UE_EMITTER_COUNT, 204, 1) \
    X(UE_BRDF_MODELS, 205, 1) \
    X(UE_FRAME, 206, 1) /* frames rendered (random stream), seed */

enum EmitterUniform : int { GIS_EMITTER_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kEmitterUniforms[] = {GIS_EMITTER_UNIFORMS(GIS_UNIFORM_SLOT)};

// How both ReSTIR stages reuse reservoirs (the emitters.* parameters of this frame).
#define GIS_RESTIR_BLOCK(M, A) \
    M(int, candidates)          /* M: candidates drawn per pixel by power */ \
    M(int, bsdfCandidates)      /* candidates drawn per pixel along BSDF directions */ \
    M(int, temporal)            /* 1: reuse the reprojected history */ \
    M(int, spatial)             /* k: neighbours combined */ \
    M(int, unbiased)            /* 1: the 1/Z weights, a visibility ray per reused reservoir */ \
    M(int, historyValid)        /* 0: the first frame, or a change the history cannot survive */ \
    M(float, maxM)              /* the history's M cap */ \
    M(float, radius)            /* of the spatial neighbours' disc, pixels */ \
    M(float, framesAveraged)    /* still frames already in the running mean */ \
    M(vec4, prevCameraPos) /* xyz: the camera of the history's frame (its surfaces' view vectors) */
GIS_UNIFORM_BLOCK(RestirBlock, 1, GIS_RESTIR_BLOCK)
}  // namespace gis::emitters
