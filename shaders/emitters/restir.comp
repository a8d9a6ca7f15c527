// ReSTIR DI (Bitterli et al. 2020) over the ray scene's emissive triangles
// (renderer/emitters/emitter_lights.h) and the environment when it is a light of this pass
// (emitters.environment). Two stages, one program each:
//   RESTIR_STAGE 0: M candidates by power, resampled against the unshadowed target
//     p_hat = luminance(f * Le * G); a visibility ray for the survivor (its W is 0 when occluded);
//     then the last frame's reservoir at the reprojected pixel, unless the surface there differs
//     (disocclusion), its M capped.  history -> temporal.
//   RESTIR_STAGE 1: k neighbours within a radius whose depth and normal are close, combined; the
//     survivor shaded with a visibility ray and averaged over the frames of a still view.
//     temporal -> history, accumulation.
// A reservoir is (sample y = emitter triangle and barycentrics, or an environment direction; W, M).
// The two kinds of sample live in one domain, the emitters' area and the sphere of directions side
// by side: each target and density is taken in its own sample's measure (per unit area, per
// steradian), which RIS allows as long as a sample is always weighed in the one it was drawn in. Reservoirs are combined by
// generalized RIS with bounded MIS weights (balance heuristics, see combine()); the target of a
// domain other than this pixel is unshadowed (biased: darker wherever neighbours see the emitters
// differently, README) or times the visibility from that domain's surface (unbiased: a ray per
// reused reservoir).
#include "common.glsl"
#include "brdf.glsl"
#include "gbuffer_layout.glsl"
#include "random.glsl"
#include "ray_scene.glsl"
#include "bsdf_sampling.glsl"
#include "environment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = TE_DEPTH) uniform sampler2D s_depth;
layout(binding = TE_BASE_COLOR) uniform sampler2D s_gbufBaseColor;
layout(binding = TE_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TE_MATERIAL) uniform sampler2D s_gbufMaterial;

// Reservoir images: sample = (emitter triangle + 1 (0: none, -1: the environment), barycentrics of
// p1 and p2 (the environment: the direction's map coordinates, environmentUv), W);
// surface = (world position, M); normal = (shading normal, 0). A stage reads the IN images and
// writes the OUT ones (renderer/emitters/emitter_uniforms.h).
layout(binding = IE_SAMPLE_IN, rgba32f) uniform readonly image2D i_sampleIn;
layout(binding = IE_SURFACE_IN, rgba32f) uniform readonly image2D i_surfaceIn;
layout(binding = IE_NORMAL_IN, rgba16f) uniform readonly image2D i_normalIn;
layout(binding = IE_SAMPLE_OUT, rgba32f) uniform writeonly image2D i_sampleOut;
layout(binding = IE_SURFACE_OUT, rgba32f) uniform writeonly image2D i_surfaceOut;
layout(binding = IE_NORMAL_OUT, rgba16f) uniform writeonly image2D i_normalOut;
#if RESTIR_STAGE == 1
layout(binding = IE_ACCUMULATION, rgba32f) uniform image2D i_accumulation;  // running mean over still frames
// The environment's part of it (the emitters.environment debug view): written only when it is a light.
layout(binding = IE_ENVIRONMENT_ACCUMULATION, rgba32f) uniform image2D i_environmentAccumulation;
#endif

layout(location = UE_VIEW_PROJ) uniform mat4 u_viewProj;
layout(location = UE_PREV_VIEW_PROJ) uniform mat4 u_prevViewProj;
layout(location = UE_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UE_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UE_EMITTER_COUNT) uniform int u_emitterCount;
layout(location = UE_BRDF_MODELS) uniform ivec2 u_brdfModels;
layout(location = UE_FRAME) uniform uvec2 u_frame;     // frame number, seed
RestirBlock u_reuse;

// The largest finite float: radiance is clamped here so that it never becomes Inf.
const float MAX_RADIANCE = 3.4028e38;
// Reuse only surfaces this close: normals within ~25 degrees, depth within 10% (Bitterli et al. 5.3).
const float MIN_NORMAL_DOT = 0.906;
const float MAX_DEPTH_RATIO = 0.1;

struct Surface {
    vec3 P, N, V;
    SurfaceBrdf brdf;
    ivec2 models;
    bool valid;
};

Surface loadSurface(ivec2 pixel, ivec2 size) {
    Surface s;
    float depth = texelFetch(s_depth, pixel, 0).r;
    s.valid = depth < 1.0;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    s.P = world.xyz / world.w;
    vec4 normalAndModels = texelFetch(s_gbufNormal, pixel, 0);
    s.N = dot(normalAndModels.xyz, normalAndModels.xyz) > 0.0 ? normalize(normalAndModels.xyz) : vec3(0.0, 0.0, 1.0);
    s.models = decodeBrdfOverride(normalAndModels.w, u_brdfModels);
    vec4 material = texelFetch(s_gbufMaterial, pixel, 0);
    s.brdf = makeSurfaceBrdf(texelFetch(s_gbufBaseColor, pixel, 0).rgb, material.x, material.y, material.w);
    s.V = normalize(u_cameraPos - s.P);
    return s;
}

struct Reservoir {
    uint triangle;  // NO_SAMPLE, ENVIRONMENT_SAMPLE or an emissive triangle
    vec2 b;         // barycentrics of p1 and p2, or the environment direction's environmentUv
    float W, M;
};

const uint NO_SAMPLE = 0xFFFFFFFFu;
const uint ENVIRONMENT_SAMPLE = 0xFFFFFFFEu;

Reservoir emptyReservoir() { return Reservoir(NO_SAMPLE, vec2(0.0), 0.0, 0.0); }

Reservoir loadReservoir(ivec2 pixel) {
    vec4 a = imageLoad(i_sampleIn, pixel);
    float M = imageLoad(i_surfaceIn, pixel).w;
    uint y = a.x < -0.5 ? ENVIRONMENT_SAMPLE : a.x < 0.5 ? NO_SAMPLE : uint(a.x + 0.5) - 1u;
    return Reservoir(M <= 0.0 ? NO_SAMPLE : y, a.yz, a.w, M);
}

void storeReservoir(ivec2 pixel, Reservoir r, vec3 P, vec3 N) {
    float t = r.triangle == NO_SAMPLE ? 0.0 : r.triangle == ENVIRONMENT_SAMPLE ? -1.0 : float(r.triangle + 1u);
    imageStore(i_sampleOut, pixel, vec4(t, r.b, finiteOrZero(vec3(r.W)).x));
    imageStore(i_surfaceOut, pixel, vec4(P, r.M));
    imageStore(i_normalOut, pixel, vec4(N, 0.0));
}

// Sample y seen from `from`: the point on its triangle (or the environment's direction), the
// radiance it sends towards `from` and the emitters' per-area source density.
struct LightPoint {
    vec3 position, Le;
    float cosLight;  // |cos| at the emitter where it emits towards `from`, else 0 (1: the environment)
    float pdfArea;   // selection probability / area (ray_scene.glsl's attribute; 0: the environment)
    bool environment;
    vec3 direction;  // towards the environment sample
};

LightPoint emitterPoint(uint ti, vec2 b, vec3 from) {
    LightPoint e;
    e.environment = false;
    e.direction = vec3(0.0);
    TraceTriangle tri = u_triangles[ti];
    TriangleAttributes a = u_attributes[ti];
    RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
    e.position = tri.p0.xyz * (1.0 - b.x - b.y) + tri.p1.xyz * b.x + tri.p2.xyz * b.y;
    vec3 nl = cross(tri.p1.xyz - tri.p0.xyz, tri.p2.xyz - tri.p0.xyz);
    vec3 toFrom = from - e.position;
    float c = dot(nl, nl) > 0.0 && dot(toFrom, toFrom) > 0.0 ? dot(normalize(nl), normalize(toFrom)) : 0.0;
    e.cosLight = c > 0.0 || m.emissive.w > 0.5 ? abs(c) : 0.0;  // one-sided emitters light their front only
    e.Le = m.emissive.rgb;
    if (m.textures.w >= 0) e.Le *= srgbToLinear(sampleLayer(m.textures.w, triangleUv(a, b)).rgb);
    e.pdfArea = a.uv2MaterialEmitter.w;
    return e;
}

LightPoint lightPoint(Reservoir r, vec3 from) {
    if (r.triangle != ENVIRONMENT_SAMPLE) return emitterPoint(r.triangle, r.b, from);
    LightPoint e;
    e.environment = true;
    e.direction = environmentDirection(r.b);
    e.position = from + e.direction;
    e.Le = environmentRadiance(e.direction);
    e.cosLight = 1.0;
    e.pdfArea = 0.0;
    return e;
}

// f * cos(theta) * Le * cos(theta_l) / d^2: the unshadowed contribution of y, per unit area; of an
// environment direction f * cos(theta) * Le, per steradian (dist: infinite).
vec3 contribution(Surface s, LightPoint e, out vec3 L, out float dist) {
    if (e.environment) {
        L = e.direction;
        dist = 1e30;  // beyond the scene
        return dot(s.N, L) > 0.0 ? evaluateBrdfCosine(s.brdf, s.N, s.V, L, s.models.x, s.models.y) * e.Le : vec3(0.0);
    }
    vec3 d = e.position - s.P;
    float d2 = dot(d, d);
    dist = sqrt(d2);
    L = d2 > 0.0 ? d / dist : s.N;
    if (!(d2 > 0.0) || e.cosLight <= 0.0 || dot(s.N, L) <= 0.0) return vec3(0.0);
    return evaluateBrdfCosine(s.brdf, s.N, s.V, L, s.models.x, s.models.y) * e.Le * (e.cosLight / d2);
}

float targetAt(Surface s, Reservoir r) {
    if (r.triangle == NO_SAMPLE) return 0.0;
    vec3 L;
    float dist;
    return luminance(contribution(s, lightPoint(r, s.P), L, dist));
}

// A ray from a G-buffer position (gbufferRayOrigin) to the sample: to its point on an emitter, or
// out of the scene along an environment direction.
bool visible(vec3 P, vec3 N, LightPoint e) {
    vec3 origin = gbufferRayOrigin(P, N, u_cameraPos);
    Hit h;
    if (e.environment) return !traceRay(origin, e.direction, 1e30, true, h);
    vec3 d = e.position - origin;
    float dist = length(d);
    if (!(dist > 0.0)) return false;
    return !traceRay(origin, d / dist, dist * (1.0 - 1e-4), true, h);
}

// The target function of another pixel's domain (a neighbour, or the history's surface) for the
// MIS weights: unshadowed, or (unbiased) times the visibility from that surface, so that a domain
// is weighted 0 where it cannot produce y; its reservoirs keep W = 0 for an occluded sample.
float domainTarget(Surface d, Reservoir y) {
    if (y.triangle == NO_SAMPLE) return 0.0;
    vec3 L;
    float dist;
    LightPoint e = lightPoint(y, d.P);
    float p = luminance(contribution(d, e, L, dist));
    if (p > 0.0 && u_reuse.unbiased != 0 && !visible(d.P, d.N, e)) p = 0.0;
    return p;
}

// Streaming resampling of reservoirs at one pixel, generalized RIS (Lin et al. 2022): reservoir
// i enters with weight m_i(y_i) * p_hat_q(y_i) * W_i, where the MIS weights m_i sum to one over the
// domains for every y; the survivor's W is the sum of weights / p_hat_q(y). The weights below are
// balance heuristics with confidence M, bounded by one, so a reused sample can never carry more
// than its own domain's estimate. (The 1/Z weights used before are unbiased too, but a sample that
// Z credited to fewer reservoirs than its weight came from was amplified by sum M / Z, and the
// history fed the amplified W back every frame: the divergence on glossy surfaces.)
struct Combined {
    Reservoir r;
    float weightSum, target;  // target: p_hat_q of the kept sample
};

// Adds sample x with resampling weight w (and its target here) to c, kept with probability w / sum.
void stream(inout Combined c, Reservoir x, float w, float targetHere, inout Rng rng) {
    if (!(w > 0.0) || !(w < MAX_RADIANCE)) return;
    c.weightSum += w;
    if (nextFloat(rng) * c.weightSum < w) {
        c.r.triangle = x.triangle;
        c.r.b = x.b;
        c.target = targetHere;
    }
}

void combine(inout Combined c, Reservoir x, float mis, float targetHere, inout Rng rng) {
    c.r.M += x.M;
    stream(c, x, mis * targetHere * x.W, targetHere, rng);
}

// W of the combined reservoir.
void finish(inout Combined c) {
    c.r.W = c.target > 0.0 ? c.weightSum / c.target : 0.0;
    if (!(c.r.W < MAX_RADIANCE)) c.r.W = 0.0;
}

// The balance heuristic of domain a against b for a sample with targets pa, pb there.
float balance(float Ma, float pa, float Mb, float pb) {
    float d = Ma * pa + Mb * pb;
    return d > 0.0 ? Ma * pa / d : 0.0;
}

// Picks an emissive triangle in proportion to its power and a uniform point on it.
Reservoir candidate(inout Rng rng) {
    Reservoir r;
    r.triangle = pickEmitter(nextFloat(rng), u_emitterCount);
    vec2 u = nextFloat2(rng);
    float su = sqrt(u.x);
    r.b = vec2(su * (1.0 - u.y), su * u.y);
    r.W = 0.0;
    r.M = 1.0;
    return r;
}

// The environment as a light of this pass: candidates are drawn from it at each pixel.
bool environmentLights() { return u_reuse.environmentCandidates > 0; }
bool anyLight() { return u_emitterCount > 0 || environmentLights(); }

#if RESTIR_STAGE == 0
// How many candidates each strategy draws at a pixel: emitters by power, environment directions,
// and along BSDF directions. The BSDF's are drawn only where there is a specular lobe: a diffuse
// surface gains little from them and they cost a ray each.
struct CandidateCounts {
    float light, environment, bsdf;
};

// An environment direction: a map's by its luminance (the path tracer's sampler), a constant's by
// the cosine around the normal (the unshadowed target is then the same for every candidate).
float environmentCandidatePdf(Surface s, vec3 L) {
    return environmentIsMap() ? environmentPdf(L) : max(dot(s.N, L), 0.0) * INV_PI;
}

Reservoir environmentCandidate(Surface s, inout Rng rng) {
    float pdf;
    vec3 L = environmentIsMap() ? sampleEnvironment(nextFloat2(rng), pdf) : cosineDirection(s.N, nextFloat2(rng));
    return Reservoir(ENVIRONMENT_SAMPLE, environmentUv(L), 0.0, 1.0);
}

// Streams candidate y (its target p at s, reached along L at distance dist) into c, weighed by
// the balance heuristic over the strategies that can draw it (Talbot et al. 2005, resampled
// importance sampling with several source densities): p / (M_light p_light(y) + M_bsdf p_bsdf(y)),
// the densities per unit emitter area, or per steradian for an environment direction (drawn by
// the environment's and the BSDF's strategies). Light sampling alone spikes where the BRDF is a
// narrow lobe (a mirror); the BSDF's density bounds the weight there by about Le times the lobe's albedo.
void streamCandidate(inout Combined c, Surface s, Reservoir x, CandidateCounts n, float pSpecular, inout Rng rng) {
    LightPoint e = lightPoint(x, s.P);
    vec3 L;
    float dist;
    float p = luminance(contribution(s, e, L, dist));
    float toMeasure = e.environment ? 1.0 : dist > 0.0 ? e.cosLight / (dist * dist) : 0.0;
    float bsdfDensity = n.bsdf > 0.0 ? bsdfPdf(s.brdf, s.N, s.V, L, pSpecular) * toMeasure : 0.0;
    float sourceDensity = e.environment ? n.environment * environmentCandidatePdf(s, L) : n.light * e.pdfArea;
    float denominator = sourceDensity + n.bsdf * bsdfDensity;
    stream(c, x, denominator > 0.0 ? p / denominator : 0.0, p, rng);
}

// The emitter point a BSDF direction from s meets first, or the environment direction when it
// leaves the scene and the environment is a light, as a candidate (NO_SAMPLE if neither).
Reservoir bsdfCandidate(Surface s, float pSpecular, inout Rng rng) {
    Reservoir r = emptyReservoir();
    vec3 L;
    bool specularLobe;
    if (!sampleBsdf(s.brdf, s.N, s.N, s.V, pSpecular, rng, L, specularLobe)) return r;
    Hit h;
    vec3 origin = gbufferRayOrigin(s.P, s.N, u_cameraPos);
    if (!traceRay(origin, L, 1e30, false, h)) {
        if (environmentLights()) r = Reservoir(ENVIRONMENT_SAMPLE, environmentUv(L), 0.0, 0.0);
        return r;
    }
    if (!(u_attributes[h.triangle].uv2MaterialEmitter.w > 0.0) || u_emitterCount <= 0) return r;
    r.triangle = h.triangle;
    r.b = h.barycentric;
    return r;
}

// Resampled importance sampling of the emitter candidates (by power), the environment's and the BSDF's.
Combined initialCandidates(Surface s, inout Rng rng) {
    Combined c = Combined(emptyReservoir(), 0.0, 0.0);
    bool hasSpecular = s.models.y != SPECULAR_NONE && (any(greaterThan(s.brdf.f0, vec3(0.0))) || s.brdf.f90 > 0.0);
    float pSpecular = specularChoice(s.brdf, hasSpecular, max(dot(s.N, s.V), MIN_N_DOT_V));
    CandidateCounts n = CandidateCounts(u_emitterCount > 0 ? float(u_reuse.candidates) : 0.0,
                                        float(u_reuse.environmentCandidates),
                                        hasSpecular ? float(u_reuse.bsdfCandidates) : 0.0);
    for (int i = 0; i < int(n.light); ++i) streamCandidate(c, s, candidate(rng), n, pSpecular, rng);
    for (int i = 0; i < int(n.environment); ++i) streamCandidate(c, s, environmentCandidate(s, rng), n, pSpecular, rng);
    for (int i = 0; i < int(n.bsdf); ++i) {
        Reservoir x = bsdfCandidate(s, pSpecular, rng);
        if (x.triangle != NO_SAMPLE) streamCandidate(c, s, x, n, pSpecular, rng);
    }
    c.r.M = n.light + n.environment + n.bsdf;
    finish(c);
    return c;
}

// Temporal reuse: this frame's candidates c and the history h found at the reprojected pixel, on
// the surface h was made for (its position and normal; this pixel's material, seen from the last
// frame's camera). History M is capped so that the current candidates keep a share.
Combined temporalReuse(Surface s, Combined c, Reservoir h, Surface hs, inout Rng rng) {
    h.M = min(h.M, u_reuse.maxM);
    float pcC = c.target, pcH = targetAt(s, h);
    float phC = c.r.W > 0.0 ? domainTarget(hs, c.r) : 0.0;
    float phH = h.W > 0.0 && pcH > 0.0 ? targetAt(hs, h) : 0.0;
    Combined t = Combined(emptyReservoir(), 0.0, 0.0);
    combine(t, c.r, balance(c.r.M, pcC, h.M, phC), pcC, rng);
    combine(t, h, balance(h.M, phH, c.r.M, pcH), pcH, rng);
    finish(t);
    return t;
}

// The surface the reservoir at `prev` of the last frame was made for, if it is this one.
bool historySurface(Surface s, ivec2 prev, out Surface hs) {
    hs = s;
    hs.P = imageLoad(i_surfaceIn, prev).xyz;
    hs.N = imageLoad(i_normalIn, prev).xyz;
    hs.V = normalize(u_reuse.prevCameraPos.xyz - hs.P);
    float viewDistance = length(u_cameraPos - s.P);
    return imageLoad(i_surfaceIn, prev).w > 0.0 && dot(hs.N, s.N) > MIN_NORMAL_DOT &&
           length(hs.P - s.P) < MAX_DEPTH_RATIO * 0.25 * viewDistance;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_sampleOut);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Surface s = loadSurface(pixel, size);
    if (!s.valid || !anyLight()) {
        storeReservoir(pixel, emptyReservoir(), s.P, vec3(0.0));
        return;
    }
    Rng rng = makeRng(uvec2(pixel), 2u * u_frame.x, u_frame.y);
    Combined c = initialCandidates(s, rng);
    // Visibility reuse (Bitterli et al. 4.4): an occluded survivor is worth nothing to reuse.
    if (c.r.W > 0.0 && !visible(s.P, s.N, lightPoint(c.r, s.P))) c.r.W = 0.0;

    if (u_reuse.temporal != 0 && u_reuse.historyValid != 0) {
        vec4 clip = u_prevViewProj * vec4(s.P, 1.0);
        vec2 prevUv = clip.xy / clip.w * 0.5 + 0.5;
        ivec2 prev = ivec2(floor(prevUv * vec2(size)));
        Surface hs;
        if (clip.w > 0.0 && all(greaterThanEqual(prev, ivec2(0))) && all(lessThan(prev, size)) &&
            historySurface(s, prev, hs))
            c = temporalReuse(s, c, loadReservoir(prev), hs, rng);
    }
    storeReservoir(pixel, c.r, s.P, s.N);
}
#else
// Spatial reuse with pairwise MIS (Bitterli 2022, ch. 9.1.3; Wyman et al. 2023, "A gentle
// introduction to ReSTIR"): the pixel's own reservoir is the canonical domain c, each neighbour j
// is weighed against it alone, with confidence M and c's M split evenly over the k pairs. Pair j
// holds the share (M_j + M_c/k) / sum M of the unit weight, so with equal targets every reservoir
// weighs M_i / sum M, as the plain confidence-weighted combination does.
struct Neighbour {
    ivec2 pixel;
    Surface s;
};

bool similarNeighbour(Surface s, ivec2 n) {
    vec4 nSurface = imageLoad(i_surfaceIn, n);
    vec3 nN = imageLoad(i_normalIn, n).xyz;
    float viewDistance = length(u_cameraPos - s.P);
    return nSurface.w > 0.0 && dot(nN, s.N) > MIN_NORMAL_DOT &&
           abs(length(u_cameraPos - nSurface.xyz) - viewDistance) <= MAX_DEPTH_RATIO * viewDistance;
}

Combined spatialReuse(Surface s, ivec2 pixel, ivec2 size, Reservoir own, inout Rng rng) {
    Neighbour neighbours[8];
    int k = 0;
    float totalM = own.M;
    for (int i = 0; i < min(u_reuse.spatial, 8); ++i) {
        vec2 u = nextFloat2(rng);
        float r = u_reuse.radius * sqrt(u.x), phi = 2.0 * PI * u.y;
        ivec2 n = pixel + ivec2(round(r * vec2(cos(phi), sin(phi))));
        if (n == pixel || any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size))) continue;
        if (!similarNeighbour(s, n)) continue;
        neighbours[k].pixel = n;
        neighbours[k].s = loadSurface(n, size);
        totalM += imageLoad(i_surfaceIn, n).w;
        ++k;
    }
    Combined c = Combined(emptyReservoir(), 0.0, 0.0);
    float pcOwn = targetAt(s, own);
    if (k == 0) {
        combine(c, own, 1.0, pcOwn, rng);
        finish(c);
        return c;
    }
    float ownShare = own.M / float(k);
    float ownMis = 0.0;
    for (int j = 0; j < k; ++j) {
        Reservoir x = loadReservoir(neighbours[j].pixel);
        float pairShare = (x.M + ownShare) / totalM;
        float pjOwn = own.W > 0.0 && pcOwn > 0.0 ? domainTarget(neighbours[j].s, own) : 0.0;
        ownMis += pairShare * balance(ownShare, pcOwn, x.M, pjOwn);
        float pcX = targetAt(s, x), pjX = x.W > 0.0 && pcX > 0.0 ? targetAt(neighbours[j].s, x) : 0.0;
        combine(c, x, pairShare * balance(x.M, pjX, ownShare, pcX), pcX, rng);
    }
    combine(c, own, ownMis, pcOwn, rng);
    finish(c);
    return c;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_sampleOut);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Surface s = loadSurface(pixel, size);
    vec3 radiance = vec3(0.0);
    bool fromEnvironment = false;
    if (s.valid && anyLight()) {
        Rng rng = makeRng(uvec2(pixel), 2u * u_frame.x + 1u, u_frame.y);
        Combined c = spatialReuse(s, pixel, size, loadReservoir(pixel), rng);
        bool seen = c.r.triangle != NO_SAMPLE && c.r.W > 0.0 && visible(s.P, s.N, lightPoint(c.r, s.P));
        if (seen) {
            vec3 L;
            float dist;
            radiance = contribution(s, lightPoint(c.r, s.P), L, dist) * c.r.W;
            fromEnvironment = c.r.triangle == ENVIRONMENT_SAMPLE;
        } else {
            c.r.W = 0.0;  // kept with W = 0: the visibility reuse of stage 0, for the next frame
        }
        storeReservoir(pixel, c.r, s.P, s.N);
    } else {
        storeReservoir(pixel, emptyReservoir(), s.P, vec3(0.0));
    }
    radiance = finiteOrZero(min(radiance, vec3(MAX_RADIANCE)));
    // The mean of the frames of a still view: mean += (x - mean) / n stays finite.
    float n = u_reuse.framesAveraged + 1.0;
    vec4 mean = u_reuse.framesAveraged > 0.0 ? imageLoad(i_accumulation, pixel) : vec4(0.0);
    mean.rgb = min(mean.rgb + (radiance - mean.rgb) / n, vec3(MAX_RADIANCE));
    imageStore(i_accumulation, pixel, vec4(mean.rgb, 1.0));
    if (environmentLights()) {
        vec3 environment = fromEnvironment ? radiance : vec3(0.0);
        vec4 part = u_reuse.framesAveraged > 0.0 ? imageLoad(i_environmentAccumulation, pixel) : vec4(0.0);
        part.rgb = min(part.rgb + (environment - part.rgb) / n, vec3(MAX_RADIANCE));
        imageStore(i_environmentAccumulation, pixel, vec4(part.rgb, 1.0));
    }
}
#endif
