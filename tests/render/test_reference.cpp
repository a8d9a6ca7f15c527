// The rasterizer's direct lighting of builtin:cornell against Blender Cycles' direct-lighting pass
// of the same scene (shared/assets/reference/refs/cornell_point/direct.exr, 256x256, 2048 spp).
//
// Cycles averages each pixel over its footprint and casts hard shadows from the zero-radius point
// light; the rasterizer samples the pixel centre once and filters its shadow map (PCF). So pixels
// near geometric edges and near shadow boundaries are masked out, using a CPU ray cast of the same
// scene: a pixel is kept only if every pixel within EDGE_RADIUS sees the same face, and every pixel
// within PENUMBRA_RADIUS has the same visibility to the light. Means are then compared per face.
#include <cstdio>
#include <map>

#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 256;
constexpr int EDGE_RADIUS = 1;
constexpr int PENUMBRA_RADIUS = 3;
constexpr double kTolerance = 0.03;  // relative, per region mean (reference noise is ~0.2% per region)

TEST(Reference, CornellDirectLightingMatchesCycles) {
    const std::string refPath = std::string(GIS_SHARED_DIR) + "/assets/reference/refs/cornell_point/direct.exr";
    const ImageF ref = readExr(refPath);
    ASSERT_EQ(ref.width, kSize);
    ASSERT_EQ(ref.height, kSize);

    const Scene scene = makeBuiltinScene("cornell");
    ASSERT_EQ(scene.lights.size(), 1u);
    RenderSettings r;
    r.width = r.height = kSize;
    r.ambient = glm::vec3(0.0f);
    const ImageF img = renderHdr(scene, r);

    const glm::vec3 light = scene.lights[0].position;
    const std::vector<PixelHit> hits = castPixels(scene, 0, kSize, kSize, &light);
    const std::vector<bool> keep = interiorPixels(hits, kSize, kSize, EDGE_RADIUS, PENUMBRA_RADIUS);

    struct Sum { double ours[3] = {}, cycles[3] = {}; int n = 0; };
    std::map<int, Sum> regions;
    int kept = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const PixelHit& h = hits[size_t(y) * kSize + x];
            if (h.region < 0 || !keep[size_t(y) * kSize + x]) continue;
            Sum& s = regions[h.region];
            for (int c = 0; c < 3; ++c) {
                s.ours[c] += img.at(x, y)[c];
                s.cycles[c] += ref.at(x, y)[c];
            }
            ++s.n;
            ++kept;
        }

    std::printf("%-8s %6s %28s %28s %8s\n", "region", "pixels", "ours (r g b)", "cycles (r g b)", "error");
    int compared = 0, unlit = 0;
    double worst = 0.0;
    for (const auto& [region, s] : regions) {
        if (s.n < 30) continue;  // slivers: too few pixels for a stable mean
        const double ours = s.ours[0] + s.ours[1] + s.ours[2], cycles = s.cycles[0] + s.cycles[1] + s.cycles[2];
        if (cycles / (3.0 * s.n) < 1e-3) {  // a face turned away from the light: both must be ~0
            std::printf("%3d/%-4d %6d   unlit: ours %.2e, cycles %.2e\n", region / 8, region % 8, s.n,
                        ours / (3.0 * s.n), cycles / (3.0 * s.n));
            EXPECT_LT(ours / (3.0 * s.n), 1e-3) << "region " << region;
            ++unlit;
            continue;
        }
        const double err = std::abs(ours - cycles) / cycles;
        worst = std::max(worst, err);
        std::printf("%3d/%-4d %6d %9.5f %9.5f %9.5f %9.5f %9.5f %9.5f %7.2f%%\n", region / 8, region % 8, s.n,
                    s.ours[0] / s.n, s.ours[1] / s.n, s.ours[2] / s.n, s.cycles[0] / s.n, s.cycles[1] / s.n,
                    s.cycles[2] / s.n, 100.0 * err);
        EXPECT_LT(err, kTolerance) << "draw " << region / 8 << " face " << region % 8;
        ++compared;
    }
    std::printf("%d pixels kept, %d lit regions compared, %d unlit, worst %.2f%% (tolerance %.0f%%)\n", kept,
                compared, unlit, 100.0 * worst, 100.0 * kTolerance);
    // Lit: floor, ceiling, back, left, right walls, the tall block's front, the short block's top.
    EXPECT_GE(compared, 7);
    EXPECT_GT(kept, kSize * kSize / 3);
}

}  // namespace
}  // namespace gis::test
