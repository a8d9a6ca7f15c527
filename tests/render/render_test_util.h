// Shared by the in-process rendering tests: one headless GL context for the whole test binary,
// hand-built scenes, and small image statistics.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "gl/context.h"
#include "image.h"
#include "renderer.h"
#include "scene/scene.h"

namespace gis::test {

// The backend comes from GIS_TEST_BACKEND (auto, egl, osmesa); ctest registers both.
GlContext& context();

// Material helpers: an ideal Lambertian (no specular lobe) like the reference scenes use.
Material lambert(glm::vec3 albedo, bool doubleSided = false);

// A square of side `size` centred at `center`, facing `normal`, single-sided unless the material says otherwise.
void addQuad(Scene& scene, glm::vec3 center, glm::vec3 normal, float size, int material);

// Camera at `eye` looking at `target` (+Y up unless looking straight down).
Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfovDegrees = 40.0f);

// Renders one frame with the given settings; returns linear radiance (RGBA32F target).
ImageF renderHdr(const Scene& scene, RenderSettings settings);

// Mean of channel c over the square of half-size r pixels around (x, y).
double meanAround(const ImageF& img, int x, int y, int r, int c = 0);

// Pixel covering world point p for a scene rendered with the given settings (rounded).
glm::ivec2 projectToPixel(const Scene& scene, const RenderSettings& settings, glm::vec3 p);

}  // namespace gis::test
