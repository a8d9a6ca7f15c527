// ReSTIR DI (Bitterli et al. 2020) over the ray scene's emissive triangles
// (renderer/emitters/emitter_lights.h). Two stages, one program each:
//   RESTIR_STAGE 0: M candidates by power, resampled against the unshadowed target
//     p_hat = luminance(f * Le * G); a visibility ray for the survivor (its W is 0 when occluded);
//     then the last frame's reservoir at the reprojected pixel, unless the surface there differs
//     (disocclusion), its M capped.  history -> temporal.
//   RESTIR_STAGE 1: k neighbours within a radius whose depth and normal are close, combined; the
//     survivor shaded with a visibility ray and averaged over the frames of a still view.
//     temporal -> history, accumulation.
// A reservoir is (sample y = emitter triangle and barycentrics, W, M); combining reservoirs i at
// pixel q weighs each by p_hat_q(y_i) * W_i * M_i and keeps one with probability proportional to
// its weight. W = sum of weights / (Z * p_hat_q(y)): biased, Z = sum of M_i; unbiased, Z counts
// only the M_i whose pixel could have produced y (its p_hat > 0 and y visible from it), the 1/Z
// weights of Bitterli et al.'s algorithm 6.
#include "common.glsl"
#include "brdf.glsl"
#include "gbuffer_layout.glsl"
#include "random.glsl"
#include "ray_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 1) uniform sampler2D s_depth;
layout(binding = 2) uniform sampler2D s_gbufBaseColor;
layout(binding = 3) uniform sampler2D s_gbufNormal;
layout(binding = 4) uniform sampler2D s_gbufMaterial;

// Reservoir images: sample = (emitter triangle + 1 (0: none), barycentrics of p1 and p2, W);
// surface = (world position, M); normal = (shading normal, 0). Inputs 0-2, outputs 3-5.
layout(binding = 0, rgba32f) uniform readonly image2D i_sampleIn;
layout(binding = 1, rgba32f) uniform readonly image2D i_surfaceIn;
layout(binding = 2, rgba16f) uniform readonly image2D i_normalIn;
layout(binding = 3, rgba32f) uniform writeonly image2D i_sampleOut;
layout(binding = 4, rgba32f) uniform writeonly image2D i_surfaceOut;
layout(binding = 5, rgba16f) uniform writeonly image2D i_normalOut;
#if RESTIR_STAGE == 1
layout(binding = 6, rgba32f) uniform image2D i_accumulation;  // running mean over still frames
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

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

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
    uint triangle;  // 0xFFFFFFFF: no sample
    vec2 b;
    float W, M;
};

const uint NO_SAMPLE = 0xFFFFFFFFu;

Reservoir emptyReservoir() { return Reservoir(NO_SAMPLE, vec2(0.0), 0.0, 0.0); }

Reservoir loadReservoir(ivec2 pixel) {
    vec4 a = imageLoad(i_sampleIn, pixel);
    float M = imageLoad(i_surfaceIn, pixel).w;
    uint t = uint(a.x + 0.5);
    return Reservoir(t == 0u || M <= 0.0 ? NO_SAMPLE : t - 1u, a.yz, a.w, M);
}

void storeReservoir(ivec2 pixel, Reservoir r, vec3 P, vec3 N) {
    float t = r.triangle == NO_SAMPLE ? 0.0 : float(r.triangle + 1u);
    imageStore(i_sampleOut, pixel, vec4(t, r.b, finiteOrZero(vec3(r.W)).x));
    imageStore(i_surfaceOut, pixel, vec4(P, r.M));
    imageStore(i_normalOut, pixel, vec4(N, 0.0));
}

// The point y on its triangle, its normal, radiance towards `from` and per-area source density.
struct EmitterPoint {
    vec3 position, Le;
    float cosLight;  // |cos| at the emitter where it emits towards `from`, else 0
    float pdfArea;   // selection probability / area (ray_scene.glsl's attribute)
};

EmitterPoint emitterPoint(uint ti, vec2 b, vec3 from) {
    EmitterPoint e;
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

// f * cos(theta) * Le * cos(theta_l) / d^2: the unshadowed contribution of y, per unit area.
vec3 contribution(Surface s, EmitterPoint e, out vec3 L, out float dist) {
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
    return luminance(contribution(s, emitterPoint(r.triangle, r.b, s.P), L, dist));
}

// A ray from a G-buffer position: reconstructed from depth, it may lie a few depth-buffer steps
// behind its surface, a distance that grows with the distance to the camera; so the origin first
// moves off by a small fraction of that distance, then by offsetRayOrigin's few ulps.
bool visible(vec3 P, vec3 N, vec3 target) {
    vec3 origin = offsetRayOrigin(P + N * (2e-4 * length(u_cameraPos - P)), N);
    vec3 d = target - origin;
    float dist = length(d);
    if (!(dist > 0.0)) return false;
    Hit h;
    return !traceRay(origin, d / dist, dist * (1.0 - 1e-4), true, h);
}

// Could the reservoir at (P, N) have produced y: y lies in front of it, faces it, and (unbiased)
// is visible from it. Geometry alone decides p_hat > 0 for every BRDF here but a black one.
bool canProduce(vec3 P, vec3 N, Reservoir y) {
    EmitterPoint e = emitterPoint(y.triangle, y.b, P);
    vec3 d = e.position - P;
    if (e.cosLight <= 0.0 || dot(N, d) <= 0.0) return false;
    return u_reuse.unbiased == 0 || visible(P, N, e.position);
}

// Streaming combination of reservoirs at one pixel.
struct Combined {
    Reservoir r;
    float weightSum, target;  // target: p_hat_q of the kept sample
};

void combine(inout Combined c, Reservoir x, float targetHere, inout Rng rng) {
    float w = targetHere * x.W * x.M;
    c.r.M += x.M;
    if (!(w > 0.0)) return;
    c.weightSum += w;
    if (nextFloat(rng) * c.weightSum < w) {
        c.r.triangle = x.triangle;
        c.r.b = x.b;
        c.target = targetHere;
    }
}

// W of the combined reservoir, given Z (the M that count).
void finish(inout Combined c, float Z) {
    c.r.W = c.target > 0.0 && Z > 0.0 ? c.weightSum / (Z * c.target) : 0.0;
    if (!(c.r.W < MAX_RADIANCE)) c.r.W = 0.0;
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

#if RESTIR_STAGE == 0
// Resampled importance sampling of M candidates (Talbot et al. 2005), each weighted
// p_hat / p with p the per-area density of the power-proportional choice.
Combined initialCandidates(Surface s, inout Rng rng) {
    Combined c = Combined(emptyReservoir(), 0.0, 0.0);
    for (int i = 0; i < u_reuse.candidates; ++i) {
        Reservoir x = candidate(rng);
        EmitterPoint e = emitterPoint(x.triangle, x.b, s.P);
        vec3 L;
        float dist;
        float p = luminance(contribution(s, e, L, dist));
        c.r.M += 1.0;
        float w = e.pdfArea > 0.0 ? p / e.pdfArea : 0.0;
        if (!(w > 0.0) || !(w < MAX_RADIANCE)) continue;
        c.weightSum += w;
        if (nextFloat(rng) * c.weightSum < w) {
            c.r.triangle = x.triangle;
            c.r.b = x.b;
            c.target = p;
        }
    }
    finish(c, c.r.M);
    return c;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_sampleOut);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Surface s = loadSurface(pixel, size);
    if (!s.valid || u_emitterCount <= 0) {
        storeReservoir(pixel, emptyReservoir(), s.P, vec3(0.0));
        return;
    }
    Rng rng = makeRng(uvec2(pixel), 2u * u_frame.x, u_frame.y);
    Combined c = initialCandidates(s, rng);
    // Visibility reuse (Bitterli et al. 4.4): an occluded survivor is worth nothing to reuse.
    if (c.r.W > 0.0 && !visible(s.P, s.N, emitterPoint(c.r.triangle, c.r.b, s.P).position)) c.r.W = 0.0;

    // Temporal reuse at the reprojected pixel, if the surface there is this one.
    if (u_reuse.temporal != 0 && u_reuse.historyValid != 0) {
        vec4 clip = u_prevViewProj * vec4(s.P, 1.0);
        vec2 prevUv = clip.xy / clip.w * 0.5 + 0.5;
        ivec2 prev = ivec2(floor(prevUv * vec2(size)));
        if (clip.w > 0.0 && all(greaterThanEqual(prev, ivec2(0))) && all(lessThan(prev, size))) {
            Reservoir h = loadReservoir(prev);
            vec3 hP = imageLoad(i_surfaceIn, prev).xyz;
            vec3 hN = imageLoad(i_normalIn, prev).xyz;
            float viewDistance = length(u_cameraPos - s.P);
            bool same = h.M > 0.0 && dot(hN, s.N) > MIN_NORMAL_DOT &&
                        length(hP - s.P) < MAX_DEPTH_RATIO * 0.25 * viewDistance;
            if (same) {
                h.M = min(h.M, u_reuse.maxM);
                Reservoir current = c.r;
                Combined t = Combined(emptyReservoir(), 0.0, 0.0);
                combine(t, current, c.target, rng);
                combine(t, h, targetAt(s, h), rng);
                float Z = t.r.M;
                if (u_reuse.unbiased != 0 && t.r.triangle != NO_SAMPLE) {
                    Z = (canProduce(s.P, s.N, t.r) ? current.M : 0.0) + (canProduce(hP, hN, t.r) ? h.M : 0.0);
                }
                finish(t, Z);
                c = t;
            }
        }
    }
    storeReservoir(pixel, c.r, s.P, s.N);
}
#else
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_sampleOut);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Surface s = loadSurface(pixel, size);
    vec3 radiance = vec3(0.0);
    if (s.valid && u_emitterCount > 0) {
        Rng rng = makeRng(uvec2(pixel), 2u * u_frame.x + 1u, u_frame.y);
        Reservoir own = loadReservoir(pixel);
        Combined c = Combined(emptyReservoir(), 0.0, 0.0);
        combine(c, own, targetAt(s, own), rng);
        // Spatial reuse: k neighbours in a disc, kept only if their surface is like this one.
        ivec2 neighbours[8];
        int count = 0;
        float viewDistance = length(u_cameraPos - s.P);
        for (int i = 0; i < min(u_reuse.spatial, 8); ++i) {
            vec2 u = nextFloat2(rng);
            float r = u_reuse.radius * sqrt(u.x), phi = 2.0 * PI * u.y;
            ivec2 n = pixel + ivec2(round(r * vec2(cos(phi), sin(phi))));
            if (n == pixel || any(lessThan(n, ivec2(0))) || any(greaterThanEqual(n, size))) continue;
            vec4 nSurface = imageLoad(i_surfaceIn, n);
            vec3 nN = imageLoad(i_normalIn, n).xyz;
            if (!(nSurface.w > 0.0) || dot(nN, s.N) <= MIN_NORMAL_DOT ||
                abs(length(u_cameraPos - nSurface.xyz) - viewDistance) > MAX_DEPTH_RATIO * viewDistance)
                continue;
            Reservoir x = loadReservoir(n);
            combine(c, x, targetAt(s, x), rng);
            neighbours[count++] = n;
        }
        bool seen = false;
        if (c.r.triangle != NO_SAMPLE) seen = visible(s.P, s.N, emitterPoint(c.r.triangle, c.r.b, s.P).position);
        float Z = c.r.M;
        if (u_reuse.unbiased != 0 && c.r.triangle != NO_SAMPLE) {
            Z = seen ? own.M : 0.0;
            for (int i = 0; i < count; ++i) {
                vec4 nSurface = imageLoad(i_surfaceIn, neighbours[i]);
                if (canProduce(nSurface.xyz, imageLoad(i_normalIn, neighbours[i]).xyz, c.r)) Z += nSurface.w;
            }
        }
        finish(c, Z);
        if (seen && c.r.W > 0.0) {
            vec3 L;
            float dist;
            radiance = contribution(s, emitterPoint(c.r.triangle, c.r.b, s.P), L, dist) * c.r.W;
        }
        // An occluded survivor is kept with W = 0 (the visibility reuse of stage 0 for the next frame).
        if (!seen) c.r.W = 0.0;
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
}
#endif
