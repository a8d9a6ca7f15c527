// Explicit uniform locations of the emitter-light module (gl/uniform_table.h: emitted into every
// shader; the shader-constants test checks no two tables overlap).
#pragma once

#include "gl/uniform_table.h"

namespace gis::emitters {
#define GIS_EMITTER_UNIFORMS(X) \
    X(UE_VIEW_PROJ, 200, 1) \
    X(UE_PREV_VIEW_PROJ, 201, 1) \
    X(UE_INV_VIEW_PROJ, 202, 1) \
    X(UE_CAMERA_POS, 203, 1) \
    X(UE_EMITTER_COUNT, 204, 1) \
    X(UE_BRDF_MODELS, 205, 1) \
    X(UE_FRAME, 206, 1) /* frames rendered (random stream), seed */ \
    X(UE_REUSE, 207, 1) /* candidates, temporal (0/1), spatial neighbours, unbiased (0/1) */ \
    X(UE_HISTORY, 208, 1) /* history valid (0/1), M cap, radius (pixels), accumulated frames */

enum EmitterUniform : int { GIS_EMITTER_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kEmitterUniforms[] = {GIS_EMITTER_UNIFORMS(GIS_UNIFORM_SLOT)};
}  // namespace gis::emitters
