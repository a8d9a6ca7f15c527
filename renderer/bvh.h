// Bounding volume hierarchy over the scene's world-space triangles, for ray tracing on the GPU
// (path tracer, ray-traced AO). Built on the CPU with Embree's SAH builder (rtcBuildBVH), then
// flattened into a binary tree whose nodes are 32 bytes and whose two children sit side by side,
// so the shader needs one index per interior node.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace gis {

struct BvhNode {             // std430 layout, mirrors shaders/bvh.glsl
    glm::vec3 boundsMin;
    uint32_t leftOrFirst;    // interior: index of the left child (right = left + 1); leaf: first triangle
    glm::vec3 boundsMax;
    uint32_t triangleCount;  // 0 = interior node
};

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

}  // namespace gis
