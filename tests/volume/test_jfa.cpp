// Jump flooding (renderer/volume/distance_field.*) against the exact Euclidean distance transform.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "render_test_util.h"
#include "sdf_test_util.h"

namespace gis::test {
namespace {

struct JfaError {
    double maxVoxels = 0.0, meanVoxels = 0.0;
    int wrongCells = 0;  // cells more than 1e-3 voxel from the exact distance
};

// The field in voxels (what the module stores in world units, divided by the cell size).
std::vector<float> floodInVoxels(const SeedGrid& g, JfaVariant variant, bool withNormals = false) {
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    const SdfVolume volume{glm::vec3(0.0f), float(g.n), g.n};  // one world unit per cell
    DistanceField field(volume, scope);
    field.build(textures.seeds(withNormals), variant);
    return field.readBack();
}

JfaError compare(const std::vector<float>& jfa, const std::vector<double>& exact) {
    JfaError e;
    for (size_t i = 0; i < exact.size(); ++i) {
        const double err = std::abs(double(jfa[i]) - exact[i]);
        e.maxVoxels = std::max(e.maxVoxels, err);
        e.meanVoxels += err;
        e.wrongCells += err > 1e-3;
    }
    e.meanVoxels /= double(exact.size());
    return e;
}

struct SeedSet {
    std::string name;
    SeedGrid grid;
};

std::vector<SeedSet> seedSets(int n) {
    const int cells = n * n * n;
    return {{"sparse", uniformSeeds(n, std::max(8, cells / 2000), 11u + n)},
            {"dense", uniformSeeds(n, cells / 20, 23u + n)},
            {"clustered", clusteredSeeds(n, 6, n * 2, 1.5f, 37u + n)}};
}

TEST(SdfJfa, ExactTransformEqualsBruteForce) {
    for (const SeedSet& set : seedSets(16)) {
        const auto exact = exactDistance(set.grid), brute = bruteForceDistance(set.grid);
        for (size_t i = 0; i < exact.size(); ++i) ASSERT_NEAR(exact[i], brute[i], 1e-9) << set.name << " cell " << i;
    }
}

// The README's table: max and mean error in voxels per variant, seed set and resolution.
// Refinement never worse than plain; plain JFA's largest error stays at or below one voxel.
TEST(SdfJfa, ErrorAgainstExactDistanceTransform) {
    for (int n : {32, 64}) {
        for (const SeedSet& set : seedSets(n)) {
            const auto exact = exactDistance(set.grid);
            JfaError plain;
            for (JfaVariant v : {JfaVariant::Plain, JfaVariant::OnePlusJfa, JfaVariant::JfaPlusTwo}) {
                const JfaError e = compare(floodInVoxels(set.grid, v), exact);
                std::printf("JFA %2d^3 %-9s %-6s max %.4f mean %.6f voxels, %d of %d cells wrong\n", n,
                            set.name.c_str(), jfaVariantName(v), e.maxVoxels, e.meanVoxels, e.wrongCells, n * n * n);
                if (v == JfaVariant::Plain) {
                    plain = e;
                    EXPECT_LE(e.maxVoxels, 1.0) << set.name << " " << n;
                } else {
                    EXPECT_LE(e.maxVoxels, plain.maxVoxels + 1e-4) << set.name << " " << n << " " << jfaVariantName(v);
                    EXPECT_LE(e.meanVoxels, plain.meanVoxels + 1e-7) << set.name << " " << n << " " << jfaVariantName(v);
                }
            }
        }
    }
}

TEST(SdfJfa, OneSeedGivesExactDistances) {
    for (int n : {1, 7, 32}) {
        SeedGrid g = uniformSeeds(n, 0, 1);
        g.seed[g.index(n / 3, n / 2, n - 1)] = 1;  // off-centre and on a face: the floods must cross the volume
        const auto jfa = floodInVoxels(g, JfaVariant::Plain);
        const auto exact = exactDistance(g);
        for (size_t i = 0; i < exact.size(); ++i) ASSERT_NEAR(jfa[i], exact[i], 1e-4) << "n " << n << " cell " << i;
    }
}

TEST(SdfJfa, NoSeedIsFarEverywhere) {
    const int n = 16;
    const SeedGrid g = uniformSeeds(n, 0, 1);
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    const SdfVolume volume{glm::vec3(-3.0f), 2.5f, n};
    DistanceField field(volume, scope);
    for (bool normals : {false, true}) {
        field.build(textures.seeds(normals), JfaVariant::JfaPlusTwo);
        for (float d : field.readBack()) ASSERT_EQ(d, volume.farValue());
    }
    std::vector<float> coarse(size_t(field.coarse().width) * field.coarse().width * field.coarse().width);
    glGetTextureImage(field.coarse().id(), 0, GL_RED, GL_FLOAT, GLsizei(coarse.size() * 4), coarse.data());
    for (float c : coarse) ASSERT_TRUE(std::isfinite(c) && c > 0.0f && c < volume.farValue());
}

// A closed box voxelized as its six faces with outward normals: negative inside, positive outside.
TEST(SdfJfa, ClosedBoxIsNegativeInsidePositiveOutside) {
    const int n = 32, lo = 8, hi = 23;
    SeedGrid g = uniformSeeds(n, 0, 1);
    for (int z = lo; z <= hi; ++z)
        for (int y = lo; y <= hi; ++y)
            for (int x = lo; x <= hi; ++x) {
                const glm::ivec3 c(x, y, z);
                glm::vec3 normal(0.0f);
                for (int a = 0; a < 3; ++a) normal[a] = c[a] == lo ? -1.0f : c[a] == hi ? 1.0f : 0.0f;
                if (normal == glm::vec3(0.0f)) continue;  // interior cell
                g.seed[g.index(x, y, z)] = 1;
                g.normal[g.index(x, y, z)] = glm::normalize(normal);  // averaged at edges and corners
            }
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    DistanceField field({glm::vec3(0.0f), float(n), n}, scope);
    field.build(textures.seeds(true), JfaVariant::JfaPlusTwo);
    const auto d = field.readBack();
    const auto exact = exactDistance(g);
    int inside = 0, outside = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const size_t i = g.index(x, y, z);
                if (g.seed[i]) {
                    ASSERT_EQ(d[i], 0.0f);
                    continue;
                }
                const bool in = x > lo && x < hi && y > lo && y < hi && z > lo && z < hi;
                ASSERT_NEAR(std::abs(d[i]), exact[i], 1e-4);
                if (in) {
                    ASSERT_LT(d[i], 0.0f) << x << "," << y << "," << z;
                    ++inside;
                } else {
                    ASSERT_GT(d[i], 0.0f) << x << "," << y << "," << z;
                    ++outside;
                }
            }
    EXPECT_EQ(inside, 14 * 14 * 14);
    EXPECT_GT(outside, 0);
}

// A wall one cell thick: voxelized from both sides of a double-sided quad its averaged normals
// cancel, and both sides are outside (positive); a single-sided wall (normals +x) makes the
// region behind it negative - what an open mesh does, stated in sdf_resolve.comp.
TEST(SdfJfa, OneCellWallSignFollowsItsNormals) {
    const int n = 16, wall = 7;
    for (bool doubleSided : {true, false}) {
        SeedGrid g = uniformSeeds(n, 0, 1);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y) {
                g.seed[g.index(wall, y, z)] = 1;
                g.normal[g.index(wall, y, z)] = doubleSided ? glm::vec3(0.0f) : glm::vec3(1, 0, 0);
            }
        gl::MemoryLedger ledger;
        const gl::MemoryScope scope{&ledger, "sdf_test"};
        SeedTextures textures = uploadSeeds(g, scope);
        DistanceField field({glm::vec3(0.0f), float(n), n}, scope);
        field.build(textures.seeds(true), JfaVariant::Plain);
        const auto d = field.readBack();
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const float expected = float(std::abs(x - wall));
                    const float sign = doubleSided || x > wall ? 1.0f : -1.0f;
                    ASSERT_EQ(d[g.index(x, y, z)], x == wall ? 0.0f : sign * expected)
                        << (doubleSided ? "double" : "single") << "-sided, x " << x;
                }
    }
}

// Time per step on this machine's GL (llvmpipe in CI), printed for the README.
TEST(SdfJfa, TimingAt64) {
    const SeedGrid g = uniformSeeds(64, 64 * 64 * 64 / 20, 5);
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    SeedTextures textures = uploadSeeds(g, scope);
    DistanceField field({glm::vec3(0.0f), 64.0f, 64}, scope);
    for (JfaVariant v : {JfaVariant::Plain, JfaVariant::OnePlusJfa, JfaVariant::JfaPlusTwo}) {
        field.build(textures.seeds(false), v);  // warm-up: shader compile caches, first dispatch
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        const int runs = 1;
        for (int r = 0; r < runs; ++r) field.build(textures.seeds(false), v);
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / runs;
        std::printf("JFA 64^3 %-6s %zu passes: %.1f ms per build (seed + passes + resolve + coarse)\n",
                    jfaVariantName(v), jfaSteps(64, v).size(), ms);
    }
    EXPECT_EQ(ledger.total(), textures.occupancy.object.bytes() + textures.normals.object.bytes() +
                                  distanceFieldBytes(64));  // the nearest-seed images were released
}

}  // namespace
}  // namespace gis::test
