// The probe pipeline's storage and lookups on the GPU (renderer/probes/): the twin of
// renderer/probes/probe_math.{h,cpp} (same constants and layouts). One grid per cascade of the
// scene volume, their probes numbered one grid after the other, finest first. Buffers (std430): irradiance (one vec4 per SH coefficient or
// octahedral texel, per probe), distance moments (vec2 per texel of a 14x14 octahedral map), state
// (two vec4 per probe: relocation offset + state 0 active / 1 relocated / 2 off; update count,
// last relative change).
#include "common.glsl"

#define PROBE_SH1 0
#define PROBE_SH2 1
#define PROBE_OCTAHEDRAL 2
#define OCT_IRRADIANCE_SIZE 6
#define OCT_DISTANCE_SIZE 14
#define PROBE_OFF 2.0
#define PROBE_MAX_GRIDS SDF_MAX_CASCADES

layout(std430, binding = SP_IRRADIANCE) buffer ProbeIrradiance { vec4 probeIrradiance[]; };
layout(std430, binding = SP_DISTANCE) buffer ProbeDistance { vec2 probeDistance[]; };
layout(std430, binding = SP_STATE) buffer ProbeState { vec4 probeState[]; };

layout(location = UP_GRID_FIRST) uniform vec3 u_gridFirst[PROBE_MAX_GRIDS];
layout(location = UP_GRID_STEP) uniform vec3 u_gridStep[PROBE_MAX_GRIDS];
layout(location = UP_GRID_COUNTS) uniform ivec3 u_gridCounts[PROBE_MAX_GRIDS];
layout(location = UP_GRID_COUNT) uniform int u_gridCount;
layout(location = UP_STORAGE) uniform int u_storage;

int gridProbes(int g) { return u_gridCounts[g].x * u_gridCounts[g].y * u_gridCounts[g].z; }
int gridBase(int g) {
    int base = 0;
    for (int k = 0; k < g; ++k) base += gridProbes(k);
    return base;
}
int probeCount() { return gridBase(u_gridCount); }
int probeGrid(int i) {
    int g = 0;
    for (int base = gridProbes(0); g < u_gridCount - 1 && i >= base; base += gridProbes(g)) ++g;
    return g;
}
float gridMinStep(int g) { return min(u_gridStep[g].x, min(u_gridStep[g].y, u_gridStep[g].z)); }
int probeIndex(int g, ivec3 c) { return gridBase(g) + c.x + u_gridCounts[g].x * (c.y + u_gridCounts[g].y * c.z); }
ivec3 probeCoord(int i) {
    int g = probeGrid(i);
    int l = i - gridBase(g);
    ivec3 n = u_gridCounts[g];
    return ivec3(l % n.x, (l / n.x) % n.y, l / (n.x * n.y));
}
bool probeOff(int i) { return probeState[2 * i].w > 1.5; }
// Grid position (without the relocation offset), and with it.
vec3 probeGridPosition(int i) { return u_gridFirst[probeGrid(i)] + vec3(probeCoord(i)) * u_gridStep[probeGrid(i)]; }
vec3 probePosition(int i) { return probeGridPosition(i) + probeState[2 * i].xyz; }

int irradianceStride() {
    return u_storage == PROBE_SH1 ? 4 : (u_storage == PROBE_SH2 ? 9 : OCT_IRRADIANCE_SIZE * OCT_IRRADIANCE_SIZE);
}

// Spherical Fibonacci: direction k of n, equal-area in z, golden-angle spiral in phi.
vec3 fibonacciDirection(int k, int n) {
    float z = 1.0 - (2.0 * float(k) + 1.0) / float(n);
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.39996323 * float(k);
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Real SH basis, bands 0-2 (Ramamoorthi & Hanrahan 2001's constants), coefficient c.
float shBasis(int c, vec3 d) {
    switch (c) {
    case 0: return 0.282095;
    case 1: return 0.488603 * d.y;
    case 2: return 0.488603 * d.z;
    case 3: return 0.488603 * d.x;
    case 4: return 1.092548 * d.x * d.y;
    case 5: return 1.092548 * d.y * d.z;
    case 6: return 0.315392 * (3.0 * d.z * d.z - 1.0);
    case 7: return 1.092548 * d.x * d.z;
    default: return 0.546274 * (d.x * d.x - d.y * d.y);
    }
}
// The clamped-cosine kernel's band factor A_l (pi, 2pi/3, pi/4).
float shCosine(int c) { return c == 0 ? PI : (c < 4 ? 2.0943951 : 0.78539816); }

vec2 octEncode(vec3 d) {
    vec3 a = d / (abs(d.x) + abs(d.y) + abs(d.z));
    vec2 p = a.xy;
    if (a.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    return p * 0.5 + 0.5;
}
vec3 octDecode(vec2 uv) {
    vec2 p = uv * 2.0 - 1.0;
    vec3 d = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (d.z < 0.0) d.xy = (1.0 - abs(d.yx)) * vec2(d.x >= 0.0 ? 1.0 : -1.0, d.y >= 0.0 ? 1.0 : -1.0);
    return normalize(d);
}
vec3 octTexelDirection(int t, int size) { return octDecode((vec2(t % size, t / size) + 0.5) / float(size)); }
// A texel past the map's edge is its mirror across that edge (how the octahedron folds), so
// bilinear lookups need no border texels.
ivec2 octWrap(ivec2 t, int n) {
    if (t.x < 0 || t.x >= n) t = ivec2(clamp(t.x, 0, n - 1), n - 1 - t.y);
    if (t.y < 0 || t.y >= n) t = ivec2(n - 1 - t.x, clamp(t.y, 0, n - 1));
    return t;
}
// Bilinear weights and the four texels around direction d on a size x size map.
void octBilinear(vec3 d, int size, out ivec2 texels[4], out vec4 weights) {
    vec2 p = octEncode(d) * float(size) - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    texels[0] = octWrap(base, size);
    texels[1] = octWrap(base + ivec2(1, 0), size);
    texels[2] = octWrap(base + ivec2(0, 1), size);
    texels[3] = octWrap(base + ivec2(1, 1), size);
    weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
}

// What reading any probe's irradiance for one normal needs, worked out once per shading point
// (a gather reads 8 probes with the same normal): SH, each coefficient's basis x cosine-lobe
// factor; octahedral, the four texels around the normal and their bilinear weights.
struct IrradianceLookup {
    float sh[9];
    int texels[4];
    vec4 weights;
};

IrradianceLookup irradianceLookup(vec3 n) {
    IrradianceLookup l;
    if (u_storage == PROBE_OCTAHEDRAL) {
        ivec2 t[4];
        octBilinear(n, OCT_IRRADIANCE_SIZE, t, l.weights);
        for (int k = 0; k < 4; ++k) l.texels[k] = t[k].y * OCT_IRRADIANCE_SIZE + t[k].x;
    } else {
        for (int c = 0; c < 9; ++c) l.sh[c] = shCosine(c) * shBasis(c, n);
    }
    return l;
}

// E / pi (the cosine-weighted mean incoming radiance) of probe i for the lookup's normal.
vec3 probeIrradianceOverPi(int i, IrradianceLookup l) {
    int stride = irradianceStride();
    int base = i * stride;
    vec3 e = vec3(0.0);
    if (u_storage == PROBE_OCTAHEDRAL) {
        for (int k = 0; k < 4; ++k) e += l.weights[k] * probeIrradiance[base + l.texels[k]].rgb;
        return e;
    }
    for (int c = 0; c < stride; ++c) e += l.sh[c] * probeIrradiance[base + c].rgb;
    return max(e, vec3(0.0)) * INV_PI;  // low orders ring below zero behind strong lights
}
vec3 probeIrradianceOverPi(int i, vec3 n) { return probeIrradianceOverPi(i, irradianceLookup(n)); }

// Mean and mean^2 of the distance probe i saw around direction d.
vec2 probeDistanceMoments(int i, vec3 d) {
    ivec2 t[4];
    vec4 w;
    octBilinear(d, OCT_DISTANCE_SIZE, t, w);
    int base = i * OCT_DISTANCE_SIZE * OCT_DISTANCE_SIZE;
    vec2 m = vec2(0.0);
    for (int k = 0; k < 4; ++k) m += w[k] * probeDistance[base + t[k].y * OCT_DISTANCE_SIZE + t[k].x];
    return m;
}

// The finest grid whose probes surround P with half a step to spare (the coarsest otherwise).
int gridAt(vec3 P) {
    for (int g = 0; g < u_gridCount - 1; ++g) {
        vec3 lo = u_gridFirst[g] + 0.5 * u_gridStep[g];
        vec3 hi = u_gridFirst[g] + (vec3(u_gridCounts[g]) - 1.5) * u_gridStep[g];
        if (all(greaterThanEqual(P, lo)) && all(lessThanEqual(P, hi))) return g;
    }
    return u_gridCount - 1;
}

// Where a gather's path test starts: the surface point itself and the unit direction off it into
// the free space in front of it. Not the gather's biased point: the bias is a fraction of the
// grid's probe step, which in a coarse cascade reaches past the ceiling of a 3 m room (issue #39: a
// room with no opening took the sky from probes outside it). At a probe ray's hit, back along the
// ray, not along the field's normal: a coarse cascade's normal at a wall thinner than a cell may
// point along the wall or out of the room.
struct PathStart {
    vec3 surface;
    vec3 away;
};

#ifdef PROBE_SEGMENT_TEST
// Defined by the program that sets PROBE_SEGMENT_TEST, through its own tracer: whether the straight
// path from surface point P (leaving it along `away`, seen along V from free space) to a probe at
// `probe` crosses no geometry.
bool probeSeesPoint(vec3 probe, vec3 P, vec3 away, vec3 V);
#endif

// Indirect diffuse (E / pi) at P (already biased off the surface) with normal N, seen along V
// (towards free space: the eye, or the probe whose ray hit P), from grid g, with `visibility` as
// renderer/probes/probe_field.h's visibilityMode writes it (0 none, 1 moments, 2 moments and path):
// trilinear over the 8 surrounding probes, weighted by how the normal faces each (wrapped, as in
// DDGI, so probes behind still count a little) and, with `visibility`, by Chebyshev's bound on the
// probe seeing P (from its distance moments: light behind a wall the probe saw closer than P is cut).
// Moments averaged over a texel cannot cut a probe behind a wall much thinner than the probe step
// seen at a slant (issue #39: a closed room lit through its 20 cm walls), so with the path (mode 2,
// programs that define PROBE_SEGMENT_TEST) a probe the tracer finds no straight path to counts
// nothing. The path starts at `path`. Returns E / pi and a = 1, or a = 0 where no probe counted (the
// caller lights such a point otherwise, or not at all).
vec4 sampleProbeGrid(int g, vec3 P, vec3 N, vec3 V, int visibility, PathStart path) {
    ivec3 counts = u_gridCounts[g];
    int first = gridBase(g);
    vec3 gp = (P - u_gridFirst[g]) / u_gridStep[g];
    ivec3 base = clamp(ivec3(floor(gp)), ivec3(0), max(counts - 2, ivec3(0)));
    vec3 alpha = clamp(gp - vec3(base), 0.0, 1.0);
    IrradianceLookup lookup = irradianceLookup(N);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int k = 0; k < 8; ++k) {
        ivec3 off = ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        ivec3 c = min(base + off, counts - 1);
        int i = first + c.x + counts.x * (c.y + counts.y * c.z);
        vec4 state = probeState[2 * i];
        if (state.w > 1.5) continue;  // switched off
        vec3 tri = mix(1.0 - alpha, alpha, vec3(off));
        float w = tri.x * tri.y * tri.z;
        vec3 toProbe = u_gridFirst[g] + vec3(c) * u_gridStep[g] + state.xyz - P;
        float d = length(toProbe);
        vec3 dir = d > 1e-30 ? toProbe / d : N;
        float facing = 0.5 * (dot(dir, N) + 1.0);
        w *= facing * facing + 0.2;
        if (visibility > 0) {
#ifdef PROBE_SEGMENT_TEST
            if (visibility > 1 && !probeSeesPoint(P + toProbe, path.surface, path.away, V)) continue;
#endif
            vec2 m = probeDistanceMoments(i, -dir);
            if (d > m.x) {
                float variance = abs(m.y - m.x * m.x);
                float excess = d - m.x;
                float chebyshev = variance / max(variance + excess * excess, 1e-30);
                w *= chebyshev * chebyshev * chebyshev;
            }
        }
        w = max(w, 1e-7);
        sum += w * probeIrradianceOverPi(i, lookup);
        weights += w;
    }
    return weights > 0.0 ? vec4(sum / weights, 1.0) : vec4(0.0);
}
vec4 sampleProbes(vec3 P, vec3 N, vec3 V, int visibility, PathStart path) {
    return sampleProbeGrid(gridAt(P), P, N, V, visibility, path);
}

// A gather at a surface seen from `eye`: the shading point moved off the surface along
// 0.2 N + 0.8 V by `normalBias` x the probe step (DDGI's normal/view bias), so a probe's distance
// moments do not shadow the very surface they were measured on.
vec4 sampleProbesSeenFrom(vec3 P, vec3 N, vec3 eye, float normalBias, int visibility) {
    vec3 toEye = eye - P;
    vec3 V = length(toEye) > 0.0 ? normalize(toEye) : N;
    float bias = normalBias * gridMinStep(gridAt(P));
    return sampleProbes(P + (0.2 * N + 0.8 * V) * bias, N, V, visibility, PathStart(P, N));
}
