// The voxelizer against exact answers: conservative modes mark every voxel an exact triangle-box
// test marks (and `off` demonstrably does not), a closed box is watertight, averaging keeps a
// uniform colour, and oversized grids are refused before anything is allocated.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <queue>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_util.h"
#include "voxel_test_util.h"

namespace gis::test {
namespace {

constexpr int kN = 32;

VolumeFit unitVoxels(int n) {
    VolumeFit f;
    f.origin = glm::vec3(0.0f);
    f.size = float(n);
    f.resolution = n;
    return f;
}

std::vector<uint8_t> occupancy(const Scene& scene, ConservativeMode mode, int n = kN) {
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    Voxelizer v(unitVoxels(n), mode, {&ledger, "test.voxels"});
    v.voxelize(gpu);
    const std::vector<uint8_t> rgba = readVoxelsRgba8(v.grid().albedo);
    std::vector<uint8_t> occ(rgba.size() / 4);
    for (size_t i = 0; i < occ.size(); ++i) occ[i] = rgba[i * 4 + 3] > 0;
    return occ;
}

glm::vec3 randomPoint(std::mt19937& rng, float lo, float hi) {
    std::uniform_real_distribution<float> u(lo, hi);
    return {u(rng), u(rng), u(rng)};
}

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    glm::vec3 v(g(rng), g(rng), g(rng));
    return glm::length(v) > 1e-6f ? glm::normalize(v) : glm::vec3(1, 0, 0);
}

// Ordinary triangles, slivers thinner than a voxel and triangles smaller than a voxel, anywhere
// inside the grid with a margin.
std::vector<Triangle> randomTriangles(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Triangle> tris;
    for (int i = 0; i < 20; ++i) {  // ordinary: up to ~8 voxels across
        const glm::vec3 c = randomPoint(rng, 6.0f, kN - 6.0f);
        tris.push_back({c + randomPoint(rng, -4, 4), c + randomPoint(rng, -4, 4), c + randomPoint(rng, -4, 4)});
    }
    for (int i = 0; i < 20; ++i) {  // slivers: 4..12 voxels long, 0.01..0.3 wide
        const glm::vec3 a = randomPoint(rng, 8.0f, kN - 8.0f);
        const glm::vec3 dir = randomUnit(rng), side = glm::normalize(glm::cross(dir, randomUnit(rng)));
        const glm::vec3 b = a + dir * (4.0f + 8.0f * u(rng));
        const glm::vec3 c = glm::mix(a, b, u(rng)) + side * (0.01f + 0.29f * u(rng));
        tris.push_back({a, b, c});
    }
    for (int i = 0; i < 20; ++i) {  // sub-voxel: edges 0.05..0.6 voxels
        const glm::vec3 c = randomPoint(rng, 4.0f, kN - 4.0f);
        const float s = 0.05f + 0.55f * u(rng);
        tris.push_back({c, c + randomUnit(rng) * s, c + randomUnit(rng) * s});
    }
    return tris;
}

struct Comparison {
    int exact = 0, missing = 0, extra = 0;
};

Comparison compare(const std::vector<uint8_t>& gpu, const std::vector<uint8_t>& mustMark,
                   const std::vector<uint8_t>& mayMark) {
    Comparison c;
    for (size_t i = 0; i < gpu.size(); ++i) {
        c.exact += mustMark[i];
        if (mustMark[i] && !gpu[i]) ++c.missing;
        if (gpu[i] && !mayMark[i]) ++c.extra;
    }
    return c;
}

TEST(Voxelizer, ConservativeModesMarkEveryOverlappedVoxel) {
    for (unsigned seed : {1u, 2u, 3u}) {
        const std::vector<Triangle> tris = randomTriangles(seed);
        const Scene scene = triangleScene(tris);
        // Voxels a triangle overlaps by more than a hair must be marked; ones it only touches
        // within float rounding may or may not be.
        const std::vector<uint8_t> must = exactVoxels(tris, kN, 0.5 - 1e-4);
        const std::vector<uint8_t> may = exactVoxels(tris, kN, 0.5 + 1e-4);
        const Comparison geometry = compare(occupancy(scene, ConservativeMode::Geometry), must, may);
        const Comparison hardware = compare(occupancy(scene, ConservativeMode::Hardware), must, may);
        const Comparison off = compare(occupancy(scene, ConservativeMode::Off), must, may);
        std::printf("seed %u: exact %d voxels; geometry misses %d, %d extra (%.0f%%); hardware misses %d, %d extra; "
                    "off misses %d (%.0f%%), %d extra\n",
                    seed, geometry.exact, geometry.missing, geometry.extra, 100.0 * geometry.extra / geometry.exact,
                    hardware.missing, hardware.extra, off.missing, 100.0 * off.missing / off.exact, off.extra);
        EXPECT_EQ(geometry.missing, 0) << "seed " << seed;
        EXPECT_EQ(hardware.missing, 0) << "seed " << seed;
        EXPECT_GT(off.missing, geometry.exact / 20) << "plain rasterization should miss thin and small triangles";
    }
}

// A rotated closed box: no 6-connected path of empty voxels leads from outside to its centre.
TEST(Voxelizer, ClosedBoxIsWatertight) {
    Scene cube = makeBuiltinScene("cornell");  // borrow nothing but a unit cube's primitive
    Primitive box;
    for (const Primitive& p : cube.primitives)
        if (p.vertices.size() == 24) box = p;  // the blocks: unit cubes, 6 quads
    ASSERT_EQ(box.vertices.size(), 24u);
    for (ConservativeMode mode : {ConservativeMode::Geometry, ConservativeMode::Off}) {
        Scene s;
        s.materials.push_back(lambert(glm::vec3(0.8f)));
        box.material = 0;
        s.primitives.push_back(box);
        glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(kN * 0.5f));
        world = glm::rotate(world, 0.5f, glm::normalize(glm::vec3(1, 2, 3)));
        world = glm::scale(world, glm::vec3(17.3f, 11.1f, 13.7f));
        s.draws.push_back(DrawItem{0, world});
        finalizeScene(s);
        const std::vector<uint8_t> occ = occupancy(s, mode);
        std::vector<uint8_t> seen(occ.size(), 0);
        std::queue<glm::ivec3> open;
        open.push(glm::ivec3(0));
        seen[0] = 1;
        bool reachedCentre = false;
        const glm::ivec3 centre(kN / 2);
        while (!open.empty()) {
            const glm::ivec3 v = open.front();
            open.pop();
            if (v == centre) reachedCentre = true;
            for (int k = 0; k < 6; ++k) {
                glm::ivec3 w = v;
                w[k / 2] += k % 2 ? 1 : -1;
                if (glm::any(glm::lessThan(w, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(w, glm::ivec3(kN))))
                    continue;
                const size_t i = (size_t(w.z) * kN + w.y) * kN + w.x;
                if (occ[i] || seen[i]) continue;
                seen[i] = 1;
                open.push(w);
            }
        }
        if (mode == ConservativeMode::Geometry) {
            EXPECT_FALSE(reachedCentre) << "a 6-connected gap in the box's surface";
        }
        std::printf("closed box, %s: %s\n", conservativeModeName(mode), reachedCentre ? "leaks" : "watertight");
    }
}

// Every voxel of a uniformly coloured wall (two triangles, so voxels on the diagonal average
// samples of both) carries the colour within 1/255.
TEST(Voxelizer, UniformWallKeepsItsColour) {
    const glm::vec3 colour(0.3f, 0.6f, 0.9f);
    const glm::vec3 a(3.3f, 4.1f, 10.2f), b(28.7f, 5.2f, 21.3f), c(27.9f, 27.6f, 19.8f), d(2.9f, 26.1f, 9.4f);
    const Scene scene = triangleScene({{a, b, c}, {a, c, d}}, colour);
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    Voxelizer v(unitVoxels(kN), ConservativeMode::Geometry, {&ledger, "test.voxels"});
    v.voxelize(gpu);
    const std::vector<uint8_t> rgba = readVoxelsRgba8(v.grid().albedo);
    int occupied = 0;
    double worst = 0.0;
    for (size_t i = 0; i < rgba.size(); i += 4) {
        if (!rgba[i + 3]) continue;
        ++occupied;
        for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(rgba[i + ch] / 255.0 - colour[ch]));
    }
    std::printf("wall: %d voxels, worst colour error %.2f/255\n", occupied, worst * 255.0);
    EXPECT_GT(occupied, 500);
    EXPECT_LE(worst, 1.0 / 255.0 + 1e-6);
}

// The same scene twice gives bit-identical voxels (integer sums do not depend on fragment order).
TEST(Voxelizer, Deterministic) {
    const Scene scene = triangleScene(randomTriangles(7), glm::vec3(0.2f, 0.7f, 0.4f));
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    Voxelizer v(unitVoxels(kN), ConservativeMode::Geometry, {&ledger, "test.voxels"});
    v.voxelize(gpu);
    const auto first = readVoxelsRgba8(v.grid().albedo);
    v.voxelize(gpu);
    EXPECT_EQ(first, readVoxelsRgba8(v.grid().albedo));
}

// A grid moved to another cube (an SDF cascade following the camera) voxelizes exactly as a new
// voxelizer made for that cube; another resolution is refused.
TEST(Voxelizer, MovedGridMatchesAFreshOne) {
    const Scene scene = triangleScene(randomTriangles(7), glm::vec3(0.2f, 0.7f, 0.4f));
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    VolumeFit shifted = unitVoxels(kN);
    shifted.origin = glm::vec3(4.0f, -3.0f, 2.0f);
    Voxelizer moved(unitVoxels(kN), ConservativeMode::Geometry, {&ledger, "test.voxels"});
    moved.voxelize(gpu);
    const auto before = readVoxelsRgba8(moved.grid().albedo);
    moved.moveTo(shifted);
    moved.voxelize(gpu);
    Voxelizer fresh(shifted, ConservativeMode::Geometry, {&ledger, "test.voxels"});
    fresh.voxelize(gpu);
    const auto after = readVoxelsRgba8(moved.grid().albedo);
    EXPECT_EQ(after, readVoxelsRgba8(fresh.grid().albedo));
    EXPECT_NE(after, before);
    EXPECT_THROW(moved.moveTo(unitVoxels(kN / 2)), Error);
}

// A square emitter of edge `edge` voxels in the plane z = 10.37, rotated 30 degrees about z (so its
// edges and its diagonal, where its two triangles meet, cross voxels at odd angles), centred at
// `centre`, then tilted by `tilt` degrees about the x axis through its centre.
std::vector<Triangle> emitterSquare(float edge, glm::vec2 centre, float tilt = 0.0f) {
    const float c = std::cos(glm::radians(30.0f)) * 0.5f * edge, s = std::sin(glm::radians(30.0f)) * 0.5f * edge;
    const float ct = std::cos(glm::radians(tilt)), st = std::sin(glm::radians(tilt));
    auto corner = [&](float u, float v) {
        const glm::vec2 p(u * c - v * s, u * s + v * c);
        return glm::vec3(centre.x + p.x, centre.y + p.y * ct, 10.37f + p.y * st);
    };
    const glm::vec3 a = corner(-1, -1), b = corner(1, -1), d = corner(1, 1), e = corner(-1, 1);
    return {{a, b, d}, {a, d, e}};
}

// The emission a grid of unit voxels carries (the sum over voxels of emitted radiance x face area)
// for an emitter of `edge` voxels whose radiance keeps its power at that of a 1-voxel emitter of
// radiance 1 (power / pi = radiance x area = 1).
double carriedEmission(float edge, glm::vec2 centre, ConservativeMode mode, float tilt = 0.0f) {
    const float radiance = 1.0f / (edge * edge);
    const Scene scene = triangleScene(emitterSquare(edge, centre, tilt), glm::vec3(0.5f), glm::vec3(radiance));
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    Voxelizer v(unitVoxels(kN), mode, {&ledger, "test.voxels"});
    v.voxelize(gpu);
    const std::vector<float> emission = readVoxelsRgba16f(v.grid().emission);
    double sum = 0.0;
    for (size_t i = 0; i < emission.size(); i += 4) sum += emission[i];
    return sum;
}

// Conservative rasterization hands a sub-voxel emitter every voxel it touches; weighted by the part
// of each voxel's cross-section it covers, the volume carries the emitter's power whatever its size
// (the "a 4 cm emitter and a 40 cm one of equal power light a room equally"): a 0.4-voxel
// emitter within 10% of a 6-voxel one of equal power, at a voxel's centre and across a corner of
// four voxels, and the large one within 5% of its exact power (at full radiance its partly covered
// edge voxels alone add far more).
TEST(Voxelizer, EmissionCarriesTheEmittersPowerWhateverTheirSize) {
    const double large = carriedEmission(6.0f, glm::vec2(15.3f, 16.6f), ConservativeMode::Geometry);
    std::printf("6-voxel emitter: %.4f of its power\n", large);
    EXPECT_NEAR(large, 1.0, 0.05);
    for (glm::vec2 centre : {glm::vec2(15.5f, 16.5f), glm::vec2(15.95f, 16.03f)}) {
        const double small = carriedEmission(0.4f, centre, ConservativeMode::Geometry);
        std::printf("0.4-voxel emitter at (%.2f, %.2f): %.4f of its power, %.3f x the 6-voxel one's\n", centre.x,
                    centre.y, small, small / large);
        EXPECT_NEAR(small / large, 1.0, 0.10);
    }
}

// A tilted emitter crosses up to three voxels of each column along its dominant axis. Each column
// carries the part of its cross-section the emitter covers once, split over those voxels by the
// share of the plane's depth within each: the volume then carries the emitter's area projected on
// the dominant axis, cos(tilt) of the flat one's (counted once per voxel crossed, it carried up to
// three times that).
TEST(Voxelizer, ATiltedEmitterIsCountedOncePerColumn) {
    for (float tilt : {20.0f, 40.0f}) {
        const double carried = carriedEmission(6.0f, glm::vec2(15.3f, 16.6f), ConservativeMode::Geometry, tilt);
        const double expected = std::cos(glm::radians(tilt));
        std::printf("6-voxel emitter tilted %.0f degrees: %.4f of its power, expected %.4f\n", tilt, carried, expected);
        EXPECT_NEAR(carried / expected, 1.0, 0.05) << tilt;
    }
}

TEST(Voxelizer, RefusesGridsThatDoNotFitBeforeAllocating) {
    context();
    gl::MemoryLedger ledger;
    VolumeFit f = unitVoxels(1024);
    try {
        Voxelizer v(f, ConservativeMode::Geometry, {&ledger, "test.voxels"});
        FAIL() << "a 1024^3 grid was accepted";
    } catch (const Error& e) {
        const std::string msg = e.what();
        std::printf("%s\n", msg.c_str());
        EXPECT_NE(msg.find("MiB"), std::string::npos) << msg;
    }
    EXPECT_EQ(ledger.total(), 0);
}

TEST(Voxelizer, EmptySceneGivesAnEmptyGrid) {
    const Scene scene = triangleScene({});
    const std::vector<uint8_t> occ = occupancy(scene, ConservativeMode::Geometry, 8);
    for (uint8_t o : occ) EXPECT_EQ(o, 0);
}

// A face of a box: the square [lo, hi]^2 across `axis` at `at`, wound to face +axis (side 1) or -axis.
void addFace(std::vector<Triangle>& tris, int axis, float at, glm::vec2 lo, glm::vec2 hi, int side) {
    auto point = [&](float u, float w) {
        glm::vec3 p;
        p[axis] = at;
        p[(axis + 1) % 3] = u;
        p[(axis + 2) % 3] = w;
        return p;
    };
    const glm::vec3 a = point(lo.x, lo.y), b = point(hi.x, lo.y), c = point(hi.x, hi.y), d = point(lo.x, hi.y);
    if (side > 0) tris.insert(tris.end(), {{a, b, c}, {a, c, d}});
    else tris.insert(tris.end(), {{a, c, b}, {a, d, c}});
}

// A slab's mark says where in its voxel the wall lies, and a second thin wall across it is marked
// as its junction (shaders/volume/voxel_resolve.comp): a floor 0.2 voxels thick whose faces lie
// in the lower part of voxel row y = 5, and a wall standing on it in the upper part of column
// x = 10. Rays and gathers judge a slab's sides from these places: judged from the voxel's centre,
// a ray leaving the wall's face started on its far side (builtin:building's closed room).
TEST(Voxelizer, SlabsMarkWhereTheirWallLiesAndTheWallAcrossThem) {
    std::vector<Triangle> tris;
    addFace(tris, 1, 5.2f, {4, 4}, {28, 28}, -1);  // the floor's underside ...
    addFace(tris, 1, 5.4f, {4, 4}, {28, 28}, 1);   // ... and top: its middle 0.2 below the centre
    addFace(tris, 0, 10.6f, {5.4f, 4}, {28, 28}, -1);  // the wall's faces (y from the floor up, z):
    addFace(tris, 0, 10.9f, {5.4f, 4}, {28, 28}, 1);   // its middle 0.25 past the voxel's centre
    const Scene scene = triangleScene(tris);
    context();
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    Voxelizer v(unitVoxels(kN), ConservativeMode::Geometry, {&ledger, "test.voxels"});
    v.voxelize(gpu);
    const std::vector<float> emission = readVoxelsRgba16f(v.grid().emission);
    const std::vector<uint8_t> normal = readVoxelsRgba8(v.grid().normal);
    auto at = [](int x, int y, int z) { return size_t((z * kN + y) * kN + x); };
    auto slab = [&](size_t i) { return emission[4 * i + 3]; };     // voxelSlabMark: axis + 1 + offset / 2
    auto junction = [&](size_t i) { return normal[4 * i + 3] / 255.0f * 3.0f; };  // axis + 0.5 + 0.9 offset
    const size_t wall = at(10, 15, 15), floor = at(20, 5, 15), corner = at(10, 5, 15);
    std::printf("marks: wall %.3f, floor %.3f, where they meet %.3f and junction %.3f\n", slab(wall), slab(floor),
                slab(corner), junction(corner));
    EXPECT_NEAR(slab(wall), 1.0f + 0.5f * 0.25f, 0.02f);   // x, 0.25 past the centre
    EXPECT_NEAR(slab(floor), 2.0f - 0.5f * 0.2f, 0.02f);   // y, 0.2 below it
    EXPECT_EQ(normal[4 * wall + 3], 0);                    // no wall across a plain wall or floor
    EXPECT_EQ(normal[4 * floor + 3], 0);
    // Where they meet, each covers the voxel's cross-section (the voxelization is conservative):
    // either is the slab, and the other its junction.
    if (slab(corner) < 1.5f) {
        EXPECT_NEAR(slab(corner), 1.0f + 0.5f * 0.25f, 0.02f);
        EXPECT_NEAR(junction(corner), 1.5f - 0.9f * 0.2f, 0.04f);
    } else {
        EXPECT_NEAR(slab(corner), 2.0f - 0.5f * 0.2f, 0.02f);
        EXPECT_NEAR(junction(corner), 0.5f + 0.9f * 0.25f, 0.04f);
    }
}

}  // namespace
}  // namespace gis::test
