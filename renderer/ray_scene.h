// The scene uploaded for GPU ray tracing (shaders/ray_scene.glsl): the BVH and its triangles in
// leaf order, per-triangle shading attributes, materials, every texture in one array, and the
// emissive triangles with their power-proportional selection probabilities. Built once per
// renderer and shared by the ray-tracing passes (path tracer, ray-traced AO).
#pragma once

#include <string>

#include "bvh.h"
#include "gpu_scene.h"

namespace gis {

struct RayScene {
    RayScene(const GpuScene& scene, gl::MemoryLedger& ledger, const std::string& owner);
    // SSBO bindings 0 (lights) to 5 (emitters), texture unit 0 (the texture array).
    void bind() const;

    Bvh bvh;
    gl::Buffer lights, nodes, triangles, attributes, materials, emitters;
    gl::Texture textures;
    gl::Object sampler;
    size_t emitterCount = 0;
};

}  // namespace gis
