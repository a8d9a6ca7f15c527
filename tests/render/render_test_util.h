// Shared by the in-process rendering tests: one headless GL context for the whole test binary,
// hand-built scenes, and small image statistics.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "gi/method.h"
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

// The smallest lit scene: one grey triangle facing a camera 2 units away, one point light beside the
// camera (the volume methods' degenerate case: a single, flat, open surface).
Scene oneTriangleScene();

// Renders with the given settings (progressive methods until converged, or `maxFrames` frames when
// that is sooner and not 0); returns linear radiance (RGBA32F target).
ImageF renderHdr(const Scene& scene, RenderSettings settings, int maxFrames = 0);

// Mean of channel c over the square of half-size r pixels around (x, y).
double meanAround(const ImageF& img, int x, int y, int r, int c = 0);

// Pixel covering world point p for a scene rendered with the given settings (rounded).
glm::ivec2 projectToPixel(const Scene& scene, const RenderSettings& settings, glm::vec3 p);

// What the centre of each pixel of a width x height render through camera `camera` sees, found by a
// CPU ray cast of the same triangles: the face (draw index * 8 + face of that draw, faces told
// apart by their plane normal) or -1 for the background, and whether it sees `light` (if given).
struct PixelHit {
    int region = -1;
    bool lit = false;
};
std::vector<PixelHit> castPixels(const Scene& scene, int camera, int width, int height, const glm::vec3* light);

// Pixels away from geometric edges (every pixel within edgeRadius sees the same face) and from
// shadow boundaries (every pixel within shadowRadius has the same visibility); image borders out.
std::vector<bool> interiorPixels(const std::vector<PixelHit>& hits, int width, int height, int edgeRadius,
                                 int shadowRadius);

// The scene scaled by `scale` about the origin: geometry, cameras (position, near, far) and lights
// (position, range, and point/spot intensity by scale^2, so irradiance is unchanged). Radiance
// does not depend on the unit of length: every method must render it the same.
Scene scaledScene(const Scene& scene, float scale);

// No NaN or Inf in any channel.
bool allFinite(const ImageF& img);
// The pixels that see an emitter at `settings`' size and camera (the G-buffer's emission, its
// antialiased edges included), grown by one pixel for a path tracer's whole-pixel footprint: what an
// energy comparison leaves out, since an emitter's own radiance is the same in every method.
std::vector<bool> emitterPixels(const Scene& scene, RenderSettings settings);
// The mask (width x height, row-major) with every set pixel's 8 neighbours set too.
std::vector<bool> grownByOnePixel(const std::vector<bool>& mask, int width, int height);
// Mean of R, G, B over the pixels not in `skip`, divided by all of the image's pixels.
double meanRgbExcept(const ImageF& img, const std::vector<bool>& skip);
// The mean over the interior pixels that see `region` (castPixels' ids) of channel c, or of R, G, B
// when c < 0.
double regionMean(const ImageF& img, const std::vector<PixelHit>& hits, const std::vector<bool>& interior, int region,
                  int channel = -1);
// RMSE over R, G, B of the interior pixels.
double interiorRmse(const ImageF& a, const ImageF& b, const std::vector<bool>& interior);
// RMSE over R, G, B of block x block means of the interior pixels (blocks weighed by how many
// interior pixels they hold): the error of a method's low frequencies, with a Monte Carlo
// reference's per-pixel noise averaged down by the block's pixel count (it otherwise dominates a
// 64-spp reference's RMSE and hides a method's bias).
double blockRmse(const ImageF& a, const ImageF& b, const std::vector<bool>& interior, int block);

// The thin-wall leak number every GI method reports: summed R+G+B of the image's right part
// (x > 55% of the width, the dark room) over its left part (x < 45%, the lit room); the middle,
// where the wall is seen, is left out. Writes the left sum to `litSum` if given.
double darkOverLitRoom(const ImageF& img, double* litSum = nullptr);

// A flat-RGBE Radiance file (the layout stb_image reads without run-length encoding) of the
// radiance at each texel centre's (u, v), u from the left, v from the top.
void writeHdrTexels(const std::string& path, int width, int height, const std::function<glm::vec3(glm::vec2)>& radiance);
// The same for radiance given by direction (through the CPU mapping, environment.h).
void writeHdr(const std::string& path, int width, int height, const std::function<glm::vec3(glm::vec3)>& radiance);

}  // namespace gis::test
