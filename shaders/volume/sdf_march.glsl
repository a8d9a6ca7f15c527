// Sphere tracing through the distance field (renderer/volume/): the one marcher the SDF method and
// probe GI share. The includer owns its uniforms and passes the field in, so this file declares
// nothing global.
//
//   SdfVolume vol = SdfVolume(origin, size, resolution);
//   SdfHit h = sdfMarch(s_distance, s_coarse, vol, rayOrigin, rayDir, sdfDefaultParams(maxDistance));
//
// or through cascades (renderer/volume/volume_cascades.h), stacked as layers of one texture:
//
//   SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, resolution);
//   SdfHit h = sdfMarchCascades(s_distance, s_coarse, cs, rayOrigin, rayDir, params);
//
// The field holds the distance at each cell's centre and is sampled trilinearly (exact for a
// plane); a second, coarse texture (sdf_coarse.comp) holds a lower bound per block of cells and is
// read first, so long empty stretches cost one cached fetch per step.

struct SdfVolume {
    vec3 origin;      // world position of the minimum corner
    float size;       // world edge of the cube
    int resolution;   // cells per edge
};

// SDF_MAX_CASCADES: renderer/volume/volume_cascades.h's kMaxCascades (a shared define).
// A ray hands over to the next coarser cascade this many cells before it would leave the finer
// one: the finer field knows nothing of surfaces outside its cube, so near its faces its values are
// too large (stepping is clamped by the distance to the faces, see sdfMarchLayer) and its gradient
// is unreliable.
const float SDF_HAND_OVER_CELLS = 2.0;

struct SdfCascades {
    vec4 volumes[SDF_MAX_CASCADES];   // origin xyz, edge; finest first, layer i of the textures
    int count;
    int resolution;                   // cells per edge of every cascade
};

struct SdfMarchParams {
    float startOffset;    // world distance skipped at the start (leave the surface a ray starts on)
    float hitThreshold;   // in cells (of the cascade marched in): |distance| below this is a hit
    float relaxation;     // over-relaxation factor in [1, 2): steps of w * distance, undone when too long
    int maxSteps;         // a ray still marching after this many steps is reported as a miss
    float maxDistance;    // world distance along the ray; beyond it, a miss
    int coarseFactor;     // fine cells per coarse texel (renderer/volume/distance_field.h)
};

struct SdfHit {
    bool hit;
    vec3 position;    // on the zero level set (the last point moved along the normal by its distance)
    vec3 normal;      // normalized gradient, central differences one cell apart
    float t;          // distance along the ray to `position`
    int steps;        // field lookups spent (a miss counts them too)
    int cascade;      // the cascade (layer) the hit was found in
    float stopValue;  // the field's value where the march stopped, before sdfRefine
};

SdfMarchParams sdfDefaultParams(float maxDistance) {
    return SdfMarchParams(0.0, SDF_HIT_THRESHOLD, 1.2, 96, maxDistance, 4);
}

float sdfCellSize(SdfVolume vol) { return vol.size / float(vol.resolution); }

SdfVolume sdfCascadeVolume(SdfCascades cs, int i) {
    return SdfVolume(cs.volumes[i].xyz, cs.volumes[i].w, cs.resolution);
}

// Texture coordinates of world position p in layer `layer` of a texture holding `vol.resolution`
// cells per layer along z. z is clamped half a cell inside the layer, so filtering never mixes two
// layers (x and y clamp at the texture's edges; one layer clamps exactly as before).
vec3 sdfLayerCoord(SdfVolume vol, int layer, int layers, vec3 p) {
    vec3 uvw = (p - vol.origin) / vol.size;
    float halfCell = 0.5 / float(vol.resolution);
    uvw.z = (float(layer) + clamp(uvw.z, halfCell, 1.0 - halfCell)) / float(layers);
    return uvw;
}

int sdfLayers(sampler3D field, SdfVolume vol) { return max(textureSize(field, 0).z / vol.resolution, 1); }

// Trilinear distance at a world position (clamped at the volume's faces), in layer `layer`.
float sdfSample(sampler3D field, SdfVolume vol, int layer, vec3 p) {
    return textureLod(field, sdfLayerCoord(vol, layer, sdfLayers(field, vol), p), 0.0).r;
}
float sdfSample(sampler3D field, SdfVolume vol, vec3 p) { return sdfSample(field, vol, 0, p); }

// Gradient by central differences one cell apart: with trilinear filtering, a narrower stencil
// would see the cell-wise constant slopes of the interpolation rather than the surface.
vec3 sdfNormal(sampler3D field, SdfVolume vol, int layer, vec3 p) {
    float h = sdfCellSize(vol);
    vec3 g = vec3(sdfSample(field, vol, layer, p + vec3(h, 0, 0)) - sdfSample(field, vol, layer, p - vec3(h, 0, 0)),
                  sdfSample(field, vol, layer, p + vec3(0, h, 0)) - sdfSample(field, vol, layer, p - vec3(0, h, 0)),
                  sdfSample(field, vol, layer, p + vec3(0, 0, h)) - sdfSample(field, vol, layer, p - vec3(0, 0, h)));
    float len = length(g);
    return len > 1e-20 ? g / len : vec3(0.0, 1.0, 0.0);
}
vec3 sdfNormal(sampler3D field, SdfVolume vol, vec3 p) { return sdfNormal(field, vol, 0, p); }

// Where the ray is inside the volume's cube: [enter, leave], empty when leave < enter.
vec2 sdfRayBox(SdfVolume vol, vec3 origin, vec3 dir) {
    vec3 inv = 1.0 / mix(dir, vec3(1e-30), equal(dir, vec3(0.0)));
    vec3 a = (vol.origin - origin) * inv;
    vec3 b = (vol.origin + vol.size - origin) * inv;
    vec3 lo = min(a, b), hi = max(a, b);
    return vec2(max(max(lo.x, lo.y), lo.z), min(min(hi.x, hi.y), hi.z));
}

// Distance from p (inside the cube) to the cube's nearest face.
float sdfFaceDistance(SdfVolume vol, vec3 p) {
    vec3 m = min(p - vol.origin, vol.origin + vol.size - p);
    return min(min(m.x, m.y), m.z);
}

// The finest cascade whose cube, less the hand-over margin, holds p (the coarsest otherwise).
int sdfCascadeAt(SdfCascades cs, vec3 p) {
    for (int i = 0; i < cs.count - 1; ++i) {
        SdfVolume vol = sdfCascadeVolume(cs, i);
        if (sdfFaceDistance(vol, p) >= SDF_HAND_OVER_CELLS * sdfCellSize(vol)) return i;
    }
    return cs.count - 1;
}

// A lower bound of |distance| over the coarse block around p (0 outside the volume).
float sdfCoarseBound(sampler3D coarse, SdfVolume vol, int layer, int coarseFactor, vec3 p) {
    int size = textureSize(coarse, 0).x;   // per layer; layers stack along z
    ivec3 c = ivec3(floor((p - vol.origin) / (sdfCellSize(vol) * float(coarseFactor))));
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(size)))) return 0.0;
    return texelFetch(coarse, c + ivec3(0, 0, layer * size), 0).r;
}

// A Newton step along the ray longer than this many cells (or than the empty sphere around its
// start) has its path checked, this many cells off the surface along its normal.
const float SDF_REFINE_FREE_CELLS = 0.5;
const float SDF_REFINE_LIFT_CELLS = 1.5;

// Whether the path from a to b, two points on a surface with normal n, crosses no other surface:
// sphere traced along the path lifted off the surface by SDF_REFINE_LIFT_CELLS, where the surface
// itself stays more than half a cell away, so a distance below that is something standing on it.
bool sdfLiftedPathClear(sampler3D field, SdfVolume vol, int layer, vec3 a, vec3 b, vec3 n) {
    float cell = sdfCellSize(vol);
    vec3 from = a + n * (SDF_REFINE_LIFT_CELLS * cell);
    float len = length(b - a);
    vec3 along = (b - a) / max(len, 1e-30);
    float s = 0.0;
    for (int i = 0; i < 64 && s < len; ++i) {
        float d = sdfSample(field, vol, layer, from + along * s);
        if (d < 0.5 * cell) return false;
        s += d;
    }
    return s >= len;
}

// The marcher stops within the hit threshold of the surface, which at a grazing angle is many
// cells short along the ray. Two Newton steps along the ray onto the zero level set (exact for a
// plane under trilinear filtering), each kept only if it brings |distance| down and, when it goes
// further than SDF_REFINE_FREE_CELLS and the empty sphere around its start, only if nothing stands
// on the surface in between: at a grazing angle the field near a floor is the floor's, and a step
// along it would pass through a wall standing on it, into the next room. If the ray runs nearly
// parallel to the surface, the point is moved onto it along the normal instead.
vec3 sdfRefineHit(sampler3D field, SdfVolume vol, int layer, vec3 origin, vec3 dir, float t, float d, vec3 n) {
    float cell = sdfCellSize(vol);
    // Where the ray comes within the hand-over margin of the cube's faces: the field knows nothing
    // beyond them.
    float tCube = sdfRayBox(vol, origin, dir).y - SDF_HAND_OVER_CELLS * cell;
    for (int k = 0; k < 2; ++k) {
        float cosine = -dot(dir, n);
        if (cosine < 0.02) break;
        float tNext = t + clamp(d / cosine, -2.0 * cell, 16.0 * cell);
        if (tNext > t && tNext > tCube) break;
        float dNext = sdfSample(field, vol, layer, origin + dir * tNext);
        if (abs(dNext) >= abs(d)) break;
        vec3 from = origin + dir * t - n * d, to = origin + dir * tNext - n * dNext;
        bool far = tNext - t > max(abs(d), SDF_REFINE_FREE_CELLS * cell);
        if (far && !sdfLiftedPathClear(field, vol, layer, from, to, n)) break;
        t = tNext;
        d = dNext;
    }
    return origin + dir * t - n * d;
}

// Marks `result` a hit at ray parameter t in layer `layer`, where the field holds d; sdfRefine
// then moves it onto the surface. Kept apart so that callers who only ask whether a ray hits
// (sdfSegmentClear) skip that work, and the marchers refine once, outside their loops.
void sdfStopAt(float t, float d, int layer, inout SdfHit result) {
    result.hit = true;
    result.t = t;
    result.stopValue = d;
    result.cascade = layer;
}

// A hit sdfStopAt marked: its normal and its point on the surface (sdfRefineHit).
void sdfRefine(sampler3D field, SdfVolume vol, vec3 origin, vec3 dir, inout SdfHit result) {
    if (!result.hit) return;
    vec3 x = origin + dir * result.t;
    result.normal = sdfNormal(field, vol, result.cascade, x);
    result.position = sdfRefineHit(field, vol, result.cascade, origin, dir, result.t, result.stopValue, result.normal);
    result.t = dot(result.position - origin, dir);
}

// Sphere traces from t up to tEnd through one volume (layer `layer`). Returns true with `result`
// marked a hit (sdfStopAt); otherwise t is where the ray left [.., tEnd] (or ran out of steps), at
// a point reached by safe steps only. `bounded`: surfaces outside the cube are missing from this
// field (a fine cascade), so no step is longer than the distance to the cube's faces - a sphere
// that reaches outside the cube is not known to be empty.
bool sdfMarchLayer(sampler3D field, sampler3D coarse, SdfVolume vol, int layer, bool bounded, vec3 origin, vec3 dir,
                   SdfMarchParams p, float tEnd, inout float t, inout SdfHit result) {
    float cell = sdfCellSize(vol);
    float threshold = p.hitThreshold * cell;
    float w = max(p.relaxation, 1.0);
    float previousRadius = 0.0, stepLength = 0.0;
    float previousSigned = 0.0;   // the last fine lookup (0: none since the start or a coarse step)
    while (result.steps < p.maxSteps && t <= tEnd) {
        vec3 x = origin + dir * t;
        result.steps += 1;
        float reach = bounded ? sdfFaceDistance(vol, x) : 3.4e38;
        // Far from everything: the coarse bound is enough and saves the trilinear fetch.
        float bound = min(sdfCoarseBound(coarse, vol, layer, p.coarseFactor, x), reach);
        if (bound > 4.0 * cell) {
            previousRadius = bound;   // the next relaxation check cannot fail on this step
            previousSigned = 0.0;
            stepLength = bound;
            t += bound;
            continue;
        }
        float d = sdfSample(field, vol, layer, x);
        float radius = min(abs(d), reach);
        // The sign flipped since the last lookup: the step crossed the zero level set (a trilinear
        // field between seed centres is not an exact distance, so a step can land past it). The
        // crossing lies between the two points: interpolate there instead of marching on inside.
        if (previousSigned * d < 0.0) {
            float tCross = t - stepLength * abs(d) / (abs(d) + abs(previousSigned));
            sdfStopAt(tCross, sdfSample(field, vol, layer, origin + dir * tCross), layer, result);
            return true;
        }
        // Over-relaxation (Keinert et al. 2015): a step of w*r is safe only if the sphere at the new
        // point still overlaps the previous one; if not, we may have jumped a surface: go back and
        // take the plain step, unrelaxed from then on.
        if (w > 1.0 && radius + previousRadius < stepLength) {
            t -= stepLength - previousRadius;
            stepLength = previousRadius;
            w = 1.0;
            continue;
        }
        if (abs(d) < threshold) {
            sdfStopAt(t, d, layer, result);
            return true;
        }
        previousRadius = radius;
        previousSigned = d;
        stepLength = radius * w;
        t += stepLength;
    }
    // Only the unrelaxed part of the last step is known to be empty: a hand-over starts there.
    t -= stepLength - previousRadius;
    return false;
}

SdfHit sdfMarch(sampler3D field, sampler3D coarse, SdfVolume vol, vec3 origin, vec3 dir, SdfMarchParams p) {
    SdfHit result = SdfHit(false, origin, vec3(0.0), 0.0, 0, 0, 0.0);
    vec2 span = sdfRayBox(vol, origin, dir);
    float t = max(p.startOffset, span.x);
    // Leaving the cube is a miss: the field says nothing outside it.
    sdfMarchLayer(field, coarse, vol, 0, false, origin, dir, p, min(p.maxDistance, span.y), t, result);
    sdfRefine(field, vol, origin, dir, result);
    return result;
}

// Cascade hand-over: the ray marches in the finest cascade that holds its current point; when it
// comes within SDF_HAND_OVER_CELLS of that cascade's faces it continues, from the same point and
// with the same step budget, in the next coarser one that holds it. Leaving the coarsest (the whole
// scene) is a miss. Each cascade's hit threshold is in its own cells. The hit is where the march
// stopped (sdfStopAt); sdfMarchCascades refines it.
SdfHit sdfStopCascades(sampler3D field, sampler3D coarse, SdfCascades cs, vec3 origin, vec3 dir, SdfMarchParams p) {
    SdfHit result = SdfHit(false, origin, vec3(0.0), 0.0, 0, 0, 0.0);
    float t = p.startOffset;
    for (int c = 0; c < cs.count; ++c) {
        SdfVolume vol = sdfCascadeVolume(cs, c);
        bool last = c == cs.count - 1;
        float margin = last ? 0.0 : SDF_HAND_OVER_CELLS * sdfCellSize(vol);
        vec2 span = sdfRayBox(SdfVolume(vol.origin + margin, vol.size - 2.0 * margin, vol.resolution), origin, dir);
        if (!last && !(span.x <= t && t < span.y)) continue;   // this cascade does not hold the ray here
        t = max(t, span.x);
        if (sdfMarchLayer(field, coarse, vol, c, !last, origin, dir, p, min(p.maxDistance, span.y), t, result))
            return result;
        if (result.steps >= p.maxSteps || t >= p.maxDistance) break;
    }
    return result;
}

SdfHit sdfMarchCascades(sampler3D field, sampler3D coarse, SdfCascades cs, vec3 origin, vec3 dir, SdfMarchParams p) {
    SdfHit result = sdfStopCascades(field, coarse, cs, origin, dir, p);
    sdfRefine(field, sdfCascadeVolume(cs, result.cascade), origin, dir, result);
    return result;
}

// p moved along the field's gradient until it is `clearance` from every surface the field holds
// (a few Newton steps on the distance; a point already that far stays where it is).
vec3 sdfPushOut(sampler3D field, SdfCascades cs, vec3 p, float clearance) {
    for (int i = 0; i < 3; ++i) {
        int c = sdfCascadeAt(cs, p);
        SdfVolume vol = sdfCascadeVolume(cs, c);
        float d = sdfSample(field, vol, c, p);
        if (d >= clearance) break;
        p += sdfNormal(field, vol, c, p) * (clearance - d);
    }
    return p;
}

// Whether the segment from `from` to `to` crosses no surface: a march along it that stops `endGap`
// short of `to`. Each cascade's hit threshold is in its own cells, so a wall the field resolves
// stops it wherever the wall lies.
bool sdfSegmentClear(sampler3D field, sampler3D coarse, SdfCascades cs, vec3 from, vec3 to, float endGap, int maxSteps) {
    float len = length(to - from);
    if (len <= endGap) return true;
    SdfMarchParams p = sdfDefaultParams(len - endGap);
    p.maxSteps = maxSteps;
    return !sdfStopCascades(field, coarse, cs, from, (to - from) / len, p).hit;
}

// Whether a surface point P sees `to` along a straight path: from `offsetCells` cells off the
// surface along `away` (a unit vector into the free space in front of it: past its own level set),
// moved a cell clear of any other surface (at a corner the start lies in the second one), to half a
// cell short of `to`. The probe gathers' path test.
bool sdfSurfaceSeesPoint(sampler3D field, sampler3D coarse, SdfCascades cs, vec3 P, vec3 away, vec3 to,
                         float offsetCells) {
    float cell = sdfCellSize(sdfCascadeVolume(cs, sdfCascadeAt(cs, P)));
    vec3 from = sdfPushOut(field, cs, P + away * (offsetCells * cell), cell);
    return sdfSegmentClear(field, coarse, cs, from, to, 0.5 * cell, 32);
}
