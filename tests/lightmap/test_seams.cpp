// Seams (renderer/lightmap/seams.h): found where a smooth surface's charts meet and nowhere else,
// and stitched so both sides read the same while texels away from them keep their light.
#include <random>

#include "lightmap/seams.h"
#include "lightmap_test_util.h"

using namespace lmtest;
using gis::lightmap::SeamPoint;
using gis::lightmap::SeamVertex;
using gis::lightmap::TexelImage;

namespace {

// The atlas's vertices as the bake draws them, normals taken from the source primitive.
struct Laid {
    Atlas atlas;
    std::vector<SeamVertex> vertices;
    std::vector<uint32_t> indices;
};

Laid layOut(const gis::Primitive& p, float texelsPerMetre) {
    Laid out;
    AtlasParams params;
    params.texelsPerMetre = texelsPerMetre;
    out.atlas = gis::lightmap::buildAtlas({meshOf(p)}, params);
    const auto& m = out.atlas.meshes[0];
    const float side = float(out.atlas.atlasSizes[0]);
    for (size_t v = 0; v < m.sourceVertex.size(); ++v) {
        const gis::Vertex& src = p.vertices[m.sourceVertex[v]];
        out.vertices.push_back({src.position, src.normal, m.uv[v] * side, out.atlas.atlasOf(0, v)});
    }
    out.indices = m.indices;
    return out;
}

// Every texel of every chart's rectangle holds light of its own: a smooth field plus noise.
TexelImage noisyLight(const Atlas& a, float noise, unsigned seed) {
    TexelImage image{std::vector<float>(size_t(a.atlasSizes[0]) * size_t(a.atlasSizes[0]) * 4, 0.0f), a.atlasSizes[0], 1};
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.0f, noise);
    for (const auto& c : a.charts)
        for (int y = c.y - 1; y < c.y + c.height + 1; ++y)
            for (int x = c.x - 1; x < c.x + c.width + 1; ++x) {
                float* t = image.at(x, y, 0);
                for (int k = 0; k < 3; ++k) t[k] = std::max(0.0f, 1.0f + n(rng));
                t[3] = 1.0f;
            }
    return image;
}

double worstGap(const std::vector<SeamPoint>& points, const TexelImage& image) {
    double worst = 0.0;
    for (const SeamPoint& p : points) {
        glm::vec3 a, b;
        if (!gis::lightmap::lookUp(image, p.a, p.layerA, a) || !gis::lightmap::lookUp(image, p.b, p.layerB, b)) continue;
        worst = std::max(worst, double(glm::length(a - b)));
    }
    return worst;
}

}  // namespace

TEST(Seams, ASmoothSphereSplitIntoChartsHasThemABoxHasNone) {
    const Laid sphere = layOut(gis::detail::uvSphere(1.0f, 32, 16, 0), 16.0f);
    ASSERT_GT(sphere.atlas.charts.size(), 4u);
    const std::vector<SeamPoint> points = gis::lightmap::findSeams(sphere.vertices, sphere.indices);
    EXPECT_GT(points.size(), 100u);
    for (const SeamPoint& p : points) EXPECT_NE(p.a, p.b);  // two places in the atlas
    const Laid box = layOut(gis::detail::unitCube(0), 16.0f);
    EXPECT_EQ(box.atlas.charts.size(), 6u);
    EXPECT_TRUE(gis::lightmap::findSeams(box.vertices, box.indices).empty()) << "a box's edges are creases";
}

// Noise of 10% on every texel leaves the two sides of the sphere's seams far apart; stitched they
// read the same within a tenth of that noise (the points' equations are nearly dependent where they
// share texels, so the solver converges slowly), and the texels move by under a third of the noise
// on average. A direction's negative components stay negative.
TEST(Seams, StitchingMakesBothSidesReadTheSameAndMovesLittle) {
    const Laid sphere = layOut(gis::detail::uvSphere(1.0f, 32, 16, 0), 16.0f);
    const std::vector<SeamPoint> points = gis::lightmap::findSeams(sphere.vertices, sphere.indices);
    TexelImage image = noisyLight(sphere.atlas, 0.1f, 7);
    const TexelImage before = image;
    const double gapBefore = worstGap(points, image);
    const float left = gis::lightmap::stitchSeams(points, image).after;
    const double gapAfter = worstGap(points, image);
    std::printf("seams: %zu points, worst gap %.4f before, %.5f after (relative %.5f)\n", points.size(), gapBefore,
                gapAfter, left);
    const double tenthOfTheNoise = 0.01;
    EXPECT_GT(gapBefore, 0.1);
    EXPECT_LT(gapAfter, tenthOfTheNoise);
    double moved = 0.0;
    size_t texels = 0, untouched = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        if (image.rgba[i + 3] != 1.0f) continue;
        const double d = std::abs(image.rgba[i] - before.rgba[i]);
        moved += d;
        ++texels;
        untouched += d == 0.0 ? 1 : 0;
    }
    EXPECT_LT(moved / double(texels), 0.03) << "the mean move, against noise of 0.1";
    EXPECT_GT(untouched, texels / 2) << "texels away from the seams keep their light";

    // The same with values around 0 that are no light (a direction's components): stitched as they
    // are, none clamped.
    TexelImage direction = noisyLight(sphere.atlas, 0.1f, 11);
    for (size_t i = 0; i < direction.rgba.size(); i += 4)
        if (direction.rgba[i + 3] == 1.0f) direction.rgba[i] -= 1.0f;
    gis::lightmap::stitchSeams(points, direction, 256, false);
    EXPECT_LT(worstGap(points, direction), tenthOfTheNoise);
    size_t negative = 0;
    for (size_t i = 0; i < direction.rgba.size(); i += 4) negative += direction.rgba[i + 3] == 1.0f && direction.rgba[i] < 0.0f;
    EXPECT_GT(negative, texels / 4) << "a direction's negative components were clamped";
}
