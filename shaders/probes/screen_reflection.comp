// The screen reflection of a probe field (renderer/probes/screen_reflection.h): the lighting
// contract's indirect.specular, the radiance the specular lobe gathers, per full-resolution pixel.
// Below the roughness cut-off, rays drawn from the GGX lobe's visible normals (Heitz 2018) are walked
// through the field's tracer and shaded as the probes' own rays are (probe_hit_light.glsl: the
// voxels' light, the probes' irradiance for the next bounce, the sky for a miss), averaged over
// the frames of a still view; over the last quarter below the cut-off the estimate blends into the
// diffuse gather, the cosine lobe's mean radiance, which stands in for a wide lobe. Where the
// gather found no probe that sees the point, cosine rays light it the same way (averaged alike),
// into indirect.diffuse.
// With REFLECTION_ENVIRONMENT (a program of its own: llvmpipe runs both sides of a uniform branch)
// the prefiltered environment instead, what the lighting pass shows without the term.
#include "common.glsl"
#include "gbuffer_layout.glsl"
#include "environment.glsl"
// (The includes are expanded once each, whatever #ifdef they stand in: a file both variants need
// is included above.)
#ifndef REFLECTION_ENVIRONMENT
#include "random.glsl"
#include "sampling.glsl"
#include "brdf.glsl"
#include "bsdf_sampling.glsl"
#define PROBE_SEGMENT_TEST 1
#include "probes/probe_common.glsl"
#include "probes/probe_hit_light.glsl"
#endif

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TP_REFLECT_DEPTH) uniform sampler2D s_depth;
layout(binding = TP_REFLECT_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TP_REFLECT_MATERIAL) uniform sampler2D s_gbufMaterial;  // metallic, roughness, occlusion, specular
// The screen gather's indirect.diffuse, alpha the share probes gave it (screen_gather.glsl): where
// that is short of 1, the unseen part is lit here by the pixel's own rays and written back.
layout(binding = IP_REFLECT_DIFFUSE, rgba16f) uniform image2D i_diffuse;
layout(binding = IP_UNSEEN_MEAN, rgba16f) uniform image2D i_unseenMean;  // those rays' running mean
layout(binding = IP_REFLECT_MEAN, rgba16f) uniform image2D i_mean;       // the traced radiance's running mean
layout(binding = IP_REFLECT_SPECULAR, rgba16f) uniform writeonly image2D i_specular;
layout(location = UP_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UP_CAMERA_POS) uniform vec3 u_cameraPos;
ProbeReflectBlock u_reflect;

#ifndef REFLECTION_ENVIRONMENT
// Where the rays leave, as the gathers' path test starts (probe_tracer.glsl): a cell and a half of
// the finest cascade holding P off along N, then clear of any surface there (a second surface
// meeting this one, a normal map's normal tilted into the solid): along the field's gradient, or
// through the occupancy towards the eye.
vec3 rayStart(vec3 P, vec3 N, vec3 V) {
#ifdef PROBE_TRACER_OCCUPANCY
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    float cell = cs.volumes[hddaCascadeAt(cs, P)].w / float(cs.resolution);
    return hddaFreeAlong(cs, P + N * (1.5 * cell), V, cell);
#else
    SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    float cell = sdfCellSize(sdfCascadeVolume(cs, sdfCascadeAt(cs, P)));
    return sdfPushOut(s_distance, cs, P + N * (1.5 * cell), cell);
#endif
}

// This frame's estimate of the lobe's mean radiance: one ray along the mirror direction for a
// mirror, else u_reflect.rays directions reflected about GGX visible normals (those that would
// leave below the surface are dropped).
vec3 tracedRadiance(vec3 P, vec3 N, vec3 V, float roughness, ivec2 pixel) {
    vec3 origin = rayStart(P, N, V);
    float alpha = roughness * roughness;
    if (alpha < 1e-4) return fieldRayRadiance(origin, reflect(-V, N), 0.0, false).rgb;
    vec3 t, b;
    orthonormalBasis(N, t, b);
    vec3 vLocal = vec3(dot(V, t), dot(V, b), max(dot(V, N), 1e-4));
    Rng rng = makeRng(uvec2(pixel), uint(u_reflect.frame), 0x7e1fu);
    vec3 sum = vec3(0.0);
    float kept = 0.0;
    for (int i = 0; i < u_reflect.rays; ++i) {
        vec3 h = sampleGgxVisibleNormal(vLocal, alpha, nextFloat2(rng));
        vec3 L = reflect(-V, normalize(h.x * t + h.y * b + h.z * N));
        if (dot(L, N) <= 0.0) continue;
        sum += fieldRayRadiance(origin, L, 0.0, false).rgb;
        kept += 1.0;
    }
    return kept > 0.0 ? sum / kept : fieldRayRadiance(origin, reflect(-V, N), 0.0, false).rgb;
}

// A point no probe sees (the far end of a corridor in a coarse cascade, where every probe of the
// grid is behind a wall): this frame's estimate of E / pi from u_reflect.rays cosine-distributed
// rays, shaded as the probes' rays are (a miss: the sky's own texel).
vec3 unseenIrradiance(vec3 P, vec3 N, vec3 V, ivec2 pixel) {
    vec3 origin = rayStart(P, N, V);
    Rng rng = makeRng(uvec2(pixel), uint(u_reflect.frame), 0x0d1fu);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_reflect.rays; ++i)
        sum += fieldRayRadiance(origin, cosineDirection(N, nextFloat2(rng)), 0.0, false).rgb;
    return sum / float(max(u_reflect.rays, 1));
}

// mean += (x - mean) / n over the still frames (the first frame of a view replaces it). Not
// guarded: the estimate is finite, and a NaN here is a bug the finiteness checks must see.
vec3 runningMean(vec4 stored, vec3 estimate) {
    vec3 mean = u_reflect.framesAveraged > 0.0 ? stored.rgb : vec3(0.0);
    return mean + (estimate - mean) / (u_reflect.framesAveraged + 1.0);
}
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(i_specular)))) return;
    vec3 P;
    if (!gbufferPosition(s_depth, u_invViewProj, pixel, P)) {
        imageStore(i_specular, pixel, vec4(0.0));
        return;
    }
    vec3 V = normalize(u_cameraPos - P);
    vec3 N = normalize(texelFetch(s_gbufNormal, pixel, 0).xyz);
    N = faceforward(N, -V, N);  // a normal seen from behind (a grazing normal map) reflects as its front
    float roughness = texelFetch(s_gbufMaterial, pixel, 0).y;
#ifdef REFLECTION_ENVIRONMENT
    // Under an environment that is a light of the direct pass, ReSTIR reflects it (with its shadows).
    vec3 reflected = environmentIsDirectLight() ? vec3(0.0) : environmentSpecular(reflect(-V, N), roughness);
    imageStore(i_specular, pixel, vec4(reflected, 1.0));
#else
    vec4 gathered = imageLoad(i_diffuse, pixel);
    vec3 diffuse = gathered.rgb;
    if (u_reflect.unseenIntensity > 0.0 && gathered.a < 1.0) {
        vec3 unseen = runningMean(imageLoad(i_unseenMean, pixel), unseenIrradiance(P, N, V, pixel));
        imageStore(i_unseenMean, pixel, vec4(unseen, 1.0));
        diffuse += (1.0 - gathered.a) * u_reflect.unseenIntensity * unseen;
        imageStore(i_diffuse, pixel, vec4(diffuse, 1.0));
    }
    if (!(roughness < u_reflect.roughness)) {
        imageStore(i_specular, pixel, vec4(diffuse, 1.0));
        return;
    }
    vec3 mean = runningMean(imageLoad(i_mean, pixel), tracedRadiance(P, N, V, roughness, pixel));
    imageStore(i_mean, pixel, vec4(mean, 1.0));
    // The rays are right at any roughness; the blend only hides the cut-off, over its last quarter.
    float towardsDiffuse = smoothstep(0.75 * u_reflect.roughness, u_reflect.roughness, roughness);
    imageStore(i_specular, pixel, vec4(mix(mean, diffuse, towardsDiffuse), 1.0));
#endif
}
