// Ray queries against the scene's BVH (renderer/bvh.h): closest hit and any hit. Traversal uses a
// short fixed stack (BVH_STACK_SIZE entries, nearer child first); Embree's builder caps the depth at
// 64 and a binary SAH tree for the scenes here stays far shallower, so the stack cannot overflow
// in practice, and if it ever would, the ray reports what it found so far instead of reading past
// the array. A stackless (parent-pointer) traversal would avoid the bound but costs extra node
// visits; this short stack is simpler and faster on llvmpipe and GPUs alike.
#define BVH_STACK_SIZE 64

// The structs and binding points are declared in renderer/bvh.h and renderer/ray_scene.h.
STRUCT_BvhNode
STRUCT_TraceTriangle

layout(std430, binding = BVH_NODES_BINDING) readonly buffer BvhNodes { BvhNode u_nodes[]; };
layout(std430, binding = BVH_TRIANGLES_BINDING) readonly buffer BvhTriangles { TraceTriangle u_triangles[]; };

struct Hit {
    float t;
    uint triangle;   // index into u_triangles
    vec2 barycentric;
};

// Slab test; returns the entry distance (>= 0) or -1 for a miss. (A miss was once a large finite
// distance, which a ray with a larger tMax took for a hit: such a ray visited every node.)
float intersectAabb(vec3 lo, vec3 hi, vec3 origin, vec3 invDir, float tMax) {
    vec3 t0 = (lo - origin) * invDir, t1 = (hi - origin) * invDir;
    vec3 tmin = min(t0, t1), tmax = max(t0, t1);
    float enter = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
    float exit = min(min(tmax.x, tmax.y), min(tmax.z, tMax));
    return enter <= exit ? enter : -1.0;
}

// Moller-Trumbore 1997. Returns t (or -1) and barycentrics of p1, p2. frontFace: the ray meets
// the side p0 -> p1 -> p2 winds counter-clockwise around (det = -dot(dir, e1 x e2) > 0).
float intersectTriangle(TraceTriangle tri, vec3 origin, vec3 dir, out vec2 bary, out bool frontFace) {
    vec3 e1 = tri.p1.xyz - tri.p0.xyz, e2 = tri.p2.xyz - tri.p0.xyz;
    vec3 p = cross(dir, e2);
    float det = dot(e1, p);
    bary = vec2(0.0);
    frontFace = det > 0.0;
    if (abs(det) < 1e-30) return -1.0;  // ray parallel to the plane, or a degenerate triangle
    float invDet = 1.0 / det;
    vec3 s = origin - tri.p0.xyz;
    float u = dot(s, p) * invDet;
    if (u < 0.0 || u > 1.0) return -1.0;
    vec3 q = cross(s, e1);
    float v = dot(dir, q) * invDet;
    if (v < 0.0 || u + v > 1.0) return -1.0;
    bary = vec2(u, v);
    return dot(e2, q) * invDet;
}

// Supplied by the including shader: alpha-mask cut-outs (true = the ray passes through), and
// whether a triangle is single-sided (glTF doubleSided: false).
bool bvhTriangleIsCutout(uint triangle, vec2 barycentric);
bool bvhTriangleIsSingleSided(uint triangle);

// anyHit = true stops at the first hit (shadow rays). cullBackFaces: the ray passes through the
// back of single-sided triangles, as the rasterizer culls them (glTF's rule; camera rays).
bool traceRay(vec3 origin, vec3 dir, float tMax, bool anyHit, bool cullBackFaces, out Hit hit) {
    vec3 invDir = 1.0 / dir;  // IEEE: 1/0 = inf, which the slab test handles
    hit.t = tMax;
    hit.triangle = 0u;
    hit.barycentric = vec2(0.0);
    bool found = false;
    uint stack[BVH_STACK_SIZE];
    int sp = 0;
    if (intersectAabb(u_nodes[0].boundsMin, u_nodes[0].boundsMax, origin, invDir, tMax) < 0.0) return false;
    stack[sp++] = 0u;
    while (sp > 0) {
        BvhNode node = u_nodes[stack[--sp]];
        if (node.triangleCount > 0u) {
            for (uint i = 0u; i < node.triangleCount; ++i) {
                uint ti = node.leftOrFirst + i;
                vec2 bary;
                bool front;
                float t = intersectTriangle(u_triangles[ti], origin, dir, bary, front);
                if (t > 0.0 && t < hit.t && !(cullBackFaces && !front && bvhTriangleIsSingleSided(ti)) &&
                    !bvhTriangleIsCutout(ti, bary)) {
                    hit.t = t;
                    hit.triangle = ti;
                    hit.barycentric = bary;
                    found = true;
                    if (anyHit) return true;
                }
            }
            continue;
        }
        uint left = node.leftOrFirst, right = left + 1u;
        float dl = intersectAabb(u_nodes[left].boundsMin, u_nodes[left].boundsMax, origin, invDir, hit.t);
        float dr = intersectAabb(u_nodes[right].boundsMin, u_nodes[right].boundsMax, origin, invDir, hit.t);
        if (sp + 2 > BVH_STACK_SIZE) break;
        // Push the farther child first so the nearer one is visited next.
        bool hitLeft = dl >= 0.0 && dl <= hit.t, hitRight = dr >= 0.0 && dr <= hit.t;
        if (hitLeft && hitRight) {
            stack[sp++] = dl < dr ? right : left;
            stack[sp++] = dl < dr ? left : right;
        } else if (hitLeft) {
            stack[sp++] = left;
        } else if (hitRight) {
            stack[sp++] = right;
        }
    }
    return found;
}

bool traceRay(vec3 origin, vec3 dir, float tMax, bool anyHit, out Hit hit) {
    return traceRay(origin, dir, tMax, anyHit, false, hit);
}
