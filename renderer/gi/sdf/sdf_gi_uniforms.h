// Explicit uniform locations and the debug block of the SDF GI method's shaders
// (gl/uniform_table.h, gl/uniform_block.h: emitted into every shader; the shader-constants test
// checks no two tables overlap and that GL lays the block out as C++ does).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"
#include "volume/volume_cascades.h"

namespace gis::sdfgi {
#define GIS_SDF_GI_UNIFORMS(X) \
    X(UG_INV_VIEW_PROJ, 420, 1) \
    X(UG_CAMERA_POS, 421, 1) \
    X(UG_VOLUME, 422, 1) /* origin xyz, edge length */ \
    X(UG_RESOLUTION, 423, 1) /* cells per edge */ \
    X(UG_RAYS, 425, 1) /* diffuse rays per traced pixel */ \
    X(UG_FRAME, 426, 1) /* frames rendered before this one (decorrelates the rays) */ \
    X(UG_SCALE, 429, 1) /* full-resolution pixels per traced pixel (1 or 2) */ \
    X(UG_AO, 430, 1) /* soft-occlusion strength */ \
    X(UG_INTENSITY, 431, 1) \
    X(UG_PREV_VIEW_PROJ, 432, 1) \
    X(UG_FILTER, 434, 1) /* filter radius in traced pixels */ \
    X(UG_PREV_CAMERA_POS, 435, 1) \
    X(UG_CASCADES, 437, kMaxCascades) /* vec4 per cascade: origin xyz, edge; finest first */ \
    X(UG_CASCADE_COUNT, 441, 1) \
    X(UG_SLICE_CASCADE, 442, 1) /* the cascade (layer) sdf.slice shows */ \


enum SdfGiUniform : int { GIS_SDF_GI_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kSdfGiUniforms[] = {GIS_SDF_GI_UNIFORMS(GIS_UNIFORM_SLOT)};

// Binding points of SDF GI's own programs: the G-buffer every one reads (gi/sdf/sdf_gbuffer.glsl;
// the trace also the material), then each program's texture units (TG_) and image units (IG_).
// The scene volume and the probes bind themselves at their own slots.
#define GIS_SDF_GI_BINDINGS(X) \
    X(TG_DEPTH, 0) \
    X(TG_NORMAL, 1) \
    X(TG_MATERIAL, 2) \
    /* sdf_trace.comp */ \
    X(IG_TRACE_DIFFUSE, 0) \
    X(IG_TRACE_REFLECTION, 1) \
    X(IG_TRACE_AO, 2) \
    X(IG_TRACE_INFO, 3) \
    /* sdf_temporal.comp */ \
    X(TG_TEMPORAL_CURRENT, 2) \
    X(TG_TEMPORAL_HISTORY, 3) \
    X(TG_TEMPORAL_HISTORY_DISTANCE, 4) \
    X(IG_TEMPORAL_HISTORY, 0) \
    X(IG_TEMPORAL_HISTORY_DISTANCE, 1) \
    /* sdf_filter.comp */ \
    X(TG_FILTER_DIFFUSE, 2) \
    X(TG_FILTER_REFLECTION, 3) \
    X(TG_FILTER_OCCLUSION, 4) \
    X(IG_FILTER_DIFFUSE, 0) \
    X(IG_FILTER_SPECULAR, 1) \
    X(IG_FILTER_AO, 2) \
    /* sdf_debug.comp */ \
    X(TG_DEBUG_INFO, 6) \
    X(IG_DEBUG_TARGET, 0)

enum SdfGiBinding : int { GIS_SDF_GI_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kSdfGiBindings[] = {GIS_SDF_GI_BINDINGS(GIS_BINDING_SLOT)};

// What the debug views show (sdf.slice, sdf.steps, sdf.normals).
#define GIS_SDF_DEBUG_BLOCK(M, A) \
    M(int, view)            /* 0 slice, 1 steps, 2 normals */ \
    M(int, sliceAxis) \
    M(float, slicePosition) /* 0..1 along the axis */ \
    M(int, maxSteps)        /* the steps view's full scale */
GIS_UNIFORM_BLOCK(SdfDebugBlock, 5, GIS_SDF_DEBUG_BLOCK)

// What the trace does per traced pixel besides marching (sdf_trace.comp).
#define GIS_SDF_TRACE_BLOCK(M, A) \
    M(int, specular)            /* 1: a mirror ray for surfaces below the roughness cut-off */ \
    M(float, specularRoughness) /* that cut-off */ \
    M(int, probeGather)         /* 1: diffuse from SDFGI's probes, not rays */ \
    M(int, probeVisibility)     /* the gather's: probes/probe_field.h, visibilityMode */ \
    M(float, gatherBias)        /* the probe lookup's offset, x the smallest probe step */
GIS_UNIFORM_BLOCK(SdfTraceBlock, 12, GIS_SDF_TRACE_BLOCK)

// The rays' temporal accumulation (sdf_temporal.comp).
#define GIS_SDF_TEMPORAL_BLOCK(M, A) \
    M(float, maxWeight)   /* the history's largest weight: 1 / (1 - it) frames while the camera moves */ \
    M(int, hasHistory) \
    M(int, cameraMoved)
GIS_UNIFORM_BLOCK(SdfTemporalBlock, 13, GIS_SDF_TEMPORAL_BLOCK)
}  // namespace gis::sdfgi
