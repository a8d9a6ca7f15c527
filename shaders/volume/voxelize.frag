// Voxelization, step 2: each fragment adds its surface sample to every voxel of its column that the
// triangle's plane crosses within the pixel (up to three: the dominant axis keeps the slope <= 1
// per axis), clipped to the triangle's depth extent. In the conservative modes fragments outside
// the triangle's box grown by half a pixel are dropped (the dilated triangle's sharp corners).
// Emission is weighted there by the part of the pixel the undilated triangle covers: conservative
// rasterization gives a 4 cm emitter every voxel it touches, and at full radiance those voxels would
// carry several times its power. Weighted, a voxel carries the emitters' power through its
// cross-section, so a small emitter lights the volume as a large one of equal power does.
#include "common.glsl"
#include "material.glsl"
#include "volume/voxel_sums.glsl"

in VoxelData {
    vec3 normal;
    vec2 uv;
    vec4 color;
} v_in;
flat in int g_axis;
flat in vec4 g_bounds;
flat in vec3 g_plane;
flat in vec2 g_depthRange;
flat in vec2 g_triangle[3];

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_CONSERVATIVE) uniform int u_conservative;
layout(location = UV_EMISSION_SCALE) uniform float u_emissionScale;
layout(location = UV_KEEP_LO) uniform ivec3 u_keepLo;   // a scrolled grid's moved cells: left alone
layout(location = UV_KEEP_HI) uniform ivec3 u_keepHi;

ivec3 unswizzleFromAxis(ivec3 s, int axis) { return axis == 0 ? s.zxy : axis == 1 ? s.yzx : s; }
vec3 unswizzleFromAxis(vec3 s, int axis) { return axis == 0 ? s.zxy : axis == 1 ? s.yzx : s; }

uint fixedPoint(float x) { return uint(clamp(x, 0.0, 1.0) * VOXEL_FIXED_ONE + 0.5); }

const int kClippedMax = 7;  // a triangle clipped by the four sides of a square has at most 7 corners

// Clips the polygon to the half-plane side * (p[axis] - bound) <= 0: one step of Sutherland and
// Hodgman 1974, "Reentrant polygon clipping" (CACM 17(1)). Returns the new corner count.
int clipToHalfPlane(inout vec2 poly[kClippedMax], int count, int axis, float bound, float side) {
    vec2 kept[kClippedMax];
    int n = 0;
    for (int i = 0; i < count; ++i) {
        vec2 p = poly[i], q = poly[(i + 1) % count];
        float dp = side * (p[axis] - bound), dq = side * (q[axis] - bound);
        if (dp <= 0.0 && n < kClippedMax) kept[n++] = p;
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0))
            if (n < kClippedMax) kept[n++] = mix(p, q, dp / (dp - dq));
    }
    poly = kept;
    return n;
}

// The fraction of the pixel at `corner` (its lower-left, in pixels) that the projected triangle
// covers: the triangle clipped to the pixel's square, its area by the shoelace formula. Corners are
// taken relative to the pixel, so the fraction of a tiny triangle far from the origin keeps its
// precision.
float pixelCoverage(vec2 corner) {
    vec2 poly[kClippedMax];
    for (int i = 0; i < 3; ++i) poly[i] = g_triangle[i] - corner;
    int n = clipToHalfPlane(poly, 3, 0, 0.0, -1.0);
    n = clipToHalfPlane(poly, n, 0, 1.0, 1.0);
    n = clipToHalfPlane(poly, n, 1, 0.0, -1.0);
    n = clipToHalfPlane(poly, n, 1, 1.0, 1.0);
    float twiceArea = 0.0;
    for (int i = 0; i < n; ++i) {
        vec2 p = poly[i], q = poly[(i + 1) % n];
        twiceArea += p.x * q.y - p.y * q.x;
    }
    return clamp(0.5 * abs(twiceArea), 0.0, 1.0);
}

void main() {
    vec4 base = materialBaseColor(v_in.uv, v_in.color);
    if (materialCutout(base.a)) discard;
    vec2 c = gl_FragCoord.xy;
    float depth = dot(g_plane.xy, c) + g_plane.z;
    float lo = depth, hi = depth;
    if (u_conservative != 0) {
        if (any(lessThan(c + 0.5, g_bounds.xy)) || any(greaterThan(c - 0.5, g_bounds.zw))) discard;
        float reach = 0.5 * (abs(g_plane.x) + abs(g_plane.y));  // depth change from centre to corner
        lo = max(depth - reach, g_depthRange.x);
        hi = min(depth + reach, g_depthRange.y);
    }
    int k0 = max(int(floor(lo)), 0), k1 = min(int(floor(hi)), u_resolution - 1);
    vec3 emission = max(u_emissive * texture(s_emissive, v_in.uv).rgb, vec3(0.0)) * u_emissionScale;
    bool emissive = any(greaterThan(emission, vec3(0.0)));
    // Plain rasterization already samples coverage at pixel centres (a pixel the triangle half
    // covers is hit half the time): its fragments count whole.
    float coverage = emissive && u_conservative != 0 ? pixelCoverage(floor(c)) : 1.0;
    float len2 = dot(v_in.normal, v_in.normal);
    vec3 n = len2 > 1e-20 ? v_in.normal * inversesqrt(len2) : vec3(0.0);
    // Emission and its coverage (channels 4-6 and 10) are set per voxel below: none for a surface
    // that does not emit.
    uint values[VOXEL_CHANNELS] = uint[VOXEL_CHANNELS](
        1u, fixedPoint(base.r), fixedPoint(base.g), fixedPoint(base.b), 0u, 0u, 0u, fixedPoint(n.x * 0.5 + 0.5),
        fixedPoint(n.y * 0.5 + 0.5), fixedPoint(n.z * 0.5 + 0.5), 0u, fixedPoint(abs(n.x)), fixedPoint(abs(n.y)),
        fixedPoint(abs(n.z)));
    for (int k = k0; k <= k1; ++k) {
        ivec3 voxel = unswizzleFromAxis(ivec3(ivec2(c), k), g_axis);
        if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, ivec3(u_resolution)))) continue;
        if (all(greaterThanEqual(voxel, u_keepLo)) && all(lessThan(voxel, u_keepHi))) continue;
        // Where in the voxel the sample lies along each axis, weighted by how squarely it faces that
        // axis: where a slab's faces lie (voxel_resolve.comp), the side of it a ray comes from.
        vec3 inVoxel = unswizzleFromAxis(vec3(fract(c), clamp(depth, max(lo, float(k)), min(hi, float(k + 1))) - float(k)), g_axis);
        for (int axis = 0; axis < 3; ++axis)
            atomicAdd(u_voxelPlaces[voxelPlaceIndex(voxel, u_resolution, axis)], fixedPoint(abs(n[axis]) * inVoxel[axis]));
        if (emissive) {
            // The pixel's coverage is its column's: a tilted emitter crosses up to three voxels of
            // it, each taking the share of the plane's depth range [lo, hi] that lies within it
            // (counted whole in each, the column carried the emitter's power once per voxel crossed).
            float share = hi - lo > 1e-6 ? clamp((min(hi, float(k + 1)) - max(lo, float(k))) / (hi - lo), 0.0, 1.0) : 1.0;
            values[4] = fixedPoint(emission.r * coverage * share);
            values[5] = fixedPoint(emission.g * coverage * share);
            values[6] = fixedPoint(emission.b * coverage * share);
            values[10] = fixedPoint(coverage * share);
        }
        for (int ch = 0; ch < VOXEL_CHANNELS; ++ch)
            atomicAdd(u_voxelSums[voxelSumIndex(voxel, u_resolution, ch)], values[ch]);
    }
}
