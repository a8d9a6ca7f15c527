// One probe update, step 1: every probe of the batch (u_batch, most urgent first) shoots u_rays
// rays (a spherical-Fibonacci set under this update's random rotation), sphere-traced through the
// distance field's cascades (volume/sdf_march.glsl), or with PROBE_TRACER_OCCUPANCY walked through
// the occupancy hierarchy by HDDA (volume/hdda.glsl), starting in the finest cascade that holds the
// probe. A hit is shaded from the voxel radiance of the cascade it was found in (direct light and
// emission as the volume injected them) plus, for multi-bounce, the probes' own irradiance there
// times the voxel albedo; a miss sees the sky. One workgroup per probe; rays go to the ray buffer for the
// blend steps, and their count to the change buffer (what a ray budget is checked against).
#define PROBE_SEGMENT_TEST 1
#include "probes/probe_common.glsl"
#include "probes/probe_tracer.glsl"
#include "environment.glsl"
#include "volume/voxel_faces.glsl"
#ifndef PROBE_TRACER_OCCUPANCY
#include "volume/sdf_hit_light.glsl"
#endif

layout(local_size_x = 64) in;
layout(std430, binding = 3) writeonly buffer Rays { vec4 rayResults[]; };
layout(std430, binding = 4) buffer Change { uint u_change; uint u_rayCount; };
layout(std430, binding = 5) readonly buffer Batch { int u_batch[]; };
layout(binding = 2) uniform sampler3D s_voxelRadiance;  // premultiplied by occupancy (a); a layer per cascade
// Albedo (a = occupancy) of each cascade, its own texture each.
layout(binding = 3) uniform sampler3D s_voxelAlbedo0;
layout(binding = 4) uniform sampler3D s_voxelAlbedo1;
layout(binding = 5) uniform sampler3D s_voxelAlbedo2;
layout(binding = 6) uniform sampler3D s_voxelAlbedo3;
layout(binding = 7) uniform sampler3D s_voxelSides;  // slab voxels' sides, a layer per cascade like the radiance

layout(location = UP_RAYS) uniform int u_rays;
layout(location = UP_SLOT_OFFSET) uniform int u_slotOffset;  // several dispatches past the work-group limit
layout(location = UP_ROTATION) uniform mat3 u_rotation;
ProbeUpdateBlock u_update;

shared uint s_traced;

// The voxels store occupancy-weighted values; trilinear lookups then blend in empty voxels, which
// dividing by the blended occupancy undoes (the surface's own value, not half of it).
vec3 unpremultiply(vec4 v) { return v.a > 1e-4 ? v.rgb / v.a : vec3(0.0); }

vec3 voxelAlbedo(int cascade, vec3 uvw) {
    switch (cascade) {
    case 0: return unpremultiply(textureLod(s_voxelAlbedo0, uvw, 0.0));
    case 1: return unpremultiply(textureLod(s_voxelAlbedo1, uvw, 0.0));
    case 2: return unpremultiply(textureLod(s_voxelAlbedo2, uvw, 0.0));
    default: return unpremultiply(textureLod(s_voxelAlbedo3, uvw, 0.0));
    }
}

// The multi-bounce term: the probes' own irradiance at the hit times its albedo, on the side the
// ray `dir` came from (a field's gradient at a wall thinner than a cell may point out of the room,
// and the gather's path test would then start behind the wall).
vec3 bounceLight(vec3 P, vec3 N, vec3 dir, vec3 albedo) {
    if (u_update.multiBounce == 0) return vec3(0.0);
    N = faceforward(N, dir, N);
    float bias = u_update.normalBias * gridMinStep(gridAt(P));
    return albedo * sampleProbes(P + N * bias, N, -dir, u_update.visibility);
}

#ifdef PROBE_TRACER_OCCUPANCY
// The light a ray along `dir` sees of voxel `v` of `cascade` whose level-0 light is `light`: a slab
// (a wall thinner than a voxel) shows the face the ray meets, not its other face's sunlit mean.
vec3 lightSeen(vec4 light, int cascade, ivec3 v, vec3 dir) {
    v = clamp(v, ivec3(0), ivec3(u_sdfResolution - 1));
    return unpremultiply(voxelLightSeen(light, texelFetch(s_voxelSides, v + ivec3(0, 0, cascade * u_sdfResolution), 0), dir));
}

// The hit voxel's own light and albedo (one voxel, no filtering: its neighbours may be empty).
vec3 voxelAlbedoAt(int cascade, ivec3 v) {
    switch (cascade) {
    case 0: return unpremultiply(texelFetch(s_voxelAlbedo0, v, 0));
    case 1: return unpremultiply(texelFetch(s_voxelAlbedo1, v, 0));
    case 2: return unpremultiply(texelFetch(s_voxelAlbedo2, v, 0));
    default: return unpremultiply(texelFetch(s_voxelAlbedo3, v, 0));
    }
}

vec4 traceRay(vec3 origin, vec3 dir) {
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    HddaHit h = hddaTraceCascades(cs, origin, dir, 0.0, u_update.missDistance, 4096);
    if (!h.hit) return vec4(environmentRadiance(dir), u_update.missDistance);
    vec3 radiance = lightSeen(texelFetch(s_voxelRadiance, h.voxel + ivec3(0, 0, h.cascade * u_sdfResolution), 0),
                              h.cascade, h.voxel, dir);
    radiance += bounceLight(h.position, h.normal, dir, voxelAlbedoAt(h.cascade, h.voxel));
    return vec4(finiteOrZero(radiance), max(h.t, 0.0));
}
#else
vec4 traceRay(vec3 origin, vec3 dir) {
    SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    SdfMarchParams params = sdfDefaultParams(u_update.missDistance);
    params.maxSteps = 128;
    SdfHit h = sdfMarchCascades(s_distance, s_coarse, cs, origin, dir, params);
    if (!h.hit) return vec4(environmentRadiance(dir), u_update.missDistance);
    SdfVolume vol = sdfCascadeVolume(cs, h.cascade);
    vec3 radiance = sdfHitLight(s_voxelRadiance, s_voxelSides, cs, h, dir);
    radiance += bounceLight(h.position, h.normal, dir, voxelAlbedo(h.cascade, (h.position - vol.origin) / vol.size));
    return vec4(finiteOrZero(radiance), max(h.t, 0.0));
}
#endif

void main() {
    int slot = u_slotOffset + int(gl_WorkGroupID.x);
    int probe = u_batch[slot];
    bool off = probeOff(probe);
    vec3 origin = probePosition(probe);
    if (gl_LocalInvocationID.x == 0u) s_traced = 0u;
    barrier();
    uint traced = 0u;
    for (int r = int(gl_LocalInvocationID.x); r < u_rays; r += int(gl_WorkGroupSize.x)) {
        vec4 result = vec4(0.0, 0.0, 0.0, u_update.missDistance);
        if (!off) {
            result = traceRay(origin, normalize(u_rotation * fibonacciDirection(r, u_rays)));
            ++traced;
        }
        rayResults[slot * u_rays + r] = result;
    }
    atomicAdd(s_traced, traced);
    barrier();
    if (gl_LocalInvocationID.x == 0u) atomicAdd(u_rayCount, s_traced);
}
