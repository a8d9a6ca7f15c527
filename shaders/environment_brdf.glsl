// The split sum's second factor for an environment map (Karis 2013, "Real Shading in Unreal Engine
// 4"): the specular lobe's directional albedo as F0 * A + F90 * B, tabulated over (N.V, roughness)
// from brdf.glsl's own GGX (environment_brdf_lut.comp), so the rasterized baseline reflects a map
// as much as the path tracer, which samples that BRDF. (The lighting contract's
// specularAlbedoSplitSum is Karis' 2014 analytic fit of the same table, kept for the methods'
// own terms.)
#ifndef ENVIRONMENT_BRDF_GLSL
#define ENVIRONMENT_BRDF_GLSL
#include "brdf.glsl"

layout(binding = ENV_BRDF_UNIT) uniform sampler2D s_envBrdf;  // rg: A, B

// Table coordinates <-> (N.V, roughness): texel centres at the table's own parameters, clamped
// at the ends (the ranges brdf.glsl clamps to).
vec2 environmentBrdfCoordinate(float NoV, float roughness) {
    return vec2((NoV - MIN_N_DOT_V) / (1.0 - MIN_N_DOT_V), (roughness - MIN_ROUGHNESS) / (1.0 - MIN_ROUGHNESS));
}
vec2 environmentBrdfParameters(vec2 coordinate) {
    return vec2(mix(MIN_N_DOT_V, 1.0, coordinate.x), mix(MIN_ROUGHNESS, 1.0, coordinate.y));
}

// GGX from the table; the other lobes from the analytic fit (they have no table).
vec3 environmentSpecularAlbedo(SurfaceBrdf s, float NoV, int specularModel) {
    if (specularModel != SPECULAR_GGX) return specularAlbedoSplitSum(s, NoV, specularModel);
    vec2 ab = textureLod(s_envBrdf, clamp(environmentBrdfCoordinate(NoV, s.roughness), 0.0, 1.0), 0.0).rg;
    return s.f0 * ab.x + vec3(s.f90 * ab.y);
}
#endif
