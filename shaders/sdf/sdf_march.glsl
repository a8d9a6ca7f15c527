// Sphere tracing through the distance field (renderer/sdf/): the one marcher the SDF method and
// probe GI share. The includer owns its uniforms and passes the field in, so this file declares
// nothing global.
//
//   SdfVolume vol = SdfVolume(origin, size, resolution);
//   SdfHit h = sdfMarch(s_distance, s_coarse, vol, rayOrigin, rayDir, sdfDefaultParams(maxDistance));
//
// The field holds the distance at each cell's centre and is sampled trilinearly (exact for a
// plane); a second, coarse texture (sdf_coarse.comp) holds a lower bound per block of cells and is
// read first, so long empty stretches cost one cached fetch per step.

struct SdfVolume {
    vec3 origin;      // world position of the minimum corner
    float size;       // world edge of the cube
    int resolution;   // cells per edge
};

struct SdfMarchParams {
    float startOffset;    // world distance skipped at the start (leave the surface a ray starts on)
    float hitThreshold;   // in cells: |distance| below this is a hit
    float relaxation;     // over-relaxation factor in [1, 2): steps of w * distance, undone when too long
    int maxSteps;         // a ray still marching after this many steps is reported as a miss
    float maxDistance;    // world distance along the ray; beyond it, a miss
    int coarseFactor;     // fine cells per coarse texel (renderer/sdf/distance_field.h)
};

struct SdfHit {
    bool hit;
    vec3 position;    // on the zero level set (the last point moved along the normal by its distance)
    vec3 normal;      // normalized gradient, central differences one cell apart
    float t;          // distance along the ray to `position`
    int steps;        // field lookups spent (a miss counts them too)
};

SdfMarchParams sdfDefaultParams(float maxDistance) {
    return SdfMarchParams(0.0, 0.5, 1.2, 96, maxDistance, 4);
}

float sdfCellSize(SdfVolume vol) { return vol.size / float(vol.resolution); }

// Trilinear distance at a world position (clamped at the volume's faces).
float sdfSample(sampler3D field, SdfVolume vol, vec3 p) {
    return textureLod(field, (p - vol.origin) / vol.size, 0.0).r;
}

// Gradient by central differences one cell apart: with trilinear filtering, a narrower stencil
// would see the cell-wise constant slopes of the interpolation rather than the surface.
vec3 sdfNormal(sampler3D field, SdfVolume vol, vec3 p) {
    float h = sdfCellSize(vol);
    vec3 g = vec3(sdfSample(field, vol, p + vec3(h, 0, 0)) - sdfSample(field, vol, p - vec3(h, 0, 0)),
                  sdfSample(field, vol, p + vec3(0, h, 0)) - sdfSample(field, vol, p - vec3(0, h, 0)),
                  sdfSample(field, vol, p + vec3(0, 0, h)) - sdfSample(field, vol, p - vec3(0, 0, h)));
    float len = length(g);
    return len > 1e-20 ? g / len : vec3(0.0, 1.0, 0.0);
}

// Where the ray is inside the volume's cube: [enter, leave], empty when leave < enter.
vec2 sdfRayBox(SdfVolume vol, vec3 origin, vec3 dir) {
    vec3 inv = 1.0 / mix(dir, vec3(1e-30), equal(dir, vec3(0.0)));
    vec3 a = (vol.origin - origin) * inv;
    vec3 b = (vol.origin + vol.size - origin) * inv;
    vec3 lo = min(a, b), hi = max(a, b);
    return vec2(max(max(lo.x, lo.y), lo.z), min(min(hi.x, hi.y), hi.z));
}

// A lower bound of |distance| over the coarse block around p (0 outside the volume).
float sdfCoarseBound(sampler3D coarse, SdfVolume vol, int coarseFactor, vec3 p) {
    ivec3 size = textureSize(coarse, 0);
    ivec3 c = ivec3(floor((p - vol.origin) / (sdfCellSize(vol) * float(coarseFactor))));
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, size))) return 0.0;
    return texelFetch(coarse, c, 0).r;
}

// The marcher stops within the hit threshold of the surface, which at a grazing angle is many
// cells short along the ray. Two Newton steps along the ray onto the zero level set (exact for a
// plane under trilinear filtering), each kept only if it brings |distance| down; if the ray runs
// nearly parallel to the surface, the point is moved onto it along the normal instead.
vec3 sdfRefineHit(sampler3D field, SdfVolume vol, vec3 origin, vec3 dir, float t, float d, vec3 n) {
    float cell = sdfCellSize(vol);
    for (int k = 0; k < 2; ++k) {
        float cosine = -dot(dir, n);
        if (cosine < 0.02) break;
        float tNext = t + clamp(d / cosine, -2.0 * cell, 16.0 * cell);
        float dNext = sdfSample(field, vol, origin + dir * tNext);
        if (abs(dNext) >= abs(d)) break;
        t = tNext;
        d = dNext;
    }
    return origin + dir * t - n * d;
}

SdfHit sdfMarch(sampler3D field, sampler3D coarse, SdfVolume vol, vec3 origin, vec3 dir, SdfMarchParams p) {
    SdfHit result = SdfHit(false, origin, vec3(0.0), 0.0, 0);
    float cell = sdfCellSize(vol);
    vec2 span = sdfRayBox(vol, origin, dir);
    float t = max(p.startOffset, span.x);
    // Leaving the cube is a miss: the field says nothing outside it.
    float tEnd = min(p.maxDistance, span.y);
    float threshold = p.hitThreshold * cell;
    float w = max(p.relaxation, 1.0);
    float previousRadius = 0.0, stepLength = 0.0;
    float previousSigned = 0.0;   // the last fine lookup (0: none since the start or a coarse step)
    for (int i = 0; i < p.maxSteps && t <= tEnd; ++i) {
        vec3 x = origin + dir * t;
        result.steps = i + 1;
        // Far from everything: the coarse bound is enough and saves the trilinear fetch.
        float bound = sdfCoarseBound(coarse, vol, p.coarseFactor, x);
        if (bound > 4.0 * cell) {
            previousRadius = bound;   // the next relaxation check cannot fail on this step
            previousSigned = 0.0;
            stepLength = bound;
            t += bound;
            continue;
        }
        float d = sdfSample(field, vol, x);
        float radius = abs(d);
        // The sign flipped since the last lookup: the step crossed the zero level set (a trilinear
        // field between seed centres is not an exact distance, so a step can land past it). The
        // crossing lies between the two points: interpolate there instead of marching on inside.
        if (previousSigned * d < 0.0) {
            float tCross = t - stepLength * abs(d) / (abs(d) + abs(previousSigned));
            vec3 xc = origin + dir * tCross;
            float dc = sdfSample(field, vol, xc);
            result.normal = sdfNormal(field, vol, xc);
            result.position = sdfRefineHit(field, vol, origin, dir, tCross, dc, result.normal);
            result.t = dot(result.position - origin, dir);
            result.hit = true;
            return result;
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
        if (radius < threshold) {
            result.normal = sdfNormal(field, vol, x);
            result.position = sdfRefineHit(field, vol, origin, dir, t, d, result.normal);
            result.t = dot(result.position - origin, dir);
            result.hit = true;
            return result;
        }
        previousRadius = radius;
        previousSigned = d;
        stepLength = radius * w;
        t += stepLength;
    }
    return result;
}
