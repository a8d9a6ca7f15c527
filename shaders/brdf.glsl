// Every BRDF the app offers, in one place. Inputs are clamped by the named constants below so that
// no model divides by zero or raises zero to a zero power at the extremes (roughness 0, grazing).
#include "common.glsl"

// Perceptual roughness floor: alpha = 0.045^2 ~ 0.002 keeps the GGX peak (1/(pi alpha^2)) finite in
// 32-bit float and fp16 render targets (same floor as Filament).
const float MIN_ROUGHNESS = 0.045;
// N.V floor: interpolated or normal-mapped normals can face slightly away from the viewer.
const float MIN_N_DOT_V = 1e-4;

#define DIFFUSE_LAMBERT 0
#define SPECULAR_GGX 0
#define SPECULAR_NONE 1

struct SurfaceBrdf {
    vec3 diffuseColor;   // baseColor * (1 - metallic)
    vec3 f0;             // specular reflectance at normal incidence
    float f90;           // specular reflectance at grazing incidence
    float roughness;     // perceptual, >= MIN_ROUGHNESS
};

SurfaceBrdf makeSurfaceBrdf(vec3 baseColor, float metallic, float roughness, float specularFactor) {
    SurfaceBrdf s;
    s.diffuseColor = baseColor * (1.0 - metallic);
    // Dielectric F0 = 0.04 (IOR 1.5). KHR_materials_specular's factor scales the whole dielectric
    // lobe, F0 and F90 alike: a factor of 0 means no specular reflection at any angle. Metals tint F0.
    s.f0 = mix(vec3(0.04 * specularFactor), baseColor, metallic);
    s.f90 = mix(specularFactor, 1.0, metallic);
    s.roughness = clamp(roughness, MIN_ROUGHNESS, 1.0);
    return s;
}

// Lambert 1760: constant BRDF, albedo / pi.
vec3 diffuseLambert(SurfaceBrdf s) { return s.diffuseColor * INV_PI; }

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007), alpha = roughness^2.
float distributionGgx(float NoH, float alpha) {
    float a2 = alpha * alpha;
    float f = (NoH * a2 - NoH) * NoH + 1.0;
    return a2 / (PI * f * f);
}

// Height-correlated Smith G2 / (4 N.L N.V), Hammon's approximation (GDC 2017, "PBR Diffuse
// Lighting for GGX+Smith Microsurfaces"): 0.5 / lerp(2 N.L N.V, N.L + N.V, alpha).
float visibilitySmithGgxHammon(float NoV, float NoL, float alpha) {
    return 0.5 / max(mix(2.0 * NoL * NoV, NoL + NoV, alpha), 1e-8);
}

// Schlick 1994 Fresnel, with the grazing reflectance f90.
vec3 fresnelSchlick(vec3 f0, float f90, float VoH) {
    float m = 1.0 - saturate(VoH);
    float m2 = m * m;
    return f0 + (vec3(f90) - f0) * (m2 * m2 * m);
}

vec3 specularGgx(SurfaceBrdf s, float NoV, float NoL, float NoH, float VoH) {
    float alpha = s.roughness * s.roughness;
    return distributionGgx(NoH, alpha) * visibilitySmithGgxHammon(NoV, NoL, alpha) * fresnelSchlick(s.f0, s.f90, VoH);
}

// f(l, v) for unit N, V, L. NoL <= 0 gives 0; NoV is floored at MIN_N_DOT_V.
vec3 evaluateBrdf(SurfaceBrdf s, vec3 N, vec3 V, vec3 L, int diffuseModel, int specularModel) {
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    float NoV = max(dot(N, V), MIN_N_DOT_V);
    vec3 h = V + L;
    float hLen2 = dot(h, h);
    // L = -V: the half vector is undefined; that configuration has no specular reflection.
    vec3 H = hLen2 > 1e-12 ? h * inversesqrt(hLen2) : N;
    float NoH = saturate(dot(N, H));
    float VoH = saturate(dot(V, H));

    vec3 f = diffuseLambert(s);
    if (specularModel == SPECULAR_GGX) f += specularGgx(s, NoV, NoL, NoH, VoH);
    return f;
}
