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

// restir.comp's units: the G-buffer's textures (unit 0 is the ray scene's texture array) and the
// reservoirs read (IN) and written (OUT) by a stage, and the still view's running mean.
#define GIS_EMITTER_BINDINGS(X) \
    X(TE_DEPTH, 1) \
    X(TE_BASE_COLOR, 2) \
    X(TE_NORMAL, 3) \
    X(TE_MATERIAL, 4) \
    X(IE_SAMPLE_IN, 0) \
    X(IE_SURFACE_IN, 1) \
    X(IE_NORMAL_IN, 2) \
    X(IE_SAMPLE_OUT, 3) \
    X(IE_SURFACE_OUT, 4) \
    X(IE_NORMAL_OUT, 5) \
    X(IE_ACCUMULATION, 6) \
    X(IE_ENVIRONMENT_ACCUMULATION, 7) /* the environment's part of it (emitters.environment) */

enum EmitterBinding : int { GIS_EMITTER_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kEmitterBindings[] = {GIS_EMITTER_BINDINGS(GIS_BINDING_SLOT)};

// How both ReSTIR stages reuse reservoirs (the emitters.* parameters of this frame).
#define GIS_RESTIR_BLOCK(M, A) \
    M(int, candidates)          /* M: candidates drawn per pixel by power */ \
    M(int, bsdfCandidates)      /* candidates drawn per pixel along BSDF directions */ \
    M(int, environmentCandidates) /* drawn per pixel from the environment; 0: it is not a light here */ \
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
