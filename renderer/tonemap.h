// Exposure, tone mapping and sRGB transfer on the CPU: the one C++ copy of what
// shaders/tonemap.frag and common.glsl do on the GPU (a test renders a PNG and an EXR of the same
// frame and checks that this code turns the EXR into the PNG). Change both together.
#pragma once

#include <glm/glm.hpp>

#include "image.h"
#include "render_settings.h"  // Tonemapper

namespace gis {

// How linear radiance becomes a display image: scale by 2^exposureEV, then the tone mapper
// (ACES fitted, or a clamp to [0, 1]), then the sRGB transfer function.
struct DisplaySettings {
    Tonemapper tonemap = Tonemapper::Aces;
    float exposureEV = 0.0f;
};

// IEC 61966-2-1 transfer functions; the input is clamped to [0, 1] first.
float linearToSrgb(float c);
float srgbToLinear(float c);

// Stephen Hill's fit of the ACES RRT+ODT (BakingLab), linear sRGB in, linear [0, 1] out.
glm::vec3 acesFitted(glm::vec3 c);

// Radiance -> display-referred linear RGB in [0, 1] (tone mapped, not yet sRGB-encoded).
// NaN and Inf become 0, as in the shader.
glm::vec3 toneMap(glm::vec3 radiance, const DisplaySettings& display);

// Whole images (alpha is carried over unchanged).
ImageF toneMapImage(const ImageF& radiance, const DisplaySettings& display);        // linear [0, 1]
ImageF encodeSrgbImage(const ImageF& displayLinear);                                // sRGB-encoded [0, 1]
ImageU8 toLdrImage(const ImageF& radiance, const DisplaySettings& display);         // what the tonemap pass writes
ImageF decodeSrgbImage(const ImageU8& srgb);  // 8-bit sRGB (e.g. a PNG) -> linear float, alpha / 255

}  // namespace gis
