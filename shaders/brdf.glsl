// Every BRDF the app offers, in one place, selected by the DIFFUSE_* / SPECULAR_* ids below
// (renderer.h's DiffuseModel / SpecularModel mirror them). The guards are named constants, each
// with the reason it exists: no model divides by zero, takes log(0) or pow(0, 0) at the extremes.
#include "common.glsl"

// Perceptual roughness floor: alpha = 0.045^2 ~ 0.002 keeps the GGX peak (1/(pi alpha^2)) finite in
// 32-bit float and fp16 render targets (same floor as Filament).
const float MIN_ROUGHNESS = 0.045;

// N.V floor (Godot uses the same 1e-4): interpolated or normal-mapped normals can face slightly
// away from the viewer, and the visibility and Burley terms must not see N.V <= 0.
const float MIN_N_DOT_V = 1e-4;
// N.L floor for turning the cosine-weighted response of the models that are not BRDFs (wrap,
// toon) back into an f = response / N.L. Never used by the physical models, which have no 1/N.L.
const float MIN_N_DOT_L = 1e-4;
// |V + L|^2 below this (L within ~1e-4 rad of -V): the half vector is undefined, and so is every
// half-vector lobe; specular is 0 there and Burley's difference angle is 90 degrees.
const float MIN_HALF_VECTOR_LENGTH2 = 1e-8;
// Smallest argument handed to log(): log(0) = -inf times an exponent of 0 would be NaN.
const float MIN_LOG_ARGUMENT = 1e-30;

#define DIFFUSE_LAMBERT 0
#define DIFFUSE_LAMBERT_WRAP 1
#define DIFFUSE_TOON 2
#define DIFFUSE_BURLEY 3

#define SPECULAR_GGX 0
#define SPECULAR_BLINN_PHONG 1
#define SPECULAR_TOON 2
#define SPECULAR_NONE 3

// The models compiled in, one bit per id above; every one unless the including shader says. The
// lighting pass compiles the set its scene can meet (the render's models and the materials'
// overrides): llvmpipe runs the body of a branch no pixel takes as a masked pass, so every model
// compiled in costs every pixel (the lighting pass ~10% faster on cornell_point with one pair).
#ifndef BRDF_DIFFUSE_MODELS
#define BRDF_DIFFUSE_MODELS 15
#endif
#ifndef BRDF_SPECULAR_MODELS
#define BRDF_SPECULAR_MODELS 15
#endif
#define HAS_DIFFUSE(id) ((BRDF_DIFFUSE_MODELS & (1 << (id))) != 0)
#define HAS_SPECULAR(id) ((BRDF_SPECULAR_MODELS & (1 << (id))) != 0)
#define IS_DIFFUSE(model, id) (HAS_DIFFUSE(id) && (model) == (id))
#define IS_SPECULAR(model, id) (HAS_SPECULAR(id) && (model) == (id))

struct SurfaceBrdf {
    vec3 diffuseColor;   // baseColor * (1 - metallic)
    vec3 f0;             // specular reflectance at normal incidence
    float f90;           // specular reflectance at grazing incidence (KHR_materials_specular)
    float roughness;     // perceptual, in [MIN_ROUGHNESS, 1]
};

SurfaceBrdf makeSurfaceBrdf(vec3 baseColor, float metallic, float roughness, float specularFactor) {
    SurfaceBrdf s;
    baseColor = saturate(baseColor);
    metallic = saturate(metallic);
    specularFactor = saturate(specularFactor);
    s.diffuseColor = baseColor * (1.0 - metallic);
    // Dielectric F0 = 0.04 (IOR 1.5); KHR_materials_specular's factor scales the whole dielectric
    // lobe, F0 and F90 alike, so a factor of 0 means no specular reflection at any angle. Metals
    // reflect their base colour at normal incidence and white at grazing.
    s.f0 = mix(vec3(0.04 * specularFactor), baseColor, metallic);
    s.f90 = mix(specularFactor, 1.0, metallic);
    s.roughness = clamp(roughness, MIN_ROUGHNESS, 1.0);
    return s;
}

// What the models need to know about one (N, V, L), computed once, with the guards applied.
struct BrdfGeometry {
    float NoL;       // signed: wrap and toon diffuse respond a little past the terminator
    float NoV;       // >= MIN_N_DOT_V
    float NoH;       // >= 0; 0 when there is no half vector
    float sinNH2;    // 1 - N.H^2, as |N x H|^2: exact near N.H = 1, where the sharp lobes live
    float LoH;       // = V.H, cosine of the difference angle, from |L + V| (0 when L = -V)
    float RoV;       // reflect(-L, N) . V, the Phong angle the toon highlight thresholds
    bool hasHalf;    // false when L = -V
};

BrdfGeometry brdfGeometry(vec3 N, vec3 V, vec3 L) {
    BrdfGeometry g;
    g.NoL = clamp(dot(N, L), -1.0, 1.0);
    float NoVraw = clamp(dot(N, V), -1.0, 1.0);
    g.NoV = max(NoVraw, MIN_N_DOT_V);
    g.RoV = 2.0 * g.NoL * NoVraw - dot(L, V);
    vec3 h = V + L;
    float hLen2 = dot(h, h);
    g.hasHalf = hLen2 >= MIN_HALF_VECTOR_LENGTH2;
    // |L + V| = 2 cos(theta_d) for unit vectors: no normalised H needed, and symmetric in L, V.
    g.LoH = g.hasHalf ? saturate(0.5 * sqrt(hLen2)) : 0.0;
    g.NoH = 0.0;
    g.sinNH2 = 1.0;
    if (g.hasHalf) {
        vec3 H = h * inversesqrt(hLen2);
        g.NoH = saturate(dot(N, H));
        vec3 c = cross(N, H);
        g.sinNH2 = saturate(dot(c, c));
    }
    return g;
}

float pow5(float x) {
    float x2 = x * x;
    return x2 * x2 * x;
}

// ln(1 - x) for x in [0, 1], accurate for tiny x (where 1 - x rounds away the digits that matter).
float log1mx(float x) {
    if (x < 0.01) return -x * (1.0 + x * (0.5 + x * (1.0 / 3.0 + x * 0.25)));
    return log(max(1.0 - x, MIN_LOG_ARGUMENT));
}

// ---- Diffuse. Each returns the cosine-weighted response f * max(N.L, 0) (for wrap and toon, the
// ---- model's own response, which is not of that form) per unit diffuse colour.

// Lambert 1760 ("Photometria"): f = 1/pi.
float diffuseLambert(BrdfGeometry g) { return max(g.NoL, 0.0) * INV_PI; }

// Wrapped Lambert, energy-conserving form (McAuley 2011, as in Godot 4.2's DIFFUSE_LAMBERT_WRAP):
// (N.L + w) / (1 + w)^2 / pi with the wrap w = roughness; integrates to 1 over the whole sphere.
float diffuseLambertWrap(BrdfGeometry g, float roughness) {
    float w = roughness;
    return max(g.NoL + w, 0.0) / ((1.0 + w) * (1.0 + w)) * INV_PI;
}

// Smoothstep ramp (lo < hi by construction: every caller keeps the ramp at least MIN_ROUGHNESS wide).
float ramp(float lo, float hi, float x) {
    float t = saturate((x - lo) / (hi - lo));
    return t * t * (3.0 - 2.0 * t);
}

// Toon diffuse (Godot 4.2's DIFFUSE_TOON): a smoothstep ramp from N.L = -r to +r, over pi.
float diffuseToon(BrdfGeometry g, float roughness) {
    return ramp(-roughness, roughness, g.NoL) * INV_PI;
}

// Burley 2012 ("Physically-Based Shading at Disney", sec. 5.3): Schlick-shaped retro-reflection with
// F_D90 = 0.5 + 2 roughness cos^2(theta_d) on both the light and the view side. This is f * pi.
float burleyFactor(BrdfGeometry g, float roughness) {
    float fd90Minus1 = 2.0 * roughness * g.LoH * g.LoH - 0.5;
    float lightScatter = 1.0 + fd90Minus1 * pow5(1.0 - max(g.NoL, 0.0));
    float viewScatter = 1.0 + fd90Minus1 * pow5(1.0 - g.NoV);
    return lightScatter * viewScatter;
}

float diffuseBurley(BrdfGeometry g, float roughness) {
    return burleyFactor(g, roughness) * max(g.NoL, 0.0) * INV_PI;
}

// ---- Specular microfacet terms (alpha = roughness^2 throughout).

// GGX / Trowbridge-Reitz normal distribution (Walter et al. 2007, eq. 33), written with
// 1 - N.H^2 = sinNH2 so the peak is not lost to cancellation. The denominator is >= alpha^2 > 0.
float distributionGgx(BrdfGeometry g, float alpha) {
    float a2 = alpha * alpha;
    float d = g.NoH * g.NoH * a2 + g.sinNH2;
    return a2 / (PI * d * d);
}

// Blinn 1977 lobe as a normalised NDF, (n + 2)/(2 pi) N.H^n, with Walter et al. 2007's exponent
// n = 2/alpha^2 - 2 (same highlight width as GGX/Beckmann at equal roughness). N.H^n is evaluated
// as exp(n/2 ln(1 - sinNH2)): n = 0 (roughness 1) gives 1 everywhere, never pow(0, 0).
float distributionBlinnPhong(BrdfGeometry g, float alpha) {
    float n = 2.0 / (alpha * alpha) - 2.0;
    return (n + 2.0) * (0.5 * INV_PI) * exp(0.5 * n * log1mx(g.sinNH2));
}

// Height-correlated Smith G2 / (4 N.L N.V), Hammon's approximation (GDC 2017, "PBR Diffuse
// Lighting for GGX+Smith Microsurfaces"): 0.5 / lerp(2 N.L N.V, N.L + N.V, alpha). The
// denominator is >= alpha * MIN_N_DOT_V >= 2e-7, so no guard is needed.
float visibilitySmithGgxHammon(float NoV, float NoL, float alpha) {
    return 0.5 / mix(2.0 * NoL * NoV, NoL + NoV, alpha);
}

// Schlick 1994 Fresnel, with the grazing reflectance f90 (1 for a plain Schlick).
vec3 fresnelSchlick(vec3 f0, float f90, float LoH) {
    return f0 + (vec3(f90) - f0) * pow5(1.0 - LoH);
}

// Microfacet specular f for N.L > 0 (D chosen by the model), without the cosine.
vec3 specularMicrofacet(SurfaceBrdf s, BrdfGeometry g, float roughness, int model) {
    // No half vector, or one facing away from N (Walter's chi+(N.H)): no facet reflects L into V.
    if (!g.hasHalf || g.NoH <= 0.0) return vec3(0.0);
    float alpha = roughness * roughness;
    float D = !HAS_SPECULAR(SPECULAR_BLINN_PHONG) || model == SPECULAR_GGX ? distributionGgx(g, alpha)
                                                                          : distributionBlinnPhong(g, alpha);
    return D * visibilitySmithGgxHammon(g.NoV, max(g.NoL, 0.0), alpha) * fresnelSchlick(s.f0, s.f90, g.LoH);
}

// Toon specular (Godot 4.2's SPECULAR_TOON): a smoothstep step on R.V around mid = (1 - r)^2,
// r wide, scaled by mid. Cosine-weighted response. Godot adds it to the diffuse light (so it is
// multiplied by albedo * (1 - metallic)); here it is tinted by diffuse colour + F0 and scaled by
// F90, so metals keep a highlight and a specular factor of 0 removes it, as for the other lobes.
vec3 specularToon(SurfaceBrdf s, BrdfGeometry g, float roughness) {
    if (g.NoL <= 0.0) return vec3(0.0);
    float mid = (1.0 - roughness) * (1.0 - roughness);
    float intensity = ramp(mid - 0.5 * roughness, mid + 0.5 * roughness, g.RoV) * mid;
    return intensity * saturate(s.diffuseColor + s.f0) * s.f90;
}

// ---- Entry points.

// Cosine-weighted response f(l, v) * max(N.L, 0) for unit N, V, L: the reflected radiance per unit
// of irradiance at normal incidence. This is what a light loop multiplies by the light's irradiance.
// For wrap and toon diffuse it is the model's own response, which reaches past N.L = 0.
vec3 evaluateBrdfCosine(SurfaceBrdf s, vec3 N, vec3 V, vec3 L, int diffuseModel, int specularModel) {
    BrdfGeometry g = brdfGeometry(N, V, L);
    float r = clamp(s.roughness, MIN_ROUGHNESS, 1.0);  // also for surfaces not built by makeSurfaceBrdf
    float d;
    if (IS_DIFFUSE(diffuseModel, DIFFUSE_LAMBERT_WRAP)) d = diffuseLambertWrap(g, r);
    else if (IS_DIFFUSE(diffuseModel, DIFFUSE_TOON)) d = diffuseToon(g, r);
    else if (IS_DIFFUSE(diffuseModel, DIFFUSE_BURLEY)) d = diffuseBurley(g, r);
    else d = diffuseLambert(g);
    vec3 response = s.diffuseColor * d;
    if (g.NoL > 0.0) {
        if (IS_SPECULAR(specularModel, SPECULAR_GGX) || IS_SPECULAR(specularModel, SPECULAR_BLINN_PHONG))
            response += specularMicrofacet(s, g, r, specularModel) * g.NoL;
        else if (IS_SPECULAR(specularModel, SPECULAR_TOON))
            response += specularToon(s, g, r);
    }
    return response;
}

// The BRDF f(l, v) for unit N, V, L; 0 for N.L <= 0. The physical models are evaluated directly;
// wrap and toon, defined by their cosine-weighted response, are divided by max(N.L, MIN_N_DOT_L).
vec3 evaluateBrdf(SurfaceBrdf s, vec3 N, vec3 V, vec3 L, int diffuseModel, int specularModel) {
    BrdfGeometry g = brdfGeometry(N, V, L);
    if (g.NoL <= 0.0) return vec3(0.0);
    float r = clamp(s.roughness, MIN_ROUGHNESS, 1.0);
    float invNoL = 1.0 / max(g.NoL, MIN_N_DOT_L);
    float d;
    if (IS_DIFFUSE(diffuseModel, DIFFUSE_LAMBERT_WRAP)) d = diffuseLambertWrap(g, r) * invNoL;
    else if (IS_DIFFUSE(diffuseModel, DIFFUSE_TOON)) d = diffuseToon(g, r) * invNoL;
    else if (IS_DIFFUSE(diffuseModel, DIFFUSE_BURLEY)) d = burleyFactor(g, r) * INV_PI;
    else d = INV_PI;
    vec3 f = s.diffuseColor * d;
    if (IS_SPECULAR(specularModel, SPECULAR_GGX) || IS_SPECULAR(specularModel, SPECULAR_BLINN_PHONG))
        f += specularMicrofacet(s, g, r, specularModel);
    else if (IS_SPECULAR(specularModel, SPECULAR_TOON))
        f += specularToon(s, g, r) * invNoL;
    return f;
}

// Directional albedo of the specular lobe, integral of f * cos over the hemisphere, as the split
// sum's scale and bias on F0 and F90: Karis, "Physically Based Shading on Mobile" (2014), an
// analytic fit to the pre-integrated GGX table (Karis, "Real Shading in Unreal Engine 4", 2013).
// Used to weight a method's pre-integrated specular radiance (the lighting contract); the other
// lobes use the same fit, and SPECULAR_NONE reflects nothing.
vec3 specularAlbedoSplitSum(SurfaceBrdf s, float NoV, int specularModel) {
    if (specularModel == SPECULAR_NONE) return vec3(0.0);
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = s.roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    vec2 scaleBias = vec2(-1.04, 1.04) * a004 + r.zw;
    return s.f0 * scaleBias.x + vec3(s.f90 * scaleBias.y);
}
