// Texture units of the screen-space AO's programs (gl/uniform_table.h: emitted into every shader
// through the method's registry entry): the AO pass (gi/ssao/ssao_common.glsl, under ssao.frag and
// gtao.frag), its bilateral blur and its temporal accumulation.
#pragma once

#include "gl/uniform_table.h"

namespace gis::ssao {
#define GIS_SSAO_BINDINGS(X) \
    X(TA_DEPTH, 0) /* the pass binds a linear sampler here */ \
    X(TA_NORMAL, 1) \
    X(TA_NOISE, 2) \
    /* ssao_blur.frag */ \
    X(TA_BLUR_AO, 0) \
    X(TA_BLUR_NORMAL, 1) \
    /* ssao_temporal.frag */ \
    X(TA_TEMPORAL_AO, 0) \
    X(TA_TEMPORAL_HISTORY, 1) \
    X(TA_TEMPORAL_DEPTH, 2)

enum SsaoBinding : int { GIS_SSAO_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kSsaoBindings[] = {GIS_SSAO_BINDINGS(GIS_BINDING_SLOT)};
}  // namespace gis::ssao
