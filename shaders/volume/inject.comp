// Light injection: the radiance each voxel's surface sends out, assuming Lambertian reflection:
// albedo / pi * (sum over punctual lights of irradiance * shadow-map visibility) + emission.
// Stored premultiplied by occupancy (rgb = L * a, a = occupancy), ready for averaging into mips.
// A slab voxel (a wall thinner than a voxel, volume/voxel_faces.glsl) has its two faces lit apart:
// i_radiance holds their mean, i_sides half their difference, so that a cone or ray meeting the
// slab from one side sees that face's light alone (voxelLightSeen).
#include "common.glsl"
#include "lights.glsl"
#include "volume/voxel_faces.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TV_INJECT_ALBEDO) uniform sampler3D s_albedo;
layout(binding = TV_INJECT_NORMAL) uniform sampler3D s_normal;
layout(binding = TV_INJECT_EMISSION) uniform sampler3D s_emission;
layout(binding = TV_INJECT_SHADOW_MAPS) uniform sampler2DArrayShadow s_shadowMaps;
layout(binding = TV_INJECT_SHADOW_CUBES) uniform sampler2DArrayShadow s_shadowCubes;  // cube faces, 6 layers per cube
layout(rgba16f, binding = IV_INJECT_RADIANCE) uniform writeonly image3D i_radiance;
// Slab voxels: rgb = (L(+axis face) - L(-axis face)) / 2, a = the slab's mark (volume/voxel_faces.glsl); 0 elsewhere.
layout(rgba16f, binding = IV_INJECT_SIDES) uniform writeonly image3D i_sides;
// The share of i_radiance's mean the punctual lights gave (rgb; a = occupancy, as i_radiance), which
// the tracers' hits take out to light themselves (volume/hit_light.glsl).
layout(rgba16f, binding = IV_INJECT_PUNCTUAL) uniform writeonly image3D i_punctual;

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_VOXEL_TO_WORLD) uniform mat4 u_voxelToWorld;
layout(location = UV_VOXEL_SIZE) uniform float u_voxelSize;
layout(location = UV_LIGHT_COUNT) uniform int u_lightCount;
layout(location = UV_SHADOWS_ENABLED) uniform int u_shadowsEnabled;
// 0 when emissive triangles are lights of the direct pass (renderer/emitters/): then the volume
// holds reflected light only and emitters reach it through no method a second time.
layout(location = UV_EMISSION_WEIGHT) uniform float u_emissionWeight;

#include "shadows.glsl"

#ifndef TRACED_LIGHT
#define TRACED_LIGHT 0
#endif
#if TRACED_LIGHT
// The lights of the direct pass (renderer/emitters/) as lights of the volume, sampled through the
// ray scene with a visibility ray each: the surfaces they light then pass their light on, as they
// do under punctual lights, and no method's rays see them a second time.
//   - Emissive triangles (emitters.mode=lights): u_emitterSamples.y points per voxel drawn by power
//     from the ray scene's emitter table (as the direct pass's ReSTIR candidates).
//   - The environment (emitters.environment): u_environmentSamples directions per voxel (not on a
//     slab, below).
#define RAY_SCENE_TEXTURE_UNIT TV_INJECT_RAY_SCENE
#include "random.glsl"
#include "ray_scene.glsl"
#include "environment.glsl"
layout(location = UV_EMITTER_SAMPLES) uniform ivec2 u_emitterSamples;  // emitter count, samples per voxel
layout(location = UV_ENVIRONMENT_SAMPLES) uniform int u_environmentSamples;  // per voxel; 0: not a light

vec3 emitterIrradiance(ivec3 v, vec3 P, vec3 N, bool oriented) {
    Rng rng = makeRng(uvec2(v.x + u_resolution * v.z, v.y), 0u, 0x9e3779b9u);
    vec3 origin = P + N * (oriented ? u_voxelSize : 0.0);
    // Closer than half a voxel the centre is no estimate of the surface's distance to the emitter.
    float minD2 = 0.25 * u_voxelSize * u_voxelSize;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_emitterSamples.y; ++i) {
        uint ti = pickEmitter(nextFloat(rng), u_emitterSamples.x);
        TraceTriangle tri = u_triangles[ti];
        TriangleAttributes a = u_attributes[ti];
        RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
        vec2 u = nextFloat2(rng);
        float su = sqrt(u.x);
        vec2 b = vec2(su * (1.0 - u.y), su * u.y);
        vec3 q = tri.p0.xyz * (1.0 - b.x - b.y) + tri.p1.xyz * b.x + tri.p2.xyz * b.y;
        vec3 nl = cross(tri.p1.xyz - tri.p0.xyz, tri.p2.xyz - tri.p0.xyz);
        vec3 d = q - P;
        float d2 = dot(d, d);
        if (!(d2 > 0.0) || !(dot(nl, nl) > 0.0) || !(a.uv2MaterialEmitter.w > 0.0)) continue;
        vec3 L = d * inversesqrt(d2);
        float cosLight = dot(normalize(nl), -L);
        if (!(cosLight > 0.0 || m.emissive.w > 0.5)) continue;  // one-sided: its front only
        float cosine = oriented ? dot(N, L) : 0.5;
        if (cosine <= 0.0) continue;
        vec3 toQ = q - origin;
        float dist = length(toQ);
        Hit h;
        if (dist > 0.0 && traceRay(origin, toQ / dist, dist * (1.0 - 1e-3), true, h)) continue;
        vec3 le = m.emissive.rgb;
        if (m.textures.w >= 0) le *= srgbToLinear(sampleLayer(m.textures.w, triangleUv(a, b)).rgb);
        sum += le * (cosine * abs(cosLight) / (max(d2, minD2) * a.uv2MaterialEmitter.w));
    }
    return sum / float(max(u_emitterSamples.y, 1));
}

// The irradiance the environment gives a face just off `origin` with normal N (unoriented: lit from
// every side with the clamped cosine's mean over orientations, 1/4), each direction with a
// visibility ray. Directions come from a mixture of the map's luminance (a sun) and the cosine
// around N (the rest of the sky: a sun below the face's horizon leaves the luminance samples
// nothing to find), weighed by the mixture's density (one-sample MIS, balance heuristic; Veach
// 1997, 9.2.4); a constant uses the cosine alone.
vec3 environmentIrradiance(ivec3 v, vec3 origin, vec3 N, bool oriented) {
    Rng rng = makeRng(uvec2(v.x + u_resolution * v.z, v.y), 1u, 0x85ebca6bu);
    float mapShare = environmentIsMap() ? 0.5 : 0.0;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_environmentSamples; ++i) {
        vec2 u = nextFloat2(rng);
        vec3 L;
        float pdf;
        if (nextFloat(rng) < mapShare) {
            L = sampleEnvironment(u, pdf);
        } else if (oriented) {
            L = cosineDirection(N, u);
        } else {
            L = uniformSphereDirection(u);
        }
        float cosine = oriented ? dot(N, L) : 0.25;
        float otherPdf = oriented ? max(cosine, 0.0) * INV_PI : 0.25 * INV_PI;
        pdf = mapShare * (mapShare > 0.0 ? environmentPdf(L) : 0.0) + (1.0 - mapShare) * otherPdf;
        if (cosine <= 0.0 || !(pdf > 0.0)) continue;
        Hit h;
        if (traceRay(origin, L, 1e30, true, h)) continue;
        sum += environmentRadiance(L) * (cosine / pdf);
    }
    return sum / float(max(u_environmentSamples, 1));
}
#endif

// Irradiance from the punctual lights on a surface at P with normal N (oriented; else lit from
// every side at half strength), the shadow looked up at Ps.
vec3 punctualIrradiance(vec3 P, vec3 Ps, vec3 N, bool oriented) {
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < u_lightCount; ++i) {
        vec3 L;
        float dist;
        // Irradiance at the centre (the surface is within a voxel of it; the shadow lookup point is
        // not, and near a light the inverse-square law would overshoot there).
        vec3 e = lightIrradiance(u_lights[i], P, L, dist);
        float cosine = oriented ? max(dot(N, L), 0.0) : 0.5;
        if (cosine <= 0.0 || all(equal(e, vec3(0.0)))) continue;
        irradiance += e * cosine * shadowVisibility(u_lights[i], Ps, N, cosine);
    }
    return irradiance;
}

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(u_resolution)))) return;
    vec4 albedo = texelFetch(s_albedo, v, 0);
    if (albedo.a == 0.0) {
        imageStore(i_radiance, v, vec4(0.0));
        imageStore(i_sides, v, vec4(0.0));
        imageStore(i_punctual, v, vec4(0.0));
        return;
    }
    vec3 meanNormal = texelFetch(s_normal, v, 0).xyz * 2.0 - 1.0;
    float len = length(meanNormal);
    vec4 emission = texelFetch(s_emission, v, 0);
    int slab = voxelSlabAxis(emission);  // the voxelizer's mark, in emission.a
    // Surfaces facing opposite ways in one voxel average to a short normal: light it from every
    // side at half strength rather than not at all; a slab's two faces each on its own.
    bool oriented = len > VOXEL_TWO_SIDED && slab < 0;
    vec3 N = oriented ? meanNormal / len : vec3(0.0, 1.0, 0.0);
    vec3 P = (u_voxelToWorld * vec4(vec3(v) + 0.5, 1.0)).xyz;
    vec3 irradiance, difference = vec3(0.0), punctual = vec3(0.0);
    if (slab >= 0) {
        // Each face's shadow one voxel in front of it, on its own side of the wall.
        vec3 A = vec3(0.0);
        A[slab] = 1.0;
        vec3 front = punctualIrradiance(P, P + A * u_voxelSize, A, true);
        vec3 back = punctualIrradiance(P, P - A * u_voxelSize, -A, true);
        // No environment light here: a building's every outer wall faces the sky, and the readers
        // that blend a slab's faces (coarser levels and cascades, trilinear lookups) carried that
        // sky into the rooms behind (builtin:building's hall at 1.53-1.72 of Cycles' mean, 1.06-1.14
        // without it). What is lost is the sky's bounce off thin walls.
        irradiance = punctual = 0.5 * (front + back);
        difference = 0.5 * (front - back);
    } else {
        // Look the shadow up one voxel in front of the surface: the voxel centre may lie behind it.
        vec3 origin = P + N * (oriented ? u_voxelSize : 0.0);
        irradiance = punctual = punctualIrradiance(P, origin, N, oriented);
#if TRACED_LIGHT
        if (u_environmentSamples > 0) irradiance += environmentIrradiance(v, origin, N, oriented);
#endif
    }
#if TRACED_LIGHT
    if (u_emitterSamples.x > 0) irradiance += emitterIrradiance(v, P, N, oriented);
#endif
    vec3 radiance = albedo.rgb * INV_PI * irradiance + emission.rgb * u_emissionWeight;
    imageStore(i_radiance, v, vec4(min(finiteOrZero(radiance), vec3(MAX_HALF_FLOAT)), 1.0));
    vec3 sides = clamp(finiteOrZero(albedo.rgb * INV_PI * difference), vec3(-MAX_HALF_FLOAT), vec3(MAX_HALF_FLOAT));
    imageStore(i_sides, v, vec4(sides, slab >= 0 ? emission.a : 0.0));
    vec3 punctualRadiance = min(finiteOrZero(albedo.rgb * INV_PI * punctual), vec3(MAX_HALF_FLOAT));
    imageStore(i_punctual, v, vec4(punctualRadiance, 1.0));
}
