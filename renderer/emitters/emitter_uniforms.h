// Explicit uniform locations of the emitter-light module: shaders/emitters/emitter_uniforms.glsl
// mirrors it. A range of its own (200..219) so they never collide with renderer/uniforms.h.
#pragma once

namespace gis::emitters {
enum EmitterUniform : int {
    UE_VIEW_PROJ = 200,
    UE_PREV_VIEW_PROJ = 201,
    UE_INV_VIEW_PROJ = 202,
    UE_CAMERA_POS = 203,
    UE_EMITTER_COUNT = 204,
    UE_BRDF_MODELS = 205,
    UE_FRAME = 206,           // frames rendered (random stream), seed
    UE_REUSE = 207,           // candidates, temporal (0/1), spatial neighbours, unbiased (0/1)
    UE_HISTORY = 208,         // history valid (0/1), M cap, radius (pixels), accumulated frames
};
}  // namespace gis::emitters
