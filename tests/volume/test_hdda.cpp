// The occupancy hierarchy (renderer/volume/occupancy.h) against the voxels it was built from, and
// its hierarchical DDA (shaders/volume/hdda.glsl, through shaders/volume/hdda_probe.comp) against a
// brute-force voxel-by-voxel walk (Amanatides & Woo) in double precision: random rays through
// random, clustered occupancy (empty regions, empty blocks and busy ones), in one cascade and
// across nested cascades, must find the same first voxel.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <random>

#include "render_test_util.h"
#include "volume/occupancy.h"
#include "volume/voxel_uniforms.h"
#include "volume/voxelizer.h"

namespace gis::test {
namespace {

// n^3 occupancy, x fastest; whole regions empty, whole blocks empty, the rest at random densities.
struct Occupancy {
    int n = 0;
    std::vector<uint8_t> cells;
    bool at(glm::ivec3 v) const { return cells[(size_t(v.z) * n + v.y) * n + v.x] != 0; }
};

Occupancy randomOccupancy(int n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Occupancy o{n, std::vector<uint8_t>(size_t(n) * n * n, 0)};
    const int regions = n / kOccupancyRegion;
    std::vector<float> regionDensity(size_t(regions) * regions * regions);
    for (float& d : regionDensity) {
        const float r = u(rng);
        d = r < 0.4f ? 0.0f : (r < 0.7f ? 0.02f : (r < 0.9f ? 0.1f : 0.5f));
    }
    const int blocks = n / kOccupancyBlock;
    std::vector<bool> blockEmpty(size_t(blocks) * blocks * blocks);
    for (size_t i = 0; i < blockEmpty.size(); ++i) blockEmpty[i] = u(rng) < 0.4f;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::ivec3 r = glm::ivec3(x, y, z) / kOccupancyRegion, b = glm::ivec3(x, y, z) / kOccupancyBlock;
                const float d = regionDensity[(size_t(r.z) * regions + r.y) * regions + r.x];
                if (blockEmpty[(size_t(b.z) * blocks + b.y) * blocks + b.x]) continue;
                o.cells[(size_t(z) * n + y) * n + x] = u(rng) < d ? 1 : 0;
            }
    return o;
}

gl::Texture uploadOccupancy(const Occupancy& o, const gl::MemoryScope& scope) {
    gl::Texture t = gl::createTexture3D(scope, GL_RGBA8, o.n, o.n, o.n);
    std::vector<uint8_t> rgba(o.cells.size() * 4, 0);
    for (size_t i = 0; i < o.cells.size(); ++i) rgba[i * 4 + 3] = o.cells[i] ? 255 : 0;
    glTextureSubImage3D(t.id(), 0, 0, 0, 0, o.n, o.n, o.n, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    return t;
}

struct Cascade {
    glm::dvec3 origin;
    double size;
    Occupancy occupancy;
};

struct WalkResult {
    std::optional<glm::ivec3> voxel;
    int cascade = -1;
    double closestTie = 1e30;   // smallest gap between two axes' crossings on the way (voxel units)
    int voxels = 0;             // voxels visited
};

// Amanatides & Woo through one cascade from t0 to t1 (voxel units), the same start voxel and the
// same tie-break (x, then y, then z) as the GPU walk.
std::optional<glm::ivec3> walkCascade(const Occupancy& occ, glm::dvec3 o, glm::dvec3 d, double t0, double t1,
                                      double& closestTie, int& visited) {
    const int n = occ.n;
    glm::ivec3 v;
    for (int a = 0; a < 3; ++a) v[a] = std::clamp(int(std::floor(o[a] + d[a] * t0)), 0, n - 1);
    glm::dvec3 tMax, tDelta;
    glm::ivec3 step;
    for (int a = 0; a < 3; ++a) {
        step[a] = d[a] > 0 ? 1 : (d[a] < 0 ? -1 : 0);
        tMax[a] = step[a] == 0 ? 1e300 : (double(v[a] + (step[a] > 0 ? 1 : 0)) - o[a]) / d[a];
        tDelta[a] = step[a] == 0 ? 1e300 : std::abs(1.0 / d[a]);
    }
    double t = t0;
    while (t <= t1) {
        ++visited;
        if (occ.at(v)) return v;
        const int axis = tMax.x <= tMax.y && tMax.x <= tMax.z ? 0 : (tMax.y <= tMax.z ? 1 : 2);
        for (int a = 0; a < 3; ++a)
            if (a != axis) closestTie = std::min(closestTie, std::abs(tMax[a] - tMax[axis]));
        closestTie = std::min(closestTie, std::abs(tMax[axis] - t1));
        t = std::max(tMax[axis], t);
        v[axis] += step[axis];
        if (v[axis] < 0 || v[axis] >= n) break;
        tMax[axis] += tDelta[axis];
    }
    return std::nullopt;
}

glm::dvec2 slab(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = -1e300, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return {1.0, 0.0};
            continue;
        }
        double a0 = (lo[a] - o[a]) / d[a], a1 = (hi[a] - o[a]) / d[a];
        if (a0 > a1) std::swap(a0, a1);
        t0 = std::max(t0, a0);
        t1 = std::min(t1, a1);
    }
    return {t0, t1};
}

// The cascades' hand-over as hdda.glsl does it: the finest cascade holding the start, then each
// coarser one from where the ray left the last.
WalkResult bruteForce(const std::vector<Cascade>& cs, glm::dvec3 origin, glm::dvec3 dir, double start, double maxT) {
    WalkResult r;
    int first = int(cs.size()) - 1;
    const glm::dvec3 p = origin + dir * start;
    for (int c = 0; c + 1 < int(cs.size()); ++c)
        if (glm::all(glm::greaterThanEqual(p, cs[c].origin)) && glm::all(glm::lessThanEqual(p, cs[c].origin + cs[c].size))) {
            first = c;
            break;
        }
    double t = start;
    for (int c = first; c < int(cs.size()) && t < maxT; ++c) {
        const glm::dvec2 span = slab(origin, dir, cs[c].origin, cs[c].origin + cs[c].size);
        const double t0 = std::max(span.x, t), t1 = std::min(span.y, maxT);
        if (t1 <= t0) continue;
        const double cell = cs[c].size / cs[c].occupancy.n;
        r.closestTie = std::min({r.closestTie, std::abs(span.x - t) / cell, std::abs(span.y - maxT) / cell});
        const auto v = walkCascade(cs[c].occupancy, (origin - cs[c].origin) / cell, dir, t0 / cell, t1 / cell, r.closestTie, r.voxels);
        if (v) {
            r.voxel = v;
            r.cascade = c;
            return r;
        }
        t = t1;
    }
    return r;
}

struct GpuRay {
    glm::vec4 origin;      // w = max distance
    glm::vec4 direction;   // w = start offset
};

struct GpuHit {
    std::optional<glm::ivec3> voxel;
    int cascade = -1;
    int steps = 0;
};

std::vector<GpuHit> traceGpu(const OccupancyHierarchy& h, const std::vector<Cascade>& cs, const std::vector<GpuRay>& rays) {
    static gl::Object program = buildProgram({"hdda_probe", {"volume/hdda_probe.comp"}, {}});
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "hdda_test"};
    gl::Buffer in = gl::createBuffer(scope, int64_t(rays.size() * sizeof(GpuRay)), rays.data());
    gl::Buffer voxels = gl::createBuffer(scope, int64_t(rays.size() * 16), nullptr);
    gl::Buffer positions = gl::createBuffer(scope, int64_t(rays.size() * 16), nullptr);
    const GLuint p = program.id();
    glUseProgram(p);
    glProgramUniform1ui(p, 0, GLuint(rays.size()));
    glProgramUniform1i(p, 1, h.resolution());
    glProgramUniform1i(p, 2, int(cs.size()));
    std::array<glm::vec4, 4> volumes{};
    for (size_t c = 0; c < cs.size(); ++c) volumes[c] = glm::vec4(glm::vec3(cs[c].origin), float(cs[c].size));
    glProgramUniform4fv(p, 3, 4, &volumes[0][0]);
    glProgramUniform1i(p, 7, 100000);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, voxel::SV_HDDA_PROBE_RAYS, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, voxel::SV_HDDA_PROBE_HITS, voxels.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, voxel::SV_HDDA_PROBE_POSITIONS, positions.id());
    h.bind();
    glDispatchCompute(GLuint((rays.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::ivec4> v(rays.size());
    std::vector<glm::vec4> pos(rays.size());
    glGetNamedBufferSubData(voxels.id(), 0, GLsizeiptr(v.size() * 16), v.data());
    glGetNamedBufferSubData(positions.id(), 0, GLsizeiptr(pos.size() * 16), pos.data());
    std::vector<GpuHit> out(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        if (v[i].w > 0) out[i].voxel = glm::ivec3(v[i]);
        out[i].cascade = v[i].w - 1;
        out[i].steps = int(pos[i].w);
    }
    return out;
}

// Random rays: origins inside, on and outside the coarsest cube, directions uniform on the sphere
// with some along an axis or in an axis plane (zero components), some with a start offset.
std::vector<GpuRay> randomRays(const std::vector<Cascade>& cs, int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<GpuRay> rays;
    for (int i = 0; i < count; ++i) {
        const Cascade& box = cs[size_t(i) % cs.size()];   // starts in each cascade alike
        const double s = box.size;
        glm::dvec3 o = box.origin + glm::dvec3(u(rng), u(rng), u(rng)) * s * 1.4 - 0.2 * s;
        glm::dvec3 d(g(rng), g(rng), g(rng));
        if (i % 16 == 0) d = glm::dvec3(0.0);
        if (i % 16 == 0) d[(i / 16) % 3] = (i / 48) % 2 ? 1.0 : -1.0;
        if (i % 16 == 1) d[(i / 16) % 3] = 0.0;
        d = glm::normalize(d);
        const double start = i % 4 == 2 ? u(rng) * 0.3 * s : 0.0;  // ~ s: this cascade's edge
        rays.push_back({glm::vec4(glm::vec3(o), float(3.0 * cs.back().size)), glm::vec4(glm::vec3(d), float(start))});
    }
    return rays;
}

struct Comparison {
    int rays = 0, hits = 0, mismatches = 0, tieMismatches = 0, nearTies = 0;
    double meanSteps = 0.0, meanVoxels = 0.0;   // GPU cells crossed, CPU voxels walked
};

Comparison compare(const std::vector<Cascade>& cs, const std::vector<GpuRay>& rays, const std::vector<GpuHit>& gpu) {
    Comparison c;
    for (size_t i = 0; i < rays.size(); ++i) {
        // The GPU's float ray, exactly, in double.
        const glm::dvec3 o(glm::vec3(rays[i].origin)), d(glm::vec3(rays[i].direction));
        const WalkResult ref = bruteForce(cs, o, d, rays[i].direction.w, rays[i].origin.w);
        const bool nearTie = ref.closestTie < 1e-4;
        c.nearTies += nearTie;
        ++c.rays;
        c.hits += ref.voxel.has_value();
        c.meanSteps += gpu[i].steps;
        c.meanVoxels += ref.voxels;
        const bool same = ref.voxel.has_value() == gpu[i].voxel.has_value() &&
                          (!ref.voxel || (*ref.voxel == *gpu[i].voxel && ref.cascade == gpu[i].cascade));
        if (!same) {
            (nearTie ? c.tieMismatches : c.mismatches)++;
            if (c.mismatches + c.tieMismatches <= 5 && !nearTie)
                ADD_FAILURE() << "ray " << i << " (" << o.x << ", " << o.y << ", " << o.z << ") dir (" << d.x << ", "
                              << d.y << ", " << d.z << "): brute force "
                              << (ref.voxel ? std::to_string(ref.voxel->x) + "," + std::to_string(ref.voxel->y) + "," +
                                                  std::to_string(ref.voxel->z) + " in cascade " + std::to_string(ref.cascade)
                                            : std::string("miss"))
                              << ", HDDA "
                              << (gpu[i].voxel ? std::to_string(gpu[i].voxel->x) + "," + std::to_string(gpu[i].voxel->y) +
                                                     "," + std::to_string(gpu[i].voxel->z) + " in cascade " +
                                                     std::to_string(gpu[i].cascade)
                                               : std::string("miss"));
        }
    }
    c.meanSteps /= std::max(c.rays, 1);
    c.meanVoxels /= std::max(c.rays, 1);
    return c;
}

TEST(Occupancy, MasksAndRegionBitsMatchTheVoxelsTheyWereBuiltFrom) {
    context();
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "occupancy_test"};
    const int n = 64;
    const Occupancy occ = randomOccupancy(n, 7);
    VoxelGrid grid;
    grid.albedo = uploadOccupancy(occ, scope);
    OccupancyHierarchy h(scope, n, 2);
    h.build(grid, 1);   // the second cascade's slot: offsets must be right too
    const std::vector<uint64_t> blocks = h.readBlocks(1);
    const std::vector<bool> regions = h.readRegions(1);
    const int b = n / kOccupancyBlock, r = n / kOccupancyRegion;
    int wrongBlocks = 0, wrongRegions = 0, emptyRegions = 0, emptyBlocks = 0;
    std::vector<bool> regionAny(regions.size(), false);
    for (int z = 0; z < b; ++z)
        for (int y = 0; y < b; ++y)
            for (int x = 0; x < b; ++x) {
                uint64_t mask = 0;
                for (int bit = 0; bit < 64; ++bit) {
                    const glm::ivec3 v = glm::ivec3(x, y, z) * kOccupancyBlock + glm::ivec3(bit & 3, (bit >> 2) & 3, bit >> 4);
                    if (occ.at(v)) mask |= uint64_t(1) << bit;
                }
                wrongBlocks += blocks[(size_t(z) * b + y) * b + x] != mask;
                emptyBlocks += mask == 0;
                const glm::ivec3 rc = glm::ivec3(x, y, z) * kOccupancyBlock / kOccupancyRegion;
                if (mask) regionAny[(size_t(rc.z) * r + rc.y) * r + rc.x] = true;
            }
    for (size_t i = 0; i < regions.size(); ++i) {
        wrongRegions += regions[i] != regionAny[i];
        emptyRegions += !regionAny[i];
    }
    EXPECT_EQ(wrongBlocks, 0);
    EXPECT_EQ(wrongRegions, 0);
    // The random set exercises every level: empty regions, empty blocks in busy regions, busy blocks.
    EXPECT_GT(emptyRegions, 50);
    EXPECT_GT(emptyBlocks - emptyRegions * 8, 100);
    // The first cascade's slot was left alone.
    for (uint64_t m : h.readBlocks(0)) ASSERT_EQ(m, 0u);
}

TEST(Hdda, FindsTheSameFirstVoxelAsABruteForceWalkInOneCascade) {
    context();
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "hdda_test"};
    const int n = 64;
    std::vector<Cascade> cs{{glm::dvec3(-1.25, 0.5, 2.0), 3.0, randomOccupancy(n, 11)}};
    VoxelGrid grid;
    grid.albedo = uploadOccupancy(cs[0].occupancy, scope);
    OccupancyHierarchy h(scope, n, 1);
    h.build(grid, 0);
    const std::vector<GpuRay> rays = randomRays(cs, 4096, 5);
    const Comparison c = compare(cs, rays, traceGpu(h, cs, rays));
    std::printf("one cascade: %d rays, %d hits, %d mismatches (+%d at a tie within 1e-4 voxel; %d rays pass one), "
                "%.1f cells crossed per ray (the voxel walk visits %.1f)\n",
                c.rays, c.hits, c.mismatches, c.tieMismatches, c.nearTies, c.meanSteps, c.meanVoxels);
    EXPECT_EQ(c.mismatches, 0);
    EXPECT_LE(c.tieMismatches, c.nearTies);
    EXPECT_GT(c.hits, c.rays / 4);
    EXPECT_LT(c.rays - c.hits, c.rays);
}

TEST(Hdda, FindsTheSameFirstVoxelAsABruteForceWalkAcrossCascades) {
    context();
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "hdda_test"};
    const int n = 32;
    // Nested as the volume nests them: each twice the last, the finer ones off centre.
    std::vector<Cascade> cs{{glm::dvec3(1.0, 1.5, 0.5), 2.0, randomOccupancy(n, 21)},
                            {glm::dvec3(0.5, 0.0, 0.0), 4.0, randomOccupancy(n, 22)},
                            {glm::dvec3(0.0, 0.0, 0.0), 8.0, randomOccupancy(n, 23)}};
    std::vector<VoxelGrid> grids(cs.size());
    OccupancyHierarchy h(scope, n, int(cs.size()));
    for (size_t c = 0; c < cs.size(); ++c) {
        grids[c].albedo = uploadOccupancy(cs[c].occupancy, scope);
        h.build(grids[c], int(c));
    }
    const std::vector<GpuRay> rays = randomRays(cs, 4096, 9);
    const std::vector<GpuHit> gpu = traceGpu(h, cs, rays);
    const Comparison c = compare(cs, rays, gpu);
    std::printf("three cascades: %d rays, %d hits, %d mismatches (+%d at a tie), %.1f cells crossed per ray (the voxel "
                "walk visits %.1f)\n",
                c.rays, c.hits, c.mismatches, c.tieMismatches, c.meanSteps, c.meanVoxels);
    EXPECT_EQ(c.mismatches, 0);
    int perCascade[3] = {0, 0, 0};
    for (const GpuHit& g : gpu)
        if (g.voxel) ++perCascade[g.cascade];
    for (int k = 0; k < 3; ++k) EXPECT_GT(perCascade[k], 50) << "cascade " << k;
}

}  // namespace
}  // namespace gis::test
