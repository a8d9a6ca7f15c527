// The punctual lights at a tracer's hit, as the lighting pass gives them to a surface there: each
// light with its shadow map, Lambertian with the hit's albedo. A voxel is lit as one surface facing
// its mean normal (or a slab's two faces), and lent that light to every surface in it: the shaded
// wall under a sunlit roof's edge, a column's shaded side and the loggia's back wall behind sunlit
// arches showed sunlight to the rays that met them (renderer/gi/vct/README.md, "A ray's hit lights
// itself with the punctual lights"). So a hit takes its voxel's punctual share (inject.comp's
// i_punctual) out of the voxel's light and lights itself; emission, the direct pass's lights and
// the bounces stay the voxel's. The includer binds what VoxelRadiance::bindHitLights binds.
#include "lights.glsl"

// The scene's lights (the frame's, with their shadow layers), at a binding of their own.
layout(std430, binding = VOLUME_HIT_LIGHTS_BINDING) readonly buffer HitLights { GpuLight u_hitLights[]; };

layout(binding = VOLUME_PUNCTUAL_UNIT) uniform sampler3D s_voxelPunctual;  // a layer per cascade, as the radiance
layout(binding = VOLUME_SHADOW_MAPS_UNIT) uniform sampler2DArrayShadow s_shadowMaps;
layout(binding = VOLUME_SHADOW_CUBES_UNIT) uniform sampler2DArrayShadow s_shadowCubes;
// A light that casts no shadow has no shadow layer (shadowVisibility: lit); --no-shadows leaves
// every light without one.
const int u_shadowsEnabled = 1;
// One tap (a hardware 2x2 comparison) a hit: the rays' many hits average the edges anyway, and the
// 3x3 taps cost the pixels' trace as much again.
#define SHADOW_PCF_RADIUS 0
#include "shadows.glsl"

// The punctual lights' irradiance at P on a surface facing N, each light's shadow looked up at Ps.
vec3 hitPunctualIrradiance(vec3 P, vec3 Ps, vec3 N) {
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < u_hitLights.length(); ++i) {
        vec3 L;
        float dist;
        vec3 e = lightIrradiance(u_hitLights[i], P, L, dist);
        float cosine = dot(N, L);
        if (cosine <= 0.0 || all(equal(e, vec3(0.0)))) continue;
        irradiance += e * cosine * shadowVisibility(u_hitLights[i], Ps, N, cosine);
    }
    return irradiance;
}

// The punctual lights' light reflected at P (normal N facing where the ray came from) by albedo.
vec3 hitPunctualLight(vec3 P, vec3 N, vec3 albedo) { return albedo * INV_PI * hitPunctualIrradiance(P, P, N); }

// A voxel's light `light` (unpremultiplied) with the punctual share `punctual` (premultiplied, a =
// occupancy) taken out and the hit's own put in.
vec3 withHitPunctualLight(vec3 light, vec4 punctual, vec3 P, vec3 N, vec3 albedo) {
    vec3 share = punctual.a > 1e-4 ? punctual.rgb / punctual.a : vec3(0.0);
    return max(light - share, vec3(0.0)) + hitPunctualLight(P, N, albedo);
}
