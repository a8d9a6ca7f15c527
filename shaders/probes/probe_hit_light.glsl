// What a ray of a probe field sees (renderer/probes/probe_field.h, ProbeField::bindForHitLight):
// walked through the field's tracer (probe_tracer.glsl), a hit is shaded from the voxel radiance of
// the cascade it was found in (direct light and emission as the volume injected them) plus, for
// multi-bounce, the probes' own irradiance there times the voxel albedo; a miss sees the sky. The
// probes' own rays (probe_trace.comp) and the screen reflection's (screen_reflection.comp) both
// shade this way, so a mirror shows what the probes saw.
#ifndef PROBE_HIT_LIGHT_GLSL
#define PROBE_HIT_LIGHT_GLSL
#include "probes/probe_tracer.glsl"
#include "environment.glsl"
#include "volume/voxel_faces.glsl"
#ifndef PROBE_TRACER_OCCUPANCY
#include "volume/sdf_hit_light.glsl"
#endif

layout(binding = TP_VOXEL_RADIANCE) uniform sampler3D s_voxelRadiance;  // premultiplied by occupancy (a); a layer per cascade
layout(binding = TP_VOXEL_ALBEDO) uniform sampler3D s_voxelAlbedo;  // albedo (a = occupancy); a layer per cascade
layout(binding = TP_VOXEL_SIDES) uniform sampler3D s_voxelSides;  // slab voxels' sides, a layer per cascade like the radiance

ProbeUpdateBlock u_update;

// The voxels store occupancy-weighted values; trilinear lookups then blend in empty voxels, which
// dividing by the blended occupancy undoes (the surface's own value, not half of it).
vec3 unpremultiply(vec4 v) { return v.a > 1e-4 ? v.rgb / v.a : vec3(0.0); }

// The multi-bounce term: the probes' own irradiance at the hit times its albedo, on the side the
// ray `dir` came from (a field's gradient at a wall thinner than a cell may point out of the room,
// and the gather's path test would then start behind the wall). With `momentsWhereNoPath`, a hit
// whose every surrounding probe the path test rejects takes them under the distance moments alone
// (DDGI's visibility) instead of no bounce: in a coarse cascade whose probe step is taller than the
// room, the probes above the ceiling and below the floor may be all there is, and with none of them
// the hall of builtin:building kept a quarter of Cycles' later bounces (renderer/gi/hddagi/README.md,
// bounce by bounce). The probes' own rays ask for it; the screen's rays do not: a few per pixel, each
// taking what the moments let through from probes outside, made HDDAGI's realtime hall too bright
// and noisy (its page).
vec3 bounceLight(vec3 P, vec3 N, vec3 dir, vec3 albedo, bool momentsWhereNoPath) {
    if (u_update.multiBounce == 0) return vec3(0.0);
    N = faceforward(N, dir, N);
    float bias = u_update.normalBias * gridMinStep(gridAt(P));
    vec4 e = sampleProbes(P + N * bias, N, -dir, u_update.visibility, PathStart(P, -dir));
    if (e.a == 0.0 && momentsWhereNoPath)
        e = sampleProbes(P + N * bias, N, -dir, min(u_update.visibility, 1), PathStart(P, -dir));
    return albedo * e.rgb;
}

#ifdef PROBE_TRACER_OCCUPANCY
// The light a ray from `origin` sees of voxel `v` of `cascade` whose level-0 light is `light`: a
// slab (a wall thinner than a voxel) shows the face on the ray's side, not its other face's sunlit mean.
vec3 lightSeen(vec4 light, int cascade, ivec3 v, vec3 origin) {
    v = clamp(v, ivec3(0), ivec3(u_sdfResolution - 1));
    vec4 sides = texelFetch(s_voxelSides, v + ivec3(0, 0, cascade * u_sdfResolution), 0);
    vec3 centre = u_cascades[cascade].xyz + voxelSlabCentre(v, sides) * (u_cascades[cascade].w / float(u_sdfResolution));
    return unpremultiply(voxelLightSeen(light, sides, origin - centre));
}

// Radiance along -dir at the first hit from origin (rgb) and its distance (a; a miss: the sky at
// u_update.missDistance, averaged over `missSteradians` around dir: a probe ray stands for 4 pi / n
// of the sphere, and a point-sampled sun far smaller than that is hit by almost no probe's rays and
// by one of them with all its light, so the probes' mean fell to 0.62 of Cycles' on the atrium lit
// by sky_sun.hdr alone with 32 rays; 0: the map's own texel, for a reflection ray). `probeRay`: the
// ray is a probe's (bounceLight's momentsWhereNoPath).
vec4 fieldRayRadiance(vec3 origin, vec3 dir, float missSteradians, bool probeRay) {
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    HddaHit h = hddaTraceCascades(cs, origin, dir, 0.0, u_update.missDistance, 4096);
    if (!h.hit) return vec4(environmentMissCone(dir, missSteradians), u_update.missDistance);
    // The hit voxel's own light and albedo (one voxel, no filtering: its neighbours may be empty).
    ivec3 texel = h.voxel + ivec3(0, 0, h.cascade * u_sdfResolution);
    vec3 radiance = lightSeen(texelFetch(s_voxelRadiance, texel, 0), h.cascade, h.voxel, origin);
    radiance += bounceLight(h.position, h.normal, dir, unpremultiply(texelFetch(s_voxelAlbedo, texel, 0)), probeRay);
    return vec4(finiteOrZero(radiance), max(h.t, 0.0));
}
#else
vec4 fieldRayRadiance(vec3 origin, vec3 dir, float missSteradians, bool probeRay) {
    SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    SdfMarchParams params = sdfDefaultParams(u_update.missDistance);
    params.maxSteps = 128;
    params.hitThreshold = u_update.hitThreshold;
    SdfHit h = sdfMarchCascades(s_distance, s_coarse, cs, origin, dir, params);
    if (!h.hit) return vec4(environmentMissCone(dir, missSteradians), u_update.missDistance);
    SdfVolume vol = sdfCascadeVolume(cs, h.cascade);
    vec3 radiance = sdfHitLight(s_voxelRadiance, s_voxelSides, cs, h, dir);
    vec3 albedoCoord = sdfLayerCoord(vol, h.cascade, sdfLayers(s_voxelAlbedo, vol), h.position);
    radiance += bounceLight(h.position, h.normal, dir, unpremultiply(textureLod(s_voxelAlbedo, albedoCoord, 0.0)), probeRay);
    return vec4(finiteOrZero(radiance), max(h.t, 0.0));
}
#endif
#endif
