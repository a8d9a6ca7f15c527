// The generated atlas (renderer/lightmap/): charts, flattening, density, packing, bad input and
// determinism on small meshes with known answers.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "lightmap_test_util.h"

using namespace lmtest;
using gis::lightmap::buildAtlas;

namespace {

AtlasParams params(float density, int maxSize = 2048, int maxAtlases = 4, int gutter = 2) {
    AtlasParams p;
    p.texelsPerMetre = density;
    p.maxAtlasSize = maxSize;
    p.maxAtlases = maxAtlases;
    p.gutter = gutter;
    return p;
}

double angleAt(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    return std::acos(std::clamp(glm::dot(glm::normalize(b - a), glm::normalize(c - a)), -1.0, 1.0));
}

// A plane triangulated irregularly (a fan of uneven spokes) and tilted out of every axis plane.
MeshInput tiltedFan() {
    const glm::mat4 tilt = glm::rotate(glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1, 0, 0)), 0.4f, glm::vec3(0, 0, 1));
    MeshInput m;
    m.positions.push_back(glm::vec3(tilt * glm::vec4(0, 0, 0, 1)));
    const int n = 12;
    for (int i = 0; i < n; ++i) {
        const float a = 6.2831853f * (float(i) + 0.3f * float(i % 2)) / n, r = 1.0f + 0.4f * float(i % 3);
        m.positions.push_back(glm::vec3(tilt * glm::vec4(r * std::cos(a), 0.0f, r * std::sin(a), 1)));
    }
    for (int i = 0; i < n; ++i) m.indices.insert(m.indices.end(), {0u, uint32_t(1 + (i + 1) % n), uint32_t(1 + i)});
    return m;
}

}  // namespace

// Six faces at right angles: any angle under 90 degrees gives one chart per face, each a square
// of the face's side times the density.
TEST(Atlas, CubeGivesSixSquareCharts) {
    const std::vector<MeshInput> in = {cube(1.0f)};
    const Atlas a = buildAtlas(in, params(10.0f));
    ASSERT_EQ(a.charts.size(), 6u);
    for (const auto& c : a.charts) {
        EXPECT_EQ(c.triangles, 2);
        EXPECT_EQ(c.width, 10);
        EXPECT_EQ(c.height, 10);
    }
    EXPECT_EQ(a.atlasSizes.size(), 1u);
    EXPECT_EQ(a.meshes[0].indices.size(), 36u);
    EXPECT_EQ(a.meshes[0].sourceVertex.size(), 24u);  // 4 per face, none shared across charts
    expectValidLayout(a);
    EXPECT_NEAR(a.chartTexels, 600.0, 1e-3);
}

TEST(Atlas, PlanarChartsKeepTexelDensityAndAngles) {
    const std::vector<MeshInput> in = {cube(0.75f), tiltedFan()};
    const Atlas a = buildAtlas(in, params(37.0f));
    expectValidLayout(a);
    for (double r : densityRatios(a, in)) EXPECT_NEAR(r, 1.0, 1e-3);
    EXPECT_EQ(a.charts.size(), 7u);  // the fan is one plane: one chart
    for (size_t mi = 0; mi < in.size(); ++mi) {
        const auto& m = a.meshes[mi];
        for (size_t t = 0; t < m.indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                const uint32_t v0 = m.indices[t + size_t(k)], v1 = m.indices[t + size_t(k + 1) % 3],
                               v2 = m.indices[t + size_t(k + 2) % 3];
                const auto P = [&](uint32_t v) { return glm::dvec3(in[mi].positions[m.sourceVertex[v]]); };
                const auto U = [&](uint32_t v) { return glm::dvec3(glm::dvec2(m.uv[v]), 0.0); };
                EXPECT_NEAR(angleAt(P(v0), P(v1), P(v2)), angleAt(U(v0), U(v1), U(v2)), 2e-3);
            }
    }
}

// A sphere: curved charts keep each face's texel area between cos(angle) and 1 of the target
// (projection onto the chart plane), and a smaller angle gives more charts.
TEST(Atlas, CurvedChartsStayWithinTheAngleBound) {
    const std::vector<MeshInput> in = {meshOf(gis::detail::uvSphere(1.0f, 32, 16, 0))};
    AtlasParams p = params(24.0f);
    p.chartAngleDegrees = 30.0f;
    const Atlas a30 = buildAtlas(in, p);
    expectValidLayout(a30);
    const double lo = std::cos(30.0 * 3.14159265358979 / 180.0);
    for (double r : densityRatios(a30, in)) {
        EXPECT_GE(r, lo - 1e-3);
        EXPECT_LE(r, 1.0 + 1e-3);
    }
    p.chartAngleDegrees = 15.0f;
    const Atlas a15 = buildAtlas(in, p);
    expectValidLayout(a15);
    EXPECT_GT(a15.charts.size(), a30.charts.size());
}

// A spiral ramp: its normals all lie within a few degrees of +Y, but seen from above it covers
// itself twice. The projection folds, so the chart must be split until nothing overlaps.
TEST(Atlas, FoldingChartIsSplit) {
    MeshInput m;
    const int steps = 96;
    for (int i = 0; i <= steps; ++i) {
        const float a = 4.0f * 3.14159265f * float(i) / steps, y = 0.05f * float(i) / steps;
        m.positions.push_back({std::cos(a), y, std::sin(a)});
        m.positions.push_back({2.0f * std::cos(a), y, 2.0f * std::sin(a)});
    }
    for (uint32_t i = 0; i < uint32_t(steps); ++i) {
        const uint32_t a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
        m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
    const Atlas a = buildAtlas({m}, params(16.0f));
    EXPECT_GE(a.charts.size(), 2u);
    expectValidLayout(a);
}

// A floor of separate quads (each with corners of its own, as an exporter writes tiles), 6 x 6 of
// them 1 m wide, their corners moved by `nudge` steps of the float on every other quad.
MeshInput tiledFloor(int nudge, float gap = 0.0f) {
    MeshInput m;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            const uint32_t base = uint32_t(m.positions.size());
            for (const glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
                float x = 100.0f + float(i) + c.x * (1.0f - gap), z = 100.0f + float(j) + c.y * (1.0f - gap);
                for (int k = 0; k < ((i + j) % 2) * nudge; ++k) x = std::nextafter(x, 1e9f), z = std::nextafter(z, 1e9f);
                m.positions.push_back({x, 0.0f, z});
            }
            m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
        }
    return m;
}

// Shared corners a few float steps apart are welded: the tiles' floor is one chart, as it is when
// they are exactly equal (the atrium's floor was 1320 charts of a few texels, nearly all gutter).
// Tiles a millimetre apart are not: a real gap keeps them apart.
TEST(Atlas, CornersAFewFloatStepsApartAreWelded) {
    for (int nudge : {0, 1, 3}) {
        const Atlas a = buildAtlas({tiledFloor(nudge)}, params(8.0f));
        EXPECT_EQ(a.charts.size(), 1u) << nudge << " float steps apart";
        expectValidLayout(a);
    }
    const Atlas apart = buildAtlas({tiledFloor(0, 0.001f)}, params(8.0f));
    EXPECT_EQ(apart.charts.size(), 36u);
    expectValidLayout(apart);
}

// Coplanar duplicates (a z-fighting copy) overlap at any angle: they end as charts of their own.
TEST(Atlas, DuplicateFacesGetTheirOwnTexels) {
    MeshInput m = cube(1.0f);
    const size_t n = m.indices.size();
    for (size_t i = 0; i < n; ++i) m.indices.push_back(m.indices[i]);
    const Atlas a = buildAtlas({m}, params(8.0f));
    expectValidLayout(a);
    EXPECT_EQ(a.meshes[0].indices.size(), 2 * n);
}

TEST(Atlas, DegenerateTrianglesAreSkippedAndCounted) {
    MeshInput m = cube(1.0f);
    m.positions.push_back({5, 5, 5});
    m.positions.push_back({6, 6, 6});
    m.positions.push_back({7, 7, 7});  // collinear
    m.indices.insert(m.indices.end(), {24, 25, 26, 0, 0, 1});
    const Atlas a = buildAtlas({m, MeshInput{{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {0, 1, 2}, {}}}, params(8.0f));
    EXPECT_EQ(a.meshes[0].skippedTriangles, 2);
    EXPECT_EQ(a.meshes[0].indices.size(), 36u);
    EXPECT_EQ(a.meshes[1].skippedTriangles, 1);  // a mesh without area: no texels, no failure
    EXPECT_TRUE(a.meshes[1].indices.empty());
    EXPECT_EQ(a.charts.size(), 6u);
    expectValidLayout(a);
}

TEST(Atlas, BadMeshesGiveOneClearError) {
    MeshInput flat{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2}, {}};
    EXPECT_NE(errorOf([&] { buildAtlas({flat}, params(8)); }).find("no triangle has area"), std::string::npos);
    EXPECT_NE(errorOf([&] { buildAtlas({}, params(8)); }).find("no triangle has area"), std::string::npos);
    MeshInput nan = cube(1.0f);
    nan.positions[3].y = std::nanf("");
    EXPECT_NE(errorOf([&] { buildAtlas({nan}, params(8)); }).find("vertex 3 is not finite"), std::string::npos);
    MeshInput range = cube(1.0f);
    range.indices[7] = 99;
    EXPECT_NE(errorOf([&] { buildAtlas({range}, params(8)); }).find("out of range"), std::string::npos);
    MeshInput uvs = cube(1.0f);
    uvs.uv1.resize(3);
    EXPECT_NE(errorOf([&] { buildAtlas({uvs}, params(8)); }).find("TEXCOORD_1"), std::string::npos);
}

TEST(Atlas, AbsurdDensityOrParametersGiveOneClearError) {
    const std::vector<MeshInput> in = {cube(1.0f)};
    for (float d : {0.0f, -4.0f, std::nanf(""), INFINITY}) {
        const std::string e = errorOf([&] { buildAtlas(in, params(d)); });
        EXPECT_NE(e.find("texelsPerMetre"), std::string::npos) << d << ": " << e;
    }
    // Fits no atlas budget: refused before any chart is made, with the density that would fit.
    std::string e = errorOf([&] { buildAtlas(in, params(1e7f)); });
    EXPECT_NE(e.find("texelsPerMetre"), std::string::npos) << e;
    EXPECT_NE(e.find("lower texelsPerMetre (below"), std::string::npos) << e;
    // Fits the budget by area, but one 60-texel face and its gutter do not fit a 64-texel atlas.
    e = errorOf([&] { buildAtlas(in, params(61.0f, 64, 8)); });
    EXPECT_NE(e.find("maxAtlasSize"), std::string::npos) << e;
    // Area within 1 atlas of 64^2 (6 x 24^2 = 3456), but 6 faces with gutters need 2: refused.
    e = errorOf([&] { buildAtlas(in, params(24.0f, 64, 1)); });
    EXPECT_NE(e.find("maxAtlases 1"), std::string::npos) << e;
    AtlasParams p = params(8.0f);
    p.chartAngleDegrees = 90.0f;
    EXPECT_NE(errorOf([&] { buildAtlas(in, p); }).find("chartAngleDegrees"), std::string::npos);
    EXPECT_NE(errorOf([&] { buildAtlas(in, params(8.0f, 8)); }).find("maxAtlasSize"), std::string::npos);
    EXPECT_NE(errorOf([&] { buildAtlas(in, params(8.0f, 2048, 0)); }).find("maxAtlases"), std::string::npos);
    EXPECT_NE(errorOf([&] { buildAtlas(in, params(8.0f, 2048, 4, -1)); }).find("gutter"), std::string::npos);
}

// What does not fit one atlas of the largest size spills into the next.
TEST(Atlas, ChartsSpillIntoMoreAtlases) {
    const Atlas a = buildAtlas({cube(1.0f)}, params(24.0f, 64, 4));
    EXPECT_EQ(a.atlasSizes, (std::vector<int>{64, 64}));
    expectValidLayout(a);
    const Atlas small = buildAtlas({cube(1.0f)}, params(4.0f));
    ASSERT_EQ(small.atlasSizes.size(), 1u);
    EXPECT_LE(small.atlasSizes[0], 24);  // 6 charts of 4+2 texels fit 3 x 2 in a side of 2 + 18
}

TEST(Atlas, SameInputSameHash) {
    const std::vector<MeshInput> in = {cube(1.0f), meshOf(gis::detail::uvSphere(0.5f, 24, 12, 0))};
    const Atlas a = buildAtlas(in, params(20.0f)), b = buildAtlas(in, params(20.0f));
    EXPECT_EQ(a.hash, b.hash);
    EXPECT_EQ(a.hash.size(), 16u);
    EXPECT_NE(buildAtlas(in, params(21.0f)).hash, a.hash);  // every parameter is in the key
    AtlasParams p = params(20.0f);
    p.gutter = 3;
    EXPECT_NE(buildAtlas(in, p).hash, a.hash);
    std::vector<MeshInput> moved = in;
    moved[0].positions[0].x += 0.01f;  // a cube face is no longer square
    EXPECT_NE(buildAtlas(moved, params(20.0f)).hash, a.hash);
}
