// Explicit uniform locations and the slice block of HDDAGI's own shaders (its debug views;
// gl/uniform_table.h, gl/uniform_block.h: emitted into every shader, and the shader-constants test
// checks no two tables overlap and that GL lays the block out as C++ does).
#pragma once

#include "gl/uniform_block.h"
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
    X(UH_STEPS_MAX, 550, 1) /* steps shown white in hddagi.steps */

enum HddagiUniform : int { GIS_HDDAGI_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kHddagiUniforms[] = {GIS_HDDAGI_UNIFORMS(GIS_UNIFORM_SLOT)};

// Binding points of HDDAGI's own programs: its debug views' output image (the scene volume and the
// probes bind themselves at their own slots).
#define GIS_HDDAGI_BINDINGS(X) \
    X(IH_DEBUG_TARGET, 0)

enum HddagiBinding : int { GIS_HDDAGI_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kHddagiBindings[] = {GIS_HDDAGI_BINDINGS(GIS_BINDING_SLOT)};

// The occupancy slice hddagi.occupancy shows.
#define GIS_HDDAGI_SLICE_BLOCK(M, A) \
    M(int, axis) \
    M(float, position)   /* 0..1 along the axis */ \
    M(int, cascade) \
    M(int, level)        /* 0 voxels, 1 blocks, 2 regions */
GIS_UNIFORM_BLOCK(HddagiSliceBlock, 8, GIS_HDDAGI_SLICE_BLOCK)
}  // namespace gis::hddagi
