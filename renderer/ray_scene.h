// The scene uploaded for GPU ray tracing (shaders/ray_scene.glsl): the BVH and its triangles in
// leaf order, per-triangle shading attributes, materials, every texture in one array, and the
// emissive triangles with their power-proportional selection probabilities. Built once per
// renderer, on first use, by SceneServices and shared by every ray-tracing pass.
#pragma once

#include <string>

#include "bvh.h"
#include "gpu_scene.h"

namespace gis {

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
