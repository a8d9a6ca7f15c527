// Explicit uniform locations of probe GI (gl/uniform_table.h: emitted into every shader; the
// shader-constants test checks no two tables overlap).
#pragma once

#include "gl/uniform_table.h"

namespace gis::probes {
#define GIS_PROBE_UNIFORMS(X) \
    X(UP_GRID_FIRST, 500, 1) /* world position of probe (0, 0, 0) */ \
    X(UP_GRID_STEP, 501, 1) /* world step between neighbours per axis */ \
    X(UP_GRID_COUNTS, 502, 1) /* probes per axis */ \
    X(UP_STORAGE, 503, 1) /* 0 sh1, 1 sh2, 2 octahedral */ \
    X(UP_RAYS, 504, 1) /* rays per probe */ \
    X(UP_FIRST_PROBE, 505, 1) /* first probe of this update's batch (round robin) */ \
    X(UP_ROTATION, 506, 1) /* mat3: this update's random rotation of the ray set */ \
    X(UP_ENVIRONMENT, 507, 1) /* sky radiance for rays that miss */ \
    X(UP_VOLUME, 508, 1) /* distance field: origin xyz, edge */ \
    X(UP_SDF_RESOLUTION, 509, 1) \
    X(UP_BLEND_PARAMS, 510, 1) /* hysteresis, multi-bounce on, miss distance, visibility on */ \
    X(UP_INV_VIEW_PROJ, 511, 1) \
    X(UP_CAMERA_POS, 512, 1) \
    X(UP_SHADE_PARAMS, 513, 1) /* bias (x min probe step), intensity, visibility on, probe radius (debug) */ \
    X(UP_MODE, 514, 1) /* blend: 0 irradiance, 1 distance; classify: 0 relocate, 1 off; views: mode / probe */ \
    X(UP_VIEW_PROJ, 515, 1) \
    X(UP_SLOT_OFFSET, 516, 1) /* trace/blend: batch slot of work group 0 (a batch past the group limit is split) */

enum ProbeUniform : int { GIS_PROBE_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kProbeUniforms[] = {GIS_PROBE_UNIFORMS(GIS_UNIFORM_SLOT)};
}  // namespace gis::probes
