// The check of a file's TEXCOORD_1 (renderer/lightmap/uv_overlap.cpp): which layouts pass, and
// that each rejection says why.
#include <gtest/gtest.h>

#include "lightmap/atlas.h"
#include "lightmap_test_util.h"
#include "scene/test_util.h"

using gis::lightmap::checkUvCharts;

namespace {

// Two quads side by side in UV: shared vertices touch, nothing overlaps.
const std::vector<glm::vec2> kTwoQuads = {{0.0f, 0.0f}, {0.5f, 0.0f}, {0.5f, 0.5f}, {0.0f, 0.5f},
                                          {1.0f, 0.0f}, {1.0f, 0.5f}};
const std::vector<uint32_t> kTwoQuadIndices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};

}  // namespace

TEST(UvCheck, TouchingChartsPass) {
    EXPECT_TRUE(checkUvCharts(kTwoQuads, kTwoQuadIndices).ok) << checkUvCharts(kTwoQuads, kTwoQuadIndices).reason;
}

TEST(UvCheck, OverlapIsRejectedWithTheTriangles) {
    std::vector<glm::vec2> uv = kTwoQuads;
    uv[4] = {0.4f, 0.0f};  // the second quad now reaches back over the first
    uv[5] = {0.4f, 0.5f};
    const auto check = checkUvCharts(uv, kTwoQuadIndices);
    EXPECT_FALSE(check.ok);
    EXPECT_NE(check.reason.find("overlap"), std::string::npos) << check.reason;
    // A triangle wholly inside another (no edge crosses) is an overlap too.
    const std::vector<glm::vec2> nested = {{0, 0}, {1, 0}, {0, 1}, {0.1f, 0.1f}, {0.2f, 0.1f}, {0.1f, 0.2f}};
    EXPECT_FALSE(checkUvCharts(nested, {0, 1, 2, 3, 4, 5}).ok);
    // The same triangle twice (e.g. both sides of a double-sided wall sharing texels).
    EXPECT_FALSE(checkUvCharts(kTwoQuads, {0, 1, 2, 2, 1, 0}).ok);
}

TEST(UvCheck, OutsideUnitSquareNonFiniteAndCollapsedAreRejected) {
    std::vector<glm::vec2> uv = kTwoQuads;
    uv[4].x = 1.25f;
    auto check = checkUvCharts(uv, kTwoQuadIndices);
    EXPECT_FALSE(check.ok);
    EXPECT_NE(check.reason.find("outside [0,1]"), std::string::npos) << check.reason;
    uv = kTwoQuads;
    uv[2].y = std::nanf("");
    check = checkUvCharts(uv, kTwoQuadIndices);
    EXPECT_NE(check.reason.find("non-finite"), std::string::npos) << check.reason;
    uv = kTwoQuads;
    uv[2] = uv[1];
    check = checkUvCharts(uv, kTwoQuadIndices);
    EXPECT_NE(check.reason.find("no area"), std::string::npos) << check.reason;
    EXPECT_NE(checkUvCharts(kTwoQuads, {0, 1, 9}).reason.find("vertex 9"), std::string::npos);
}

// Many small triangles in a fine grid, all touching: the grid buckets must neither miss an
// overlap placed late nor report touching neighbours.
TEST(UvCheck, LargeGridPassesAndOneMovedVertexFails) {
    const int n = 100;
    std::vector<glm::vec2> uv;
    std::vector<uint32_t> idx;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) uv.push_back(glm::vec2(x, y) / float(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            idx.insert(idx.end(), {a, b, d, a, d, c});
        }
    EXPECT_TRUE(checkUvCharts(uv, idx).ok);
    uv[size_t(77 * (n + 1) + 55)] += glm::vec2(0.015f, 0.0f);  // over its right neighbour's triangles
    EXPECT_FALSE(checkUvCharts(uv, idx).ok);
}

// End to end: a glTF whose second UV set is valid is used as laid out (one rectangle of the
// atlas per instance: two draws of one mesh are lit differently); one whose charts overlap is
// rejected with the reason and the atlas is generated.
TEST(UvCheck, FileUvsFromGltfUsedOrRejected) {
    gistest::GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}});
    std::vector<glm::vec2> uv1 = {{0.1f, 0.1f}, {0.45f, 0.1f}, {0.45f, 0.45f}, {0.1f, 0.45f},
                                  {0.8f, 0.1f}, {0.8f, 0.45f}};
    const int tc1 = g.addVec2(uv1);
    const int ind = g.addIndices(kTwoQuadIndices);
    const int mesh = g.addMesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_1", tc1}}}, {"indices", ind}});
    g.addMeshNode(mesh);
    g.addMeshNode(mesh, {{"translation", {0, 0, 3}}});
    gis::Scene scene = g.load();
    ASSERT_EQ(scene.primitives.size(), 1u);
    gis::lightmap::AtlasParams p;
    p.texelsPerMetre = 32.0f;
    gis::lightmap::Atlas a = gis::lightmap::buildAtlas(gis::lightmap::meshesFromScene(scene), p);
    ASSERT_EQ(a.meshes.size(), 2u);
    EXPECT_TRUE(a.meshes[0].fileUvs && a.meshes[1].fileUvs);
    EXPECT_EQ(a.meshes[0].fileUvsRejected, "");
    ASSERT_EQ(a.charts.size(), 2u);
    EXPECT_TRUE(a.charts[0].fromFile);
    EXPECT_NEAR(a.charts[0].width, 64, 1);  // 2 m wide at 32 texels per metre
    EXPECT_NEAR(a.charts[1].width, 64, 1);
    lmtest::expectValidLayout(a);

    scene.primitives[0].uv1[4] = {0.3f, 0.1f};  // the second quad folds back over the first
    scene.primitives[0].uv1[5] = {0.3f, 0.45f};
    a = gis::lightmap::buildAtlas(gis::lightmap::meshesFromScene(scene), p);
    EXPECT_FALSE(a.meshes[0].fileUvs);
    EXPECT_NE(a.meshes[0].fileUvsRejected.find("overlap"), std::string::npos) << a.meshes[0].fileUvsRejected;
    EXPECT_FALSE(a.charts[0].fromFile);
    lmtest::expectValidLayout(a);
    p.useFileUvs = false;  // valid or not, the parameter generates
    scene.primitives[0].uv1 = uv1;
    EXPECT_FALSE(gis::lightmap::buildAtlas(gis::lightmap::meshesFromScene(scene), p).meshes[0].fileUvs);
}
