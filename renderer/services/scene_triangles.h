// The whole scene's triangles in world space on the GPU, one SSBO, with a material table: what
// voxelization by compute, jump-flood seeding and probe rays read (shaders/scene_triangles.glsl
// declares the same layout). Built once per renderer from the same flattening as the BVH
// (worldTriangles), so triangle i here is triangle i of that list.
#pragma once

#include <vector>

#include "gl/gl.h"
#include "gpu_scene.h"

namespace gis {

struct SceneTriangle {       // std430, mirrors shaders/scene_triangles.glsl
    glm::vec4 p0;            // xyz world position; w = material index (exact as a float below 2^24)
    glm::vec4 p1;            // xyz; w = draw index
    glm::vec4 p2;            // xyz; w = triangle index within the draw's primitive
    glm::vec4 normal;        // xyz unit geometric normal (0 for a degenerate triangle); w = area
};

struct SceneTriangleMaterial {  // std430
    glm::vec4 baseColor;     // linear base colour factor (textures are not folded in)
    glm::vec4 emission;      // rgb emitted radiance; w = 1 if double sided
    glm::vec4 params;        // metallic, roughness, specular factor, alpha cutoff (<0: opaque)
};

struct SceneTriangles {
    // Charged to "scene.triangles". An empty scene gets one zero-area placeholder triangle so the
    // buffers are never of size zero (count stays 0).
    SceneTriangles(const GpuScene& scene, gl::MemoryLedger& ledger);
    // SSBO bindings: triangles, then materials.
    void bind(GLuint triangleBinding, GLuint materialBinding) const;

    std::vector<SceneTriangle> cpu;  // what was uploaded (the tests and CPU fallbacks read it)
    gl::Buffer triangles, materials;
    size_t count = 0;
    size_t materialCount = 0;
};

}  // namespace gis
