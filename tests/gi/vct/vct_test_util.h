// Drives VCT without the method registry: shadow, G-buffer and VCT passes run by hand, and the
// lighting contract applied on the CPU (indirect radiance = diffuse albedo * indirect.diffuse),
// so the indirect term can be compared with the path tracer's on its own.
#pragma once

#include "gi/vct/vct_pass.h"
#include "image.h"
#include "renderer.h"

namespace gis::test {

struct VctImages {
    ImageF diffuse;    // indirect.diffuse (E / pi)
    ImageF specular;   // indirect.specular
    ImageF ao;         // r = ao
    ImageF indirect;   // diffuse albedo * indirect.diffuse: the outgoing indirect radiance (Lambert)
    ImageF debug;      // "vct.voxels" or "vct.slice" when the settings ask for one
    double stepMs[VctPass::StepCount] = {};  // median GPU ms of each sub-step over the frames that ran it
    bool cachedSecondFrame = false;          // the second frame reused voxels and injection
    int resolution = 0;
    std::vector<float> radiance;             // level 0 of the voxel radiance, RGBA, x fastest
    std::vector<uint8_t> albedo, normal;     // the voxel grid, RGBA8
};

// Renders `frames` frames (>= 1) of VCT at settings' size and camera.
VctImages renderVct(const Scene& scene, const RenderSettings& settings, const VctSettings& vct, int frames = 1);

// Multiplies a scene's geometry, camera and lights by `scale` (light intensities by scale^2, so
// irradiance, and with it every image, stays the same).
Scene scaledScene(const Scene& scene, float scale);

ImageF add(const ImageF& a, const ImageF& b);
ImageF subtract(const ImageF& a, const ImageF& b);

}  // namespace gis::test
