// The volume a probe field walks (renderer/probes/probe_field.h, Tracer): the distance field's
// cascades (volume/sdf_march.glsl), or with PROBE_TRACER_OCCUPANCY the occupancy hierarchy
// (volume/hdda.glsl). Its inputs, as ProbeField::bindTracer and setFieldUniforms bind them, are
// declared here once for every program that traces: classify, trace and the screen gather.
#ifdef PROBE_TRACER_OCCUPANCY
#include "volume/hdda.glsl"
#else
#include "volume/sdf_march.glsl"
layout(binding = TP_FIELD_DISTANCE) uniform sampler3D s_distance;
layout(binding = TP_FIELD_COARSE) uniform sampler3D s_coarse;
#endif

layout(location = UP_CASCADES) uniform vec4 u_cascades[SDF_MAX_CASCADES];
layout(location = UP_CASCADE_COUNT) uniform int u_cascadeCount;
layout(location = UP_SDF_RESOLUTION) uniform int u_sdfResolution;

// The gathers' visibility (probe_common.glsl, PROBE_SEGMENT_TEST): the straight path to the probe
// from a cell and a half off the surface along `away`, past the surface's own voxels and level set, stopping
// half a cell short of the probe (a relocated probe sits near a surface). Where another surface
// meets this one (a corner, a box on the floor) that start lies in it, and every path would stop at
// once: the start is moved out first, along the field's gradient, or for the occupancy along V,
// the direction the point is seen from (free space: the camera's, or the probe ray's).
bool probeSeesPoint(vec3 probe, vec3 P, vec3 away, vec3 V) {
#ifdef PROBE_TRACER_OCCUPANCY
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    int c = hddaCascadeAt(cs, P);
    float cell = cs.volumes[c].w / float(cs.resolution);
    vec3 from = hddaFreeAlong(cs, P + away * (1.5 * cell), V, cell);
    float len = length(probe - from);
    if (len <= 0.5 * cell) return true;
    return !hddaTraceCascades(cs, from, (probe - from) / len, 0.0, len - 0.5 * cell, 256).hit;
#else
    SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    return sdfSurfaceSeesPoint(s_distance, s_coarse, cs, P, away, probe, 1.5);
#endif
}
