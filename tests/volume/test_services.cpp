// The shared scene volume's fitting for every kind of bounds.
#include <gtest/gtest.h>

#include <cmath>

#include "volume/volume_fit.h"

namespace gis::test {
namespace {

void expectContains(const VolumeFit& f, const Aabb& b) {
    const glm::vec3 lo = f.worldToVoxel(b.min), hi = f.worldToVoxel(b.max);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GE(lo[c], 0.0f);
        EXPECT_LE(hi[c], float(f.resolution));
        EXPECT_TRUE(std::isfinite(lo[c]) && std::isfinite(hi[c]));
    }
    EXPECT_GT(f.voxelSize(), 0.0f);
}

TEST(VolumeFit, CubeAroundBoundsWithMargin) {
    Aabb b{{-1, 0, -1}, {1, 2, 1}};
    const VolumeFit f = fitVolume(b, 64, 2.0f);
    expectContains(f, b);
    EXPECT_NEAR(f.worldToVoxel(b.min).y, 2.0f, 1e-3f);  // exactly the margin on the longest axis
    EXPECT_NEAR(f.worldToVoxel(b.max).x, 62.0f, 1e-3f);
    const glm::vec3 p(0.3f, 1.7f, -0.2f);
    const glm::vec3 back = glm::vec3(f.voxelToWorldMatrix() * (f.worldToVoxelMatrix() * glm::vec4(p, 1.0f)));
    EXPECT_NEAR(glm::length(back - p), 0.0f, 1e-5f);
}

TEST(VolumeFit, DegenerateAndExtremeBounds) {
    expectContains(fitVolume(Aabb{}, 32), Aabb{{-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}});  // empty
    const Aabb flat{{-3, 1, -2}, {3, 1, 2}};
    expectContains(fitVolume(flat, 32), flat);
    const Aabb point{{5, 5, 5}, {5, 5, 5}};
    const VolumeFit fp = fitVolume(point, 32);
    expectContains(fp, point);
    EXPECT_GT(fp.size, 0.0f);
    for (float scale : {1e-3f, 1.0f, 1e3f}) {
        const Aabb b{glm::vec3(-1, 0, -1) * scale, glm::vec3(1, 2, 1) * scale};
        const VolumeFit f = fitVolume(b, 64);
        expectContains(f, b);
        EXPECT_NEAR(f.size / scale, fitVolume(Aabb{{-1, 0, -1}, {1, 2, 1}}, 64).size, 1e-3f);
    }
    EXPECT_THROW(fitVolume(flat, 0), Error);
    EXPECT_THROW(fitVolume(Aabb{{0, 0, 0}, {INFINITY, 1, 1}}, 8), Error);
}

}  // namespace
}  // namespace gis::test
