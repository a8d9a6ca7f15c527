#include "bvh.h"

#include <embree3/rtcore.h>
#include <embree3/rtcore_builder.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>
#include <memory>

namespace gis {

namespace {

// Embree builds its own pointer tree through these callbacks; we flatten it afterwards.
struct Node {
    virtual ~Node() = default;
    RTCBounds bounds[2] = {};
};
struct Inner final : Node {
    Node* children[2] = {nullptr, nullptr};
};
// Embree's allocator frees node memory without running destructors: nodes hold no heap memory.
constexpr unsigned kMaxLeafSize = 4;
struct Leaf final : Node {
    uint32_t primitives[kMaxLeafSize] = {};
    uint32_t count = 0;
};

void* createInner(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    void* mem = rtcThreadLocalAlloc(alloc, sizeof(Inner), 16);
    return static_cast<Node*>(new (mem) Inner);
}

void setChildren(void* node, void** children, unsigned int count, void*) {
    auto* inner = static_cast<Inner*>(static_cast<Node*>(node));
    for (unsigned int i = 0; i < count && i < 2; ++i) inner->children[i] = static_cast<Node*>(children[i]);
}

void setBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    auto* inner = static_cast<Inner*>(static_cast<Node*>(node));
    for (unsigned int i = 0; i < count && i < 2; ++i) inner->bounds[i] = *bounds[i];
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
    void* mem = rtcThreadLocalAlloc(alloc, sizeof(Leaf), 16);
    auto* leaf = new (mem) Leaf;
    for (size_t i = 0; i < count && i < kMaxLeafSize; ++i) leaf->primitives[leaf->count++] = prims[i].primID;
    return static_cast<Node*>(leaf);
}

double area(const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
    return 2.0 * (double(e.x) * e.y + double(e.y) * e.z + double(e.z) * e.x);
}

glm::vec3 lower(const RTCBounds& b) { return {b.lower_x, b.lower_y, b.lower_z}; }
glm::vec3 upper(const RTCBounds& b) { return {b.upper_x, b.upper_y, b.upper_z}; }

}  // namespace

std::vector<TraceTriangle> worldTriangles(const Scene& scene) {
    std::vector<TraceTriangle> tris;
    for (size_t d = 0; d < scene.draws.size(); ++d) {
        const Primitive& p = scene.primitives[scene.draws[d].primitive];
        const glm::mat4& m = scene.draws[d].world;
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            TraceTriangle t;
            t.p0 = glm::vec3(m * glm::vec4(p.vertices[p.indices[i]].position, 1.0f));
            t.p1 = glm::vec3(m * glm::vec4(p.vertices[p.indices[i + 1]].position, 1.0f));
            t.p2 = glm::vec3(m * glm::vec4(p.vertices[p.indices[i + 2]].position, 1.0f));
            t.draw = int(d);
            t.primitiveTriangle = uint32_t(i / 3);
            tris.push_back(t);
        }
    }
    return tris;
}

namespace {
// No triangles: a root no ray reaches, so every ray misses and sees the background. It sits far
// beyond the longest ray the tracers cast (1e30), and traversal stops at the root's bounds test
// before it would read the children an interior node points to.
Bvh emptyBvh() {
    Bvh bvh;
    bvh.nodes.push_back({glm::vec3(1e38f), 0u, glm::vec3(1e38f), 0u});
    return bvh;
}
}  // namespace

Bvh buildBvh(const Scene& scene) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<TraceTriangle> tris = worldTriangles(scene);
    if (tris.empty()) return emptyBvh();

    std::vector<RTCBuildPrimitive> prims(tris.size());
    for (size_t i = 0; i < tris.size(); ++i) {
        const glm::vec3 lo = glm::min(tris[i].p0, glm::min(tris[i].p1, tris[i].p2));
        const glm::vec3 hi = glm::max(tris[i].p0, glm::max(tris[i].p1, tris[i].p2));
        prims[i] = {lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, uint32_t(i)};
    }

    std::unique_ptr<RTCDeviceTy, void (*)(RTCDevice)> device(rtcNewDevice("threads=1"), rtcReleaseDevice);
    if (!device) throw Error("Embree: cannot create a device");
    std::unique_ptr<RTCBVHTy, void (*)(RTCBVH)> bvhHandle(rtcNewBVH(device.get()), rtcReleaseBVH);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = RTC_BUILD_QUALITY_HIGH;
    args.maxBranchingFactor = 2;
    args.maxDepth = 64;
    args.minLeafSize = 1;
    args.maxLeafSize = kMaxLeafSize;
    args.traversalCost = 1.0f;
    args.intersectionCost = 1.0f;
    args.bvh = bvhHandle.get();
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.createNode = createInner;
    args.setNodeChildren = setChildren;
    args.setNodeBounds = setBounds;
    args.createLeaf = createLeaf;
    Node* root = static_cast<Node*>(rtcBuildBVH(&args));
    if (!root) throw Error("Embree: BVH build failed (error " + std::to_string(rtcGetDeviceError(device.get())) + ")");

    // Flatten depth-first; the children of an interior node get two adjacent slots.
    Bvh bvh;
    bvh.nodes.push_back({});
    glm::vec3 rootLo(1e30f), rootHi(-1e30f);
    for (const TraceTriangle& t : tris) {
        rootLo = glm::min(rootLo, glm::min(t.p0, glm::min(t.p1, t.p2)));
        rootHi = glm::max(rootHi, glm::max(t.p0, glm::max(t.p1, t.p2)));
    }
    const double rootArea = std::max(area(rootLo, rootHi), 1e-30);
    std::function<void(const Node*, uint32_t, glm::vec3, glm::vec3, int)> flatten =
        [&](const Node* node, uint32_t slot, glm::vec3 lo, glm::vec3 hi, int depth) {
            bvh.depth = std::max(bvh.depth, depth);
            bvh.nodes[slot].boundsMin = lo;
            bvh.nodes[slot].boundsMax = hi;
            const double relArea = area(lo, hi) / rootArea;
            if (const auto* leaf = dynamic_cast<const Leaf*>(node)) {
                bvh.nodes[slot].leftOrFirst = uint32_t(bvh.triangles.size());
                bvh.nodes[slot].triangleCount = leaf->count;
                for (uint32_t i = 0; i < leaf->count; ++i) bvh.triangles.push_back(tris[leaf->primitives[i]]);
                bvh.sahCost += relArea * double(leaf->count) * args.intersectionCost;
                ++bvh.leafCount;
                return;
            }
            const auto* inner = static_cast<const Inner*>(node);
            const uint32_t left = uint32_t(bvh.nodes.size());
            bvh.nodes.resize(bvh.nodes.size() + 2);
            bvh.nodes[slot].leftOrFirst = left;
            bvh.nodes[slot].triangleCount = 0;
            bvh.sahCost += relArea * args.traversalCost;
            for (int c = 0; c < 2; ++c)
                flatten(inner->children[c], left + c, lower(inner->bounds[c]), upper(inner->bounds[c]), depth + 1);
        };
    flatten(root, 0, rootLo, rootHi, 1);
    bvh.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

namespace {
// Slab test: whether the ray enters [lo, hi] before `tMax`.
bool hitsBox(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& origin, const glm::vec3& inverseDir, float tMax) {
    const glm::vec3 a = (lo - origin) * inverseDir, b = (hi - origin) * inverseDir;
    const glm::vec3 near = glm::min(a, b), far = glm::max(a, b);
    const float enter = std::max({near.x, near.y, near.z, 0.0f}), leave = std::min({far.x, far.y, far.z, tMax});
    return enter <= leave;
}

// Moller and Trumbore 1997, both faces; +inf on a miss.
float hitTriangle(const TraceTriangle& t, const glm::vec3& origin, const glm::vec3& dir) {
    const glm::vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (!(std::abs(det) > 0.0f)) return std::numeric_limits<float>::infinity();
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - t.p0;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return std::numeric_limits<float>::infinity();
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return std::numeric_limits<float>::infinity();
    const float d = glm::dot(e2, q) * inv;
    return d > 0.0f ? d : std::numeric_limits<float>::infinity();
}
}  // namespace

float nearestHit(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& dir) {
    float best = std::numeric_limits<float>::infinity();
    if (bvh.triangles.empty()) return best;
    const glm::vec3 inverseDir = 1.0f / dir;  // +-inf on an axis the ray runs along: the slabs still hold
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
        const BvhNode& node = bvh.nodes[stack.back()];
        stack.pop_back();
        if (!hitsBox(node.boundsMin, node.boundsMax, origin, inverseDir, best)) continue;
        if (node.triangleCount == 0) {
            stack.push_back(node.leftOrFirst);
            stack.push_back(node.leftOrFirst + 1);
            continue;
        }
        for (uint32_t i = 0; i < node.triangleCount; ++i)
            best = std::min(best, hitTriangle(bvh.triangles[node.leftOrFirst + i], origin, dir));
    }
    return best;
}

}  // namespace gis
