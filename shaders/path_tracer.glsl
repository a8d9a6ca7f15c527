// The path tracer's paths (pathtrace.comp's image, the lightmap bake's texels): unidirectional path
// tracing with next-event estimation to every punctual light and to emissive triangles, multiple
// importance sampling (power heuristic, Veach 1997) between light and BSDF sampling for emitters,
// Russian roulette, and the environment (environment.glsl): a constant, or a map sampled by its
// luminance at every vertex and weighted by MIS against the BSDF's samples that escape. The BRDF
// is the rasterizer's (brdf.glsl). The including shader sets the uniforms below (one location
// table, renderer/uniforms.h) and binds the ray counts at RAY_COUNTS_BINDING.
#include "common.glsl"
#include "brdf.glsl"
#include "lights.glsl"
#include "random.glsl"
#include "ray_scene.glsl"
#include "environment.glsl"
#include "bsdf_sampling.glsl"

layout(location = U_LIGHT_COUNT) uniform int u_lightCount;
layout(location = U_BRDF_MODELS) uniform ivec2 u_brdfModels;
layout(location = U_MAX_BOUNCES) uniform int u_maxBounces;
layout(location = U_EMITTER_COUNT) uniform int u_emitterCount;
layout(location = U_RR_START) uniform int u_rrStart;
// 0: no caustics. As Cycles' Reflective/Refractive Caustics switches: once a path has made a
// diffuse bounce, later vertices reflect no specular/glossy light (they are shaded and sampled as
// if the specular model were `none`), so no light reaches the camera along diffuse -> glossy ->
// light paths. Real-time methods produce no caustics; references are often rendered without.
layout(location = U_CAUSTICS) uniform int u_caustics;
// Which of the path's contributions are kept, for the term views (pathtrace_pass.cpp): the same
// paths (the random numbers do not depend on it), so the terms add up to the full radiance.
layout(location = U_PT_TERM) uniform int u_term;
// 1: an environment map is sampled as a light too (pathtrace.env-sampling); 0: BSDF samples alone.
layout(location = U_ENV_SAMPLING) uniform int u_sampleEnvironment;
const int TERM_ALL = 0, TERM_DIRECT = 1, TERM_EMISSION = 2, TERM_INDIRECT = 3;
const int TERM_INDIRECT_DIFFUSE = 4, TERM_INDIRECT_SPECULAR = 5;  // TERM_INDIRECT by the first surface's lobe
// 1 where a contribution of `term` is kept.
float kept(int term) { return u_term == TERM_ALL || u_term == term ? 1.0 : 0.0; }
// What is kept of an indirect contribution whose diffuse share (per channel) of the first
// surface's reflection is `diffuseShare`: the two lobes' views split it, the rest keep it whole.
vec3 keptIndirect(vec3 diffuseShare) {
    if (u_term == TERM_INDIRECT_DIFFUSE) return diffuseShare;
    if (u_term == TERM_INDIRECT_SPECULAR) return vec3(1.0) - diffuseShare;
    return vec3(kept(TERM_INDIRECT));
}

// Throughput figures (`--timings`' rays/s): rays traced, as 64-bit counts kept in pairs of uints
// (low, high) since core GL has no 64-bit atomics. Each invocation counts in registers and adds
// once at the end; the one add whose low word wraps carries into the high word.
#define RAYS_PRIMARY 0
#define RAYS_BOUNCE 1
#define RAYS_SHADOW 2
layout(std430, binding = RAY_COUNTS_BINDING) coherent buffer RayCounts { uint u_rayCounts[6]; };
uint g_rays[3] = uint[3](0u, 0u, 0u);

void publishRayCounts() {
    for (int k = 0; k < 3; ++k) {
        if (g_rays[k] == 0u) continue;
        uint before = atomicAdd(u_rayCounts[2 * k], g_rays[k]);
        if (before > 0xFFFFFFFFu - g_rays[k]) atomicAdd(u_rayCounts[2 * k + 1], 1u);
    }
}

// The largest finite float: path radiance is clamped here so that it never becomes Inf.
const float MAX_RADIANCE = 3.4028e38;
// Throughput below this ends a path: nothing it could still carry would show.
const float MIN_THROUGHPUT = 1e-7;
// Russian roulette never keeps a path with probability above this, so paths end eventually.
const float MAX_SURVIVAL = 0.95;

float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

struct SurfacePoint {
    vec3 position;
    vec3 geometricNormal;     // faces the incoming ray
    vec3 normal;              // shading normal, same hemisphere as geometricNormal
    SurfaceBrdf brdf;
    vec3 emission;            // radiance towards the incoming ray (0 from the back of one-sided emitters)
    float emitterPdfPerArea;
    bool hasSpecular;
};

SurfacePoint shade(Hit hit, vec3 rayDir) {
    RayHitGeometry g = hitGeometry(hit, rayDir);
    TriangleAttributes a = u_attributes[hit.triangle];
    RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
    vec2 uv = g.uv;
    bool frontFace = g.frontFace;

    SurfacePoint s;
    s.position = g.position;
    s.geometricNormal = g.geometricNormal;
    s.normal = g.normal;

    vec3 baseColor = hitBaseColor(hit, g);
    vec4 mr = sampleLayer(m.textures.y, uv);
    s.brdf = makeSurfaceBrdf(baseColor, saturate(m.params.x * mr.b), saturate(m.params.y * mr.g), m.params.z);
    s.hasSpecular = u_brdfModels.y == SPECULAR_GGX && (any(greaterThan(s.brdf.f0, vec3(0.0))) || s.brdf.f90 > 0.0);

    bool emits = frontFace || m.emissive.w > 0.5;
    vec3 emissiveTex = m.textures.w >= 0 ? srgbToLinear(sampleLayer(m.textures.w, uv).rgb) : vec3(1.0);
    s.emission = emits ? m.emissive.rgb * emissiveTex : vec3(0.0);
    s.emitterPdfPerArea = a.uv2MaterialEmitter.w;
    return s;
}

bool visible(vec3 from, vec3 dir, float dist) {
    Hit h;
    ++g_rays[RAYS_SHADOW];
    return !traceRay(from, dir, dist, true, h);
}

// Every punctual light at a surface point, a shadow ray each (no ray can hit one: they are only
// sampled so). `models`: the diffuse and specular models it is evaluated with (the render's, or a
// lightmap texel's white Lambertian). `moment` adds, per light, the luminance a white Lambertian
// surface there reflects (E cos / pi) times the light's direction in xyz and alone in w: the
// lightmap's directional bake.
vec3 punctualLight(SurfacePoint s, vec3 V, ivec2 models, inout vec4 moment) {
    vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_lightCount; ++i) {
        vec3 L;
        float dist;
        vec3 e = lightIrradiance(u_lights[i], s.position, L, dist);
        float NoL = dot(s.normal, L);
        if (NoL <= 0.0 || dot(s.geometricNormal, L) <= 0.0 || all(equal(e, vec3(0.0)))) continue;
        if (!visible(origin, L, dist * (1.0 - 1e-4))) continue;
        sum += evaluateBrdf(s.brdf, s.normal, V, L, models.x, models.y) * e * NoL;
        float l = luminance(e) * NoL * INV_PI;
        moment += vec4(l * L, l);
    }
    return sum;
}

// One emissive triangle sampled by power at a surface point, weighted by MIS against BSDF sampling.
vec3 emitterLight(SurfacePoint s, vec3 V, float pSpecular, ivec2 models, inout Rng rng) {
    vec3 origin = offsetRayOrigin(s.position, s.geometricNormal);
    vec3 sum = vec3(0.0);
    if (u_emitterCount > 0) {
        uint ti = pickEmitter(nextFloat(rng), u_emitterCount);
        TraceTriangle tri = u_triangles[ti];
        TriangleAttributes a = u_attributes[ti];
        vec2 u = nextFloat2(rng);
        float su = sqrt(u.x);
        vec2 b = vec2(su * (1.0 - u.y), su * u.y);  // uniform on the triangle
        vec3 q = tri.p0.xyz * (1.0 - b.x - b.y) + tri.p1.xyz * b.x + tri.p2.xyz * b.y;
        vec3 nl = cross(tri.p1.xyz - tri.p0.xyz, tri.p2.xyz - tri.p0.xyz);
        vec3 toLight = q - s.position;
        float d2 = dot(toLight, toLight);
        if (d2 > 0.0 && dot(nl, nl) > 0.0) {
            float dist = sqrt(d2);
            vec3 L = toLight / dist;
            nl = normalize(nl);
            RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
            float cosLight = dot(nl, -L);
            bool emits = cosLight > 0.0 || m.emissive.w > 0.5;
            float NoL = dot(s.normal, L);
            if (emits && NoL > 0.0 && dot(s.geometricNormal, L) > 0.0 && abs(cosLight) > 1e-8) {
                vec3 le = m.emissive.rgb;
                if (m.textures.w >= 0) le *= srgbToLinear(sampleLayer(m.textures.w, triangleUv(a, b)).rgb);
                float lightPdf = a.uv2MaterialEmitter.w * d2 / abs(cosLight);
                if (lightPdf > 0.0 && visible(origin, L, dist * (1.0 - 1e-4))) {
                    float weight = powerHeuristic(lightPdf, bsdfPdf(s.brdf, s.normal, V, L, pSpecular));
                    sum += evaluateBrdf(s.brdf, s.normal, V, L, models.x, models.y) * le * NoL *
                           (weight / lightPdf);
                }
            }
        }
    }
    return sum;
}

// Direct light at a surface point: every punctual light, plus one emissive triangle.
vec3 directLight(SurfacePoint s, vec3 V, float pSpecular, ivec2 models, inout Rng rng) {
    vec4 unusedMoment = vec4(0.0);
    return punctualLight(s, V, models, unusedMoment) + emitterLight(s, V, pSpecular, models, rng);
}

// The diffuse lobe's share of `f` (the whole BRDF at L), per channel; 0 where f is (nothing of it is
// then added anyway). Evaluated only for the two lobe views: the other terms do not read it.
vec3 diffuseShareOf(SurfacePoint s, vec3 V, vec3 L, vec3 f) {
    if (u_term != TERM_INDIRECT_DIFFUSE && u_term != TERM_INDIRECT_SPECULAR) return vec3(0.0);
    vec3 diffuse = evaluateBrdf(s.brdf, s.normal, V, L, u_brdfModels.x, SPECULAR_NONE);
    return vec3(greaterThan(f, vec3(0.0))) * clamp(diffuse / max(f, vec3(1e-30)), 0.0, 1.0);
}

// The term of the environment's light reaching the surface at `depth`: indirect, as the lighting
// pass splits it, unless it is a light of the direct pass (emitters.environment), which then
// lights the first surface directly.
vec3 environmentTerm(int depth, vec3 diffuseShare) {
    return depth == 0 && environmentIsDirectLight() ? vec3(kept(TERM_DIRECT)) : keptIndirect(diffuseShare);
}

// The environment map as a light: one direction drawn from its luminance, weighted by MIS (power
// heuristic) against the BSDF sampling the same direction (PBRT 3rd ed., 14.3.1). A constant
// environment is reached by BSDF samples alone, as it always was, and draws no random numbers.
vec3 environmentLight(SurfacePoint s, vec3 V, float pSpecular, ivec2 models, inout Rng rng, bool first,
                      out vec3 diffuseShare) {
    diffuseShare = vec3(0.0);
    if (!environmentIsMap() || u_sampleEnvironment == 0) return vec3(0.0);
    float lightPdf;
    vec3 L = sampleEnvironment(nextFloat2(rng), lightPdf);
    float NoL = dot(s.normal, L);
    if (!(lightPdf > 0.0) || NoL <= 0.0 || dot(s.geometricNormal, L) <= 0.0) return vec3(0.0);
    if (!visible(offsetRayOrigin(s.position, s.geometricNormal), L, 1e30)) return vec3(0.0);
    float weight = powerHeuristic(lightPdf, bsdfPdf(s.brdf, s.normal, V, L, pSpecular));
    vec3 f = evaluateBrdf(s.brdf, s.normal, V, L, models.x, models.y);
    // At the first surface it is split by its own lobes; later ones by the first surface's.
    if (first) diffuseShare = diffuseShareOf(s, V, L, f);
    return f * environmentRadiance(L) * NoL * (weight / lightPdf);
}

// `firstDepth` 0: `dir` leaves the camera; 1: it leaves a surface the caller shades itself (a
// lightmap texel), so what it hits first is that surface's direct light and the rest indirect.
// `firstPdf`: the density `dir` was drawn with, where the caller also samples the lights at its
// origin (the other half of the MIS for what the ray hits first); 0: it does not (the camera).
vec3 tracePath(vec3 origin, vec3 dir, inout Rng rng, int firstDepth, float firstPdf) {
    vec3 radiance = vec3(0.0);
    vec3 throughput = vec3(1.0);
    float lastBsdfPdf = firstPdf;  // 0 = no MIS for what the ray hits
    bool afterDiffuse = false; // the path has made a diffuse bounce (caustics switch)
    // The first surface's diffuse lobe's share of the throughput, per channel (set by its BSDF
    // sample): what of everything after it is indirect diffuse light, the rest indirect specular.
    vec3 diffuseShare = vec3(0.0);
    for (int depth = firstDepth;; ++depth) {
        Hit hit;
        ++g_rays[depth == 0 ? RAYS_PRIMARY : RAYS_BOUNCE];
        // Camera rays pass through single-sided back faces, which the rasterizer culls: every
        // method sees the same surfaces. Shadow and bounce rays meet both sides, as shadow maps
        // (and Cycles) do.
        // The terms as the lighting pass splits them: the first surface's emission or the
        // background seen directly; the light reaching the first surface straight from a light
        // or an emitter (sampled there, or hit by its BSDF sample, the other half of the MIS);
        // everything after is indirect, the environment lighting the first surface included
        // (unless it is a light of the direct pass: environmentTerm).
        if (!traceRay(origin, dir, 1e30, false, depth == 0, hit)) {
            // A map was also sampled as a light at the vertex this ray left: the other half of the MIS.
            float weight = environmentIsMap() && u_sampleEnvironment != 0 && lastBsdfPdf > 0.0 ? powerHeuristic(lastBsdfPdf, environmentPdf(dir)) : 1.0;
            // The camera sees the map filtered, as the lighting pass shows it; a light, by texel.
            vec3 sky = depth == 0 ? environmentBackground(dir) : environmentRadiance(dir);
            radiance += throughput * sky * weight *
                        (depth == 0 ? vec3(kept(TERM_EMISSION)) : environmentTerm(depth - 1, diffuseShare));
            break;
        }
        SurfacePoint s = shade(hit, dir);
        if (any(greaterThan(s.emission, vec3(0.0)))) {
            float weight = 1.0;
            if (lastBsdfPdf > 0.0 && s.emitterPdfPerArea > 0.0) {
                float cosLight = abs(dot(s.geometricNormal, dir));
                float lightPdf = s.emitterPdfPerArea * hit.t * hit.t / max(cosLight, 1e-8);
                weight = powerHeuristic(lastBsdfPdf, lightPdf);
            }
            vec3 keep = depth == 0 ? vec3(kept(TERM_EMISSION)) : depth == 1 ? vec3(kept(TERM_DIRECT)) : keptIndirect(diffuseShare);
            radiance += throughput * s.emission * weight * keep;
        }
        if (depth > u_maxBounces) break;  // that hit was only looked at for emission

        vec3 V = -dir;
        float NoV = max(dot(s.normal, V), MIN_N_DOT_V);
        bool noGlossy = afterDiffuse && u_caustics == 0;
        if (noGlossy) s.hasSpecular = false;
        int specularModel = noGlossy ? SPECULAR_NONE : u_brdfModels.y;
        float pSpecular = specularChoice(s.brdf, s.hasSpecular, NoV);
        radiance += throughput * directLight(s, V, pSpecular, ivec2(u_brdfModels.x, specularModel), rng) *
                    (depth == 0 ? vec3(kept(TERM_DIRECT)) : keptIndirect(diffuseShare));
        // The environment lights the first surface as indirect light, as the lighting pass splits it.
        vec3 environmentDiffuseShare;
        vec3 environment = environmentLight(s, V, pSpecular, ivec2(u_brdfModels.x, specularModel), rng, depth == 0,
                                            environmentDiffuseShare);
        radiance += throughput * environment * environmentTerm(depth, depth == 0 ? environmentDiffuseShare : diffuseShare);

        vec3 L;
        bool specularLobe;
        if (!sampleBsdf(s.brdf, s.normal, s.geometricNormal, V, pSpecular, rng, L, specularLobe)) break;
        afterDiffuse = afterDiffuse || !specularLobe;
        float pdf = bsdfPdf(s.brdf, s.normal, V, L, pSpecular);
        if (!(pdf > 1e-12)) break;
        vec3 f = evaluateBrdf(s.brdf, s.normal, V, L, u_brdfModels.x, specularModel);
        if (depth == 0) diffuseShare = diffuseShareOf(s, V, L, f);
        throughput *= f * dot(s.normal, L) / pdf;
        if (!(max(max(throughput.r, throughput.g), throughput.b) > MIN_THROUGHPUT)) break;
        if (depth >= u_rrStart) {
            float survive = min(max(max(throughput.r, throughput.g), throughput.b), MAX_SURVIVAL);
            if (nextFloat(rng) >= survive) break;
            throughput /= survive;
        }
        lastBsdfPdf = pdf;
        origin = offsetRayOrigin(s.position, s.geometricNormal);
        dir = L;
    }
    return radiance;
}
