// Explicit uniform locations of HDDAGI's own shaders (its debug views; gl/uniform_table.h: emitted
// into every shader, and the shader-constants test checks no two tables overlap).
#pragma once

#include "gl/uniform_table.h"
#include "volume/volume_cascades.h"

namespace gis::hddagi {
#define GIS_HDDAGI_UNIFORMS(X) \
    X(UH_INV_VIEW_PROJ, 540, 1) \
    X(UH_CAMERA_POS, 541, 1) \
    X(UH_CASCADES, 542, kMaxCascades) /* origin xyz, edge; finest first */ \
    X(UH_CASCADE_COUNT, 546, 1) \
    X(UH_RESOLUTION, 547, 1) /* voxels per cascade edge */ \
    X(UH_VIEW, 548, 1) /* 0 occupancy slice, 1 steps */ \
    X(UH_SLICE, 549, 1) /* axis, position 0..1, cascade, level (0 voxels, 1 blocks, 2 regions) */ \
    X(UH_STEPS_MAX, 550, 1) /* steps shown white in hddagi.steps */

enum HddagiUniform : int { GIS_HDDAGI_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kHddagiUniforms[] = {GIS_HDDAGI_UNIFORMS(GIS_UNIFORM_SLOT)};
}  // namespace gis::hddagi
