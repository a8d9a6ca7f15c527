// The scene as ray tracers see it (renderer/ray_scene.h): BVH and triangles (bvh.glsl), per-triangle
// shading attributes, materials, one texture array, emissive triangles; and what every tracer needs
// at a hit - position, normals facing the ray, texture coordinates - plus alpha cut-outs.
#include "common.glsl"
#include "bvh.glsl"
#include "sampling.glsl"

// The structs (what each member holds) and binding points are declared in renderer/ray_scene.h.
STRUCT_TriangleAttributes
STRUCT_RayMaterial
STRUCT_Emitter

layout(std430, binding = RAY_ATTRIBUTES_BINDING) readonly buffer Attributes { TriangleAttributes u_attributes[]; };
layout(std430, binding = RAY_MATERIALS_BINDING) readonly buffer Materials { RayMaterial u_materials[]; };
layout(std430, binding = RAY_EMITTERS_BINDING) readonly buffer Emitters { Emitter u_emitters[]; };
// The texture array's unit: 0 unless the including shader needs unit 0 for its own (RayScene::bind).
#ifndef RAY_SCENE_TEXTURE_UNIT
#define RAY_SCENE_TEXTURE_UNIT 0
#endif
layout(binding = RAY_SCENE_TEXTURE_UNIT) uniform sampler2DArray s_textures;


vec4 sampleLayer(int layer, vec2 uv) {
    return layer < 0 ? vec4(1.0) : textureLod(s_textures, vec3(uv, float(layer)), 0.0);
}

vec2 triangleUv(TriangleAttributes a, vec2 b) {
    return a.uv01.xy * (1.0 - b.x - b.y) + a.uv01.zw * b.x + a.uv2MaterialEmitter.xy * b.y;
}

bool bvhTriangleIsSingleSided(uint triangle) {
    return u_materials[int(u_attributes[triangle].uv2MaterialEmitter.z)].emissive.w < 0.5;
}

bool bvhTriangleIsCutout(uint triangle, vec2 barycentric) {
    TriangleAttributes a = u_attributes[triangle];
    RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
    if (m.params.w < 0.0) return false;
    vec4 color = a.c0 * (1.0 - barycentric.x - barycentric.y) + a.c1 * barycentric.x + a.c2 * barycentric.y;
    return m.baseColor.a * color.a * sampleLayer(m.textures.x, triangleUv(a, barycentric)).a < m.params.w;
}

// Picks one of `count` emissive triangles in proportion to its power (binary search in the CDF).
uint pickEmitter(float u, int count) {
    int lo = 0, hi = count - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (u_emitters[mid].cdf < u) lo = mid + 1;
        else hi = mid;
    }
    return u_emitters[lo].triangle;
}

// The scene's size: the largest coordinate magnitude of the BVH root's box (at least a tiny
// positive number, for a degenerate scene).
float sceneExtent() {
    vec3 m = max(abs(u_nodes[0].boundsMin), abs(u_nodes[0].boundsMax));
    return max(max(m.x, m.y), max(m.z, 1e-30));
}

// Moves a ray origin off its surface by a few units in the last place of each coordinate, so
// the offset scales with the magnitude of the position (huge scenes) yet never vanishes near
// the origin (tiny scenes). After Waechter and Binder, Ray Tracing Gems ch. 6 (2019), with one
// change: their constants assume a scene of unit size (the fixed offset near the origin is
// 1/65536 of a unit), so here both the near-origin region and its offset are scaled by the
// scene's extent; a Cornell box scaled by 1e-3 otherwise moved rays by 0.75% of its size and
// rendered 15% darker.
vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const float INT_SCALE = 256.0;
    float extent = sceneExtent();
    float origin = extent / 32.0, floatScale = extent / 65536.0;
    ivec3 ofs = ivec3(INT_SCALE * n);
    vec3 q;
    for (int i = 0; i < 3; ++i) {
        int bits = floatBitsToInt(p[i]) + (p[i] < 0.0 ? -ofs[i] : ofs[i]);
        q[i] = abs(p[i]) < origin ? p[i] + floatScale * n[i] : intBitsToFloat(bits);
    }
    return q;
}

// The origin of a ray leaving a G-buffer position P (normal N) seen from `camera`: reconstructed
// from depth, P may lie a few depth-buffer steps behind its surface, a distance that grows with the
// distance to the camera; so the origin first moves off by a small fraction of that distance, then
// by offsetRayOrigin's few ulps.
vec3 gbufferRayOrigin(vec3 P, vec3 N, vec3 camera) {
    return offsetRayOrigin(P + N * (2e-4 * length(camera - P)), N);
}

struct RayHitGeometry {
    vec3 position;
    vec3 geometricNormal;     // faces the incoming ray
    vec3 normal;              // shading normal (normal map applied), same hemisphere as geometricNormal
    vec3 weights;             // barycentric weights of the three corners
    vec2 uv;
    bool frontFace;           // the ray hit the side the winding faces
};

RayHitGeometry hitGeometry(Hit hit, vec3 rayDir) {
    TraceTriangle tri = u_triangles[hit.triangle];
    TriangleAttributes a = u_attributes[hit.triangle];
    RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
    RayHitGeometry g;
    vec3 w = vec3(1.0 - hit.barycentric.x - hit.barycentric.y, hit.barycentric);
    g.weights = w;
    g.uv = triangleUv(a, hit.barycentric);
    g.position = tri.p0.xyz * w.x + tri.p1.xyz * w.y + tri.p2.xyz * w.z;
    vec3 ng = cross(tri.p1.xyz - tri.p0.xyz, tri.p2.xyz - tri.p0.xyz);
    ng = dot(ng, ng) > 0.0 ? normalize(ng) : -rayDir;
    g.frontFace = dot(ng, rayDir) < 0.0;
    g.geometricNormal = g.frontFace ? ng : -ng;

    vec3 n = a.n0.xyz * w.x + a.n1.xyz * w.y + a.n2.xyz * w.z;
    n = dot(n, n) > 1e-20 ? normalize(n) : ng;
    if (m.textures.z >= 0) {
        vec3 t = a.t0.xyz * w.x + a.t1.xyz * w.y + a.t2.xyz * w.z;
        t -= n * dot(n, t);
        if (dot(t, t) > 1e-20) {
            t = normalize(t);
            vec3 b = cross(n, t) * (a.t0.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = sampleLayer(m.textures.z, g.uv).xyz * 2.0 - 1.0;
            tn.xy *= m.params2.x;
            vec3 mapped = mat3(t, b, n) * tn;
            if (dot(mapped, mapped) > 1e-20) n = normalize(mapped);
        }
    }
    // Shade the side the ray arrives on (surfaces are two-sided for reflection, as in Cycles).
    g.normal = dot(n, g.geometricNormal) < 0.0 ? -n : n;
    return g;
}

// The base colour at a hit: the material's factor x the vertex colour x the texture.
vec3 hitBaseColor(Hit hit, RayHitGeometry g) {
    TriangleAttributes a = u_attributes[hit.triangle];
    RayMaterial m = u_materials[int(a.uv2MaterialEmitter.z)];
    vec4 color = a.c0 * g.weights.x + a.c1 * g.weights.y + a.c2 * g.weights.z;
    return saturate(m.baseColor.rgb * color.rgb * srgbToLinear(sampleLayer(m.textures.x, g.uv).rgb));
}
