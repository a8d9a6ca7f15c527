// The scene uploaded for GPU ray tracing (shaders/ray_scene.glsl): the BVH and its triangles in
// leaf order, per-triangle shading attributes, materials, every texture in one array, and the
// emissive triangles with their power-proportional selection probabilities. Built once per
// renderer, on first use, by SceneServices and shared by every ray-tracing pass.
#pragma once

#include <string>

#include "bvh.h"
#include "gl/storage_struct.h"
#include "gpu_scene.h"
#include "ray_counts.h"

namespace gis {

// The storage buffers' element types (shaders/bvh.glsl, shaders/ray_scene.glsl).
namespace rays {
// World-space corners (w unused), in the BVH's leaf order.
#define GIS_TRACE_TRIANGLE(M) M(vec4, p0) M(vec4, p1) M(vec4, p2)
GIS_STORAGE_STRUCT(TraceTriangle, GIS_TRACE_TRIANGLE)
// Shading normals, tangents (w = bitangent sign) and vertex colours of the three corners; uv0 and
// uv1; uv2, material index, emitter selection pdf / triangle area (0: not an emitter).
#define GIS_TRIANGLE_ATTRIBUTES(M)                                                                       \
    M(vec4, n0) M(vec4, n1) M(vec4, n2) M(vec4, t0) M(vec4, t1) M(vec4, t2) M(vec4, c0) M(vec4, c1) M(vec4, c2) \
        M(vec4, uv01) M(vec4, uv2MaterialEmitter)
GIS_STORAGE_STRUCT(TriangleAttributes, GIS_TRIANGLE_ATTRIBUTES)
// emissive: rgb radiance, w = double sided; params: metallic, roughness, specular factor, alpha
// cutoff (< 0: opaque); params2: normal scale, unused; textures: texture-array layers of base
// colour, metallic-roughness, normal, emissive (-1: none).
#define GIS_RAY_MATERIAL(M) M(vec4, baseColor) M(vec4, emissive) M(vec4, params) M(vec4, params2) M(ivec4, textures)
GIS_STORAGE_STRUCT(RayMaterial, GIS_RAY_MATERIAL)
// cdf: the inclusive running sum of selection probabilities.
#define GIS_EMITTER(M) M(uint, triangle) M(float, cdf) M(float, pad0) M(float, pad1)
GIS_STORAGE_STRUCT(Emitter, GIS_EMITTER)
}  // namespace rays

// The storage-buffer binding points of RayScene::bind() (the lights' is kLightsBinding).
constexpr int kBvhNodesBinding = 1, kBvhTrianglesBinding = 2, kRayAttributesBinding = 3, kRayMaterialsBinding = 4,
              kRayEmittersBinding = 5;
// The path tracer's ray counts (shaders/path_tracer.glsl: 3 x (low, high) uint), which its passes bind.
constexpr int kRayCountsBinding = 6;
gl::Buffer createRayCounts(const gl::MemoryScope& scope);  // zeroed
RayCounts readRayCounts(const gl::Buffer& counts);         // the counts so far (a GPU sync)

struct RayScene {
    RayScene(const GpuScene& scene, gl::MemoryLedger& ledger, const std::string& owner);
    // SSBO bindings 0 (lights) to 5 (emitters), the texture array at `textureUnit`
    // (ray_scene.glsl's RAY_SCENE_TEXTURE_UNIT).
    void bind(GLuint textureUnit = 0) const;
    // The scene's lights were edited: uploads them again (the BVH and materials stay).
    void updateLights(const Scene& scene);

    Bvh bvh;
    gl::Buffer lights, nodes, triangles, attributes, materials, emitters;
    gl::Texture textures;
    gl::Object sampler;
    size_t emitterCount = 0;

private:
    gl::MemoryScope scope_;
};

// What the progressive ray tracers share: one sample per pixel per dispatch, summed in `sum`,
// with `mean` (image unit 1) the image so far, until `target` samples are in.
struct SampleAccumulator {
    SampleAccumulator(const gl::MemoryScope& scope, int width, int height, int target, int perFrame);
    // Binds the images (units 0 and 1) and dispatches this frame's batch of `program`, one sample
    // each (U_SAMPLE_INDEX = samples done so far).
    void runBatch(GLuint program);
    bool finished() const { return done >= target; }

    gl::Texture sum, mean;
    int done = 0, target = 0, perFrame = 1;
};

}  // namespace gis
