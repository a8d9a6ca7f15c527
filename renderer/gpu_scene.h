// The scene on the GPU: one vertex and one index buffer for every primitive, material textures,
// and a draw list. Charged to "scene" in the memory ledger. Built once; passes only read it.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "scene/scene.h"

namespace gis {

struct GpuDraw {
    GLsizei indexCount = 0;
    GLuint firstIndex = 0;
    GLint baseVertex = 0;
    int material = 0;               // into GpuScene::materials (a default material is appended)
    glm::mat4 world{1.0f};
    glm::mat3 normalMatrix{1.0f};   // inverse transpose of world's upper 3x3
};

struct GpuMaterial {
    Material params;
    GLuint baseColor = 0, metallicRoughness = 0, normal = 0, emissive = 0, occlusion = 0;  // never 0 after upload
    // The textures the material has (the others are a 1x1 white), one bit each in material.glsl's
    // MATERIAL_*_TEXTURE order: base colour 1, metallic-roughness 2, normal 4, emissive 8, occlusion 16.
    unsigned textures = 0;
};

struct GpuScene {
    GpuScene(const Scene& scene, gl::MemoryLedger& ledger);
    const Scene& cpu;
    gl::Object vao;
    gl::Buffer vertices, indices;
    std::vector<gl::Texture> textures;   // scene images, then the 1x1 defaults
    gl::Object sampler;
    std::vector<GpuMaterial> materials;
    std::vector<GpuDraw> draws;
};

}  // namespace gis
