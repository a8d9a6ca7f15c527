// One probe update, step 1: every probe of the batch shoots u_rays rays (a spherical-Fibonacci set
// under this update's random rotation), sphere-traced through the distance field
// (sdf/sdf_march.glsl). A hit is shaded from the voxel radiance (direct light and emission as the
// voxelizer injected them) plus, for multi-bounce, the probes' own irradiance there times the
// voxel albedo; a miss sees the sky. One workgroup per probe; rays go to the ray buffer for the
// blend steps.
#include "gi/probes/probe_common.glsl"
#include "sdf/sdf_march.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 3) writeonly buffer Rays { vec4 rayResults[]; };  // radiance, hit distance
layout(binding = 0) uniform sampler3D s_distance;
layout(binding = 1) uniform sampler3D s_coarse;
layout(binding = 2) uniform sampler3D s_voxelRadiance;  // premultiplied by occupancy (a)
layout(binding = 3) uniform sampler3D s_voxelAlbedo;    // a = occupancy

layout(location = UP_RAYS) uniform int u_rays;
layout(location = UP_FIRST_PROBE) uniform int u_firstProbe;
layout(location = UP_SLOT_OFFSET) uniform int u_slotOffset;  // several dispatches past the work-group limit
layout(location = UP_ROTATION) uniform mat3 u_rotation;
layout(location = UP_ENVIRONMENT) uniform vec3 u_environment;
layout(location = UP_VOLUME) uniform vec4 u_volume;
layout(location = UP_SDF_RESOLUTION) uniform int u_sdfResolution;
layout(location = UP_BLEND_PARAMS) uniform vec4 u_blendParams;  // hysteresis, multi-bounce, miss distance, visibility
layout(location = UP_SHADE_PARAMS) uniform vec4 u_shadeParams;  // bias (x min step), ...

// The voxels store occupancy-weighted values; trilinear lookups then blend in empty voxels, which
// dividing by the blended occupancy undoes (the surface's own value, not half of it).
vec3 voxelValue(sampler3D s, vec3 uvw) {
    vec4 v = textureLod(s, uvw, 0.0);
    return v.a > 1e-4 ? v.rgb / v.a : vec3(0.0);
}

vec3 shadeHit(SdfHit h, SdfVolume vol) {
    vec3 uvw = (h.position - vol.origin) / vol.size;
    vec3 radiance = voxelValue(s_voxelRadiance, uvw);
    if (u_blendParams.y > 0.5) {
        vec3 albedo = voxelValue(s_voxelAlbedo, uvw);
        float bias = u_shadeParams.x * min(u_gridStep.x, min(u_gridStep.y, u_gridStep.z));
        radiance += albedo * sampleProbes(h.position + h.normal * bias, h.normal, u_blendParams.w > 0.5);
    }
    return finiteOrZero(radiance);
}

void main() {
    int slot = u_slotOffset + int(gl_WorkGroupID.x);
    int probe = (u_firstProbe + slot) % probeCount();
    bool off = probeOff(probe);
    vec3 origin = probePosition(probe);
    SdfVolume vol = SdfVolume(u_volume.xyz, u_volume.w, u_sdfResolution);
    SdfMarchParams params = sdfDefaultParams(u_blendParams.z);
    params.maxSteps = 128;
    for (int r = int(gl_LocalInvocationID.x); r < u_rays; r += int(gl_WorkGroupSize.x)) {
        vec4 result = vec4(0.0, 0.0, 0.0, u_blendParams.z);
        if (!off) {
            vec3 dir = normalize(u_rotation * fibonacciDirection(r, u_rays));
            SdfHit h = sdfMarch(s_distance, s_coarse, vol, origin, dir, params);
            result = h.hit ? vec4(shadeHit(h, vol), max(h.t, 0.0)) : vec4(u_environment, u_blendParams.z);
        }
        rayResults[slot * u_rays + r] = result;
    }
}
