// Renders `--gi vct` through the renderer (registry, lighting contract) and hands back what the VCT
// tests look at: the frame, the contract's terms, the voxel grid, the sub-step timings.
#pragma once

#include <string>
#include <vector>

#include "gi/vct/vct_pass.h"
#include "gi_reference.h"
#include "image.h"
#include "renderer.h"

namespace gis::test {

struct VctImages {
    ImageF frame;      // the renderer's radiance (or the debug view, with settings.view)
    ImageF diffuse;    // indirect.diffuse (E / pi)
    ImageF specular;   // indirect.specular
    ImageF indirect;   // diffuse albedo * indirect.diffuse: the contract's diffuse term, on the CPU
    std::map<std::string, double> stepMs;    // "voxelize", "inject", "mips", "bounce", "trace": first-frame ms
    bool cachedSecondFrame = false;          // the second frame reused voxels and injection
    int resolution = 0;
    std::vector<float> radiance;             // level 0 of the voxel radiance, RGBA, x fastest
    std::vector<uint8_t> albedo, normal;     // the voxel grid, RGBA8
};

// settings.gi is set to "vct"; "vct.*" parameters come from settings.params.
VctImages renderVct(const Scene& scene, RenderSettings settings, int frames = 1);

// The renderer's VCT pass (throws where it has none).
const VctPass& vctPassOf(const Renderer& r);

// Sets "vct.KEY" to `text` (validated by the registry).
void setVct(RenderSettings& s, const std::string& key, const std::string& text);

// A lambertian quad 1 m in front of a wall, an emitter on its back lighting the wall: the
// reduced-resolution methods' (VCT's and SDF GI's) upsampling tests look for light across the step.
Scene depthStepScene();




}  // namespace gis::test
