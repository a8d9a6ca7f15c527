// Binding points of VCT's own programs (gl/uniform_table.h: emitted into every shader through the
// method's registry entry), each block one program's: texture units (TC_) and image units (IC_).
// The scene volume binds itself above them (volume/volume_slots.h); the trace reads the ray scene's
// textures, for its sky rays, one unit above the G-buffer's.
#pragma once

#include "gl/uniform_table.h"

namespace gis::vct {
#define GIS_VCT_BINDINGS(X) \
    /* vct_trace.comp */ \
    X(TC_TRACE_DEPTH, 0) \
    X(TC_TRACE_NORMAL, 1) \
    X(TC_TRACE_MATERIAL, 2) \
    X(TC_TRACE_RAY_SCENE, 3) \
    X(IC_TRACE_DIFFUSE, 0) \
    X(IC_TRACE_SPECULAR, 1) \
    X(IC_TRACE_AO, 2) \
    /* vct_sky_filter.comp */ \
    X(TC_SKY_FILTER_DEPTH, 0) \
    X(TC_SKY_FILTER_NORMAL, 1) \
    X(TC_SKY_FILTER_DIFFUSE, 2) \
    X(IC_SKY_FILTER_OUTPUT, 0) \
    /* vct_upsample.comp */ \
    X(TC_UPSAMPLE_DEPTH, 0) \
    X(TC_UPSAMPLE_NORMAL, 1) \
    X(TC_UPSAMPLE_TRACED_DIFFUSE, 2) \
    X(TC_UPSAMPLE_TRACED_SPECULAR, 3) \
    X(TC_UPSAMPLE_HISTORY_DIFFUSE, 4) \
    X(TC_UPSAMPLE_HISTORY_SPECULAR, 5) \
    X(TC_UPSAMPLE_HISTORY_GEOMETRY, 6) \
    X(IC_UPSAMPLE_DIFFUSE, 0) \
    X(IC_UPSAMPLE_SPECULAR, 1) \
    X(IC_UPSAMPLE_GEOMETRY, 2) \
    /* vct_debug.comp */ \
    X(IC_DEBUG_VIEW, 0)

enum VctBinding : int { GIS_VCT_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kVctBindings[] = {GIS_VCT_BINDINGS(GIS_BINDING_SLOT)};
}  // namespace gis::vct
