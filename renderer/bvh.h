// Bounding volume hierarchy over the scene's world-space triangles, for ray tracing on the GPU
// (path tracer, ray-traced AO). Built on the CPU with Embree's SAH builder (rtcBuildBVH), then
// flattened into a binary tree whose nodes are 32 bytes and whose two children sit side by side,
// so the shader needs one index per interior node.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/storage_struct.h"
#include "scene/scene.h"

namespace gis {

// A node as shaders/bvh.glsl reads it. leftOrFirst: interior, the index of the left child (right =
// left + 1); leaf, its first triangle. triangleCount: 0 for an interior node.
#define GIS_BVH_NODE(M) M(vec3, boundsMin) M(uint, leftOrFirst) M(vec3, boundsMax) M(uint, triangleCount)
GIS_STORAGE_STRUCT(BvhNode, GIS_BVH_NODE)

struct TraceTriangle {       // world space; one per scene triangle, in leaf order
    glm::vec3 p0, p1, p2;
    int draw = 0;            // index into Scene::draws
    uint32_t primitiveTriangle = 0;  // triangle index within the draw's primitive
};

struct Bvh {
    std::vector<BvhNode> nodes;          // nodes[0] is the root
    std::vector<TraceTriangle> triangles;
    double buildMs = 0.0;
    // SAH cost of the tree: traversal cost 1 per interior node visited, intersection cost 1 per
    // triangle, each weighted by the node's surface area relative to the root's.
    double sahCost = 0.0;
    int depth = 0;
    int leafCount = 0;
};

// Every draw's triangles in world space, in draw order (the BVH builder's input; the shared scene
// triangles of renderer/services use the same list, so both agree triangle for triangle).
std::vector<TraceTriangle> worldTriangles(const Scene& scene);

// Throws gis::Error when Embree fails. A scene without triangles gets a tree every ray misses
// (one root node, no triangles).
Bvh buildBvh(const Scene& scene);

// The distance along `dir` (unit length) from `origin` to the nearest triangle, either face; +inf
// when the ray leaves the scene. The tree the shaders walk, walked on the CPU, for the few rays a
// host-side choice needs (the cascades' view depth, volume/volume_cascades.h).
float nearestHit(const Bvh& bvh, const glm::vec3& origin, const glm::vec3& dir);

}  // namespace gis
