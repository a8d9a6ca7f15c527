// Rays through the occupancy hierarchy (renderer/volume/occupancy.h) by hierarchical DDA (Museth
// 2014; Amanatides & Woo 1987 at each level): at each step the ray is in one voxel; it crosses the
// largest cell around that voxel known to be empty (a region without its bit, a block with an
// empty mask, else the voxel itself) in one step, leaving it through the face its own slab test
// finds, and stops in the first occupied voxel. No distance field: nothing to rebuild but the
// masks when voxels change. The includer owns its uniforms and passes the cascades in.
//
//   HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, resolution);
//   HddaHit h = hddaTraceCascades(cs, rayOrigin, rayDir, startOffset, maxDistance, maxSteps);
#include "volume/occupancy.glsl"

struct HddaCascades {
    vec4 volumes[SDF_MAX_CASCADES];   // origin xyz, edge; finest first (the volume's cascade order)
    int count;
    int resolution;                   // voxels per cascade edge
};

struct HddaHit {
    bool hit;
    vec3 position;  // world: where the ray enters the hit voxel
    vec3 normal;    // the face it entered through (towards the ray); -dir when it started inside
    float t;        // world distance along the ray to `position`
    int steps;      // cells crossed, every level and cascade together (a miss counts them too)
    int cascade;    // the cascade the hit was found in
    ivec3 voxel;    // the hit voxel in that cascade
};

// [t0, t1] of the ray inside the box [lo, hi] (t1 < t0: it misses). Zero direction components
// give +-inf slabs, which min/max handle.
vec2 hddaSlab(vec3 o, vec3 invDir, vec3 lo, vec3 hi) {
    vec3 a = (lo - o) * invDir, b = (hi - o) * invDir;
    vec3 n = min(a, b), f = max(a, b);
    return vec2(max(max(n.x, n.y), n.z), min(min(f.x, f.y), f.z));
}

// The walk in one cascade, in its voxel coordinates: o + d t, from tStart to tEnd (voxel units).
// Returns the hit, or a miss with t = where it left (tEnd at most).
HddaHit hddaWalk(int cascade, int n, vec3 o, vec3 d, float tStart, float tEnd, int maxSteps, inout int steps) {
    HddaHit h;
    h.hit = false;
    h.cascade = cascade;
    h.normal = -d;
    vec3 invDir = 1.0 / d;
    ivec3 stepDir = ivec3(sign(d));
    ivec3 v = clamp(ivec3(floor(o + d * tStart)), ivec3(0), ivec3(n - 1));
    float t = tStart;
    while (t <= tEnd && steps < maxSteps) {
        ++steps;
        int size = 1;
        if (!occRegionPresent(cascade, v, n)) {
            size = OCC_REGION;
        } else {
            uvec2 mask = occBlockMask(cascade, v, n);
            if (mask == uvec2(0u)) size = OCC_BLOCK;
            else if (occMaskHas(mask, v)) {
                h.hit = true;
                h.voxel = v;
                h.t = t;
                return h;
            }
        }
        ivec3 lo = (v / size) * size;   // v >= 0, so / is floor
        vec3 bound = vec3(lo) + vec3(greaterThan(d, vec3(0.0))) * float(size);
        vec3 tAxis = (bound - o) * invDir;
        // Axes the ray does not move along never leave the cell.
        tAxis = mix(tAxis, vec3(3.4e38), equal(stepDir, ivec3(0)));
        int axis = tAxis.x <= tAxis.y && tAxis.x <= tAxis.z ? 0 : (tAxis.y <= tAxis.z ? 1 : 2);
        t = max(tAxis[axis], t);
        // The next voxel: across the exit face on `axis`, inside the cell on the other two (the
        // point may round just outside them).
        ivec3 next = clamp(ivec3(floor(o + d * t)), lo, lo + size - 1);
        next[axis] = stepDir[axis] > 0 ? lo[axis] + size : lo[axis] - 1;
        h.normal = vec3(0.0);
        h.normal[axis] = -float(stepDir[axis]);
        if (next[axis] < 0 || next[axis] >= n) break;
        v = next;
    }
    h.t = min(t, tEnd);
    return h;
}

// The finest cascade holding p (on a face counts), or the coarsest when none does.
int hddaCascadeAt(HddaCascades cs, vec3 p) {
    for (int c = 0; c < cs.count - 1; ++c) {
        vec3 lo = cs.volumes[c].xyz;
        if (all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, lo + cs.volumes[c].w))) return c;
    }
    return cs.count - 1;
}

// Whether p lies in an occupied voxel of the finest cascade holding it.
bool hddaOccupied(HddaCascades cs, vec3 p) {
    int c = hddaCascadeAt(cs, p);
    vec3 v = (p - cs.volumes[c].xyz) / (cs.volumes[c].w / float(cs.resolution));
    if (any(lessThan(v, vec3(0.0))) || any(greaterThanEqual(v, vec3(cs.resolution)))) return false;
    return occVoxel(c, ivec3(v), cs.resolution);
}

// p, or the first point in a free voxel on the way along unit `dir` (half `cell` steps, at most
// four cells): where a walk from p can start without stopping in the voxel it starts in.
vec3 hddaFreeAlong(HddaCascades cs, vec3 p, vec3 dir, float cell) {
    for (int i = 0; i < 8 && hddaOccupied(cs, p); ++i) p += dir * (0.5 * cell);
    return p;
}

// From `origin` along unit `dir`, skipping `startOffset` (world), at most `maxDistance`: in the
// finest cascade that holds the start, handed to the next coarser one where it leaves (cascades
// nest, and a coarser cascade's voxels hold everything the finer one did). A ray that starts
// outside every cascade enters the coarsest where it reaches its cube.
HddaHit hddaTraceCascades(HddaCascades cs, vec3 origin, vec3 dir, float startOffset, float maxDistance, int maxSteps) {
    HddaHit result;
    result.hit = false;
    result.t = maxDistance;
    result.cascade = cs.count - 1;
    result.normal = -dir;
    vec3 invDir = 1.0 / dir;
    float t = startOffset;
    int steps = 0;
    for (int c = hddaCascadeAt(cs, origin + dir * t); c < cs.count && t < maxDistance; ++c) {
        vec3 lo = cs.volumes[c].xyz;
        float size = cs.volumes[c].w;
        vec2 span = hddaSlab(origin, invDir, lo, lo + vec3(size));
        float t0 = max(span.x, t), t1 = min(span.y, maxDistance);
        if (t1 <= t0) continue;   // the ray's remaining part misses this cascade
        float cell = size / float(cs.resolution);
        vec3 o = (origin - lo) / cell;
        HddaHit h = hddaWalk(c, cs.resolution, o, dir, t0 / cell, t1 / cell, maxSteps, steps);
        if (h.hit) {
            h.t *= cell;
            h.position = origin + dir * h.t;
            h.steps = steps;
            return h;
        }
        t = t1;
    }
    result.steps = steps;
    return result;
}
