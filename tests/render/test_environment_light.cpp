// The environment as a light of the direct pass (emitters.environment, renderer/emitters/): ReSTIR
// draws candidates from the environment with a visibility ray each, so a sky and a map's sun cast
// their shadows under every method, and the GI methods carry only the environment's indirect
// light. Checked against the path tracer on a floor under a roof with a hole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_util.h"
#include "environment.h"
#include "gi/method.h"
#include "render_test_util.h"
#include "scene/mesh_builders.h"

namespace gis::test {
namespace {

constexpr int kSize = 64;
constexpr float kTile = 0.5f;  // the roof's tiles; the hole is the middle one

// A 4 m white floor under a 2.5 m roof at 1 m with a hole of one tile in its middle, seen from
// under the roof's edge: the sky reaches the floor around the roof and through the hole.
Scene roofScene() {
    Scene s;
    s.name = "roof-with-hole";
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    s.materials.push_back(lambert(glm::vec3(0.6f), true));
    addQuad(s, glm::vec3(0.0f), glm::vec3(0, 1, 0), 4.0f, 0);
    for (int i = -2; i <= 2; ++i)
        for (int j = -2; j <= 2; ++j)
            if (i != 0 || j != 0) addQuad(s, glm::vec3(i * kTile, 1.0f, j * kTile), glm::vec3(0, -1, 0), kTile, 1);
    s.cameras.push_back(lookAtCamera({0.0f, 0.75f, 1.3f}, {-0.35f, 0.0f, -0.2f}, 60.0f));
    finalizeScene(s);
    return s;
}

RenderSettings environmentLit(const std::string& gi) {
    RenderSettings s;
    s.width = s.height = kSize;
    s.gi = gi;
    s.ambient = glm::vec3(0.0f);
    setParam(s, "emitters.environment", "true");
    return s;
}

RenderSettings pathTraced(RenderSettings s, int spp, int bounces) {
    s.gi = "pathtrace";
    s.samplesPerFrame = 16;
    setParam(s, "pathtrace.spp", std::to_string(spp));
    setParam(s, "pathtrace.bounces", std::to_string(bounces));
    return s;
}

// The mean of R, G, B over the pixels whose mask value is `inside`.
double channelMean(const ImageF& img, const std::vector<bool>& mask, bool inside) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i] == inside) sum += (img.rgba[i * 4] + img.rgba[i * 4 + 1] + img.rgba[i * 4 + 2]) / 3.0, ++n;
    return n ? sum / n : 0.0;
}

// Under a constant sky, the direct pass's environment light is the path tracer's direct light
// (one bounce: the sky seen from the first surface), shadows of the roof included: the image and
// each quadrant's mean.
TEST(EnvironmentLight, SkyShadowsAreThePathTracersDirectLight) {
    const Scene scene = roofScene();
    RenderSettings s = environmentLit("none");
    s.background = glm::vec3(0.8f, 0.9f, 1.0f);
    setParam(s, "emitters.accumulate", "256");
    const ImageF restir = renderHdr(scene, s);
    const ImageF reference = renderHdr(scene, pathTraced(s, 512, 0));
    ASSERT_TRUE(allFinite(restir));
    const ImageF a = downsample(restir, kSize / 2), b = downsample(reference, kSize / 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a.at(x, y)[c], b.at(x, y)[c], 0.03 * b.at(x, y)[c]) << "quadrant " << x << "," << y << " channel " << c;
}

// The environment's direct light has a view of its own: under a sky alone it is the whole direct
// view, and it exists only when the environment is a light.
TEST(EnvironmentLight, ItsDirectLightHasAViewOfItsOwn) {
    const Scene scene = roofScene();
    RenderSettings s = environmentLit("none");
    s.background = glm::vec3(0.8f, 0.9f, 1.0f);
    setParam(s, "emitters.accumulate", "4");
    RenderSettings direct = s, environment = s;
    direct.view = "direct";
    environment.view = "emitters.environment";
    const ImageF a = renderHdr(scene, direct), b = renderHdr(scene, environment);
    double sum = 0, largest = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        sum += b.rgba[i];
        largest = std::max(largest, double(std::abs(a.rgba[i] - b.rgba[i])));
    }
    EXPECT_GT(sum, 0.0);
    EXPECT_LE(largest, 1e-3);
    setParam(environment, "emitters.environment", "false");
    EXPECT_THROW(renderHdr(scene, environment), Error);
}

// A uniform map and a constant of the same value are the same light (drawn by luminance and by
// the cosine: the same mean).
TEST(EnvironmentLight, UniformMapEqualsBackground) {
    const std::string file = tempDir("environment_light_uniform") + "/uniform.hdr";
    writeHdr(file, 32, 16, [](glm::vec3) { return glm::vec3(0.75f, 0.5f, 0.25f); });
    const glm::vec3 value = loadEnvironmentMap(file).texels[0];
    const Scene scene = roofScene();
    RenderSettings constant = environmentLit("none");
    setParam(constant, "emitters.accumulate", "256");
    RenderSettings map = constant;
    constant.background = value;
    map.environment = file;
    const ImageF a = downsample(renderHdr(scene, constant), kSize / 2), b = downsample(renderHdr(scene, map), kSize / 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a.at(x, y)[c], b.at(x, y)[c], 0.02 * b.at(x, y)[c]) << "quadrant " << x << "," << y << " channel " << c;
}

// A map black but for a small bright patch (a sun 3x3 texels wide, 53 degrees up) lights the floor
// through the roof's hole and beyond the roof. On the floor the sun sees (cast on the CPU towards
// the patch's centre; shadow edges left out for the patch's penumbra) the baselines without
// indirect light (none, ssao) show the path tracer's direct light (within 5%) and the GI methods
// its whole light (within 15%: their indirect error); on the floor the roof shades, every method
// holds only bounced light (under a quarter of the sunlit floor's; none and ssao the path
// tracer's direct light there, the wide patch's penumbra, within 15%): the spot is where the path
// tracer puts it. (Before the environment's radiance was read by texel, as its sampler draws it,
// none's sunlit floor was 0.86 of the path tracer's: the filtered texels shone where no candidate
// was drawn.)
TEST(EnvironmentLight, ASunInTheMapLightsTheSpotThroughTheRoofEveryMethod) {
    const std::string file = tempDir("environment_light_sun") + "/sun.hdr";
    const glm::ivec2 sunTexel(40, 6), mapSize(64, 32);
    writeHdrTexels(file, mapSize.x, mapSize.y, [&](glm::vec2 uv) {
        const glm::ivec2 t(uv * glm::vec2(mapSize));
        return glm::all(glm::lessThanEqual(glm::abs(t - sunTexel), glm::ivec2(1))) ? glm::vec3(60.0f) : glm::vec3(0.0f);
    });
    const Scene scene = roofScene();
    const glm::vec3 sun = 1e3f * equirectToDirection((glm::vec2(sunTexel) + 0.5f) / glm::vec2(mapSize));
    const std::vector<PixelHit> hits = castPixels(scene, 0, kSize, kSize, &sun);
    const std::vector<bool> interior = interiorPixels(hits, kSize, kSize, 1, 3);
    std::vector<bool> lit(hits.size()), shaded(hits.size());
    int litCount = 0, shadedCount = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
        const bool floor = hits[i].region >= 0 && hits[i].region < 8 && interior[i];  // draw 0: the floor
        lit[i] = floor && hits[i].lit, shaded[i] = floor && !hits[i].lit;
        litCount += lit[i], shadedCount += shaded[i];
    }
    ASSERT_GT(litCount, 50) << "the sunlit floor is not in view";
    ASSERT_GT(shadedCount, 50) << "the shaded floor is not in view";
    RenderSettings base = environmentLit("none");
    base.environment = file;
    const ImageF direct = renderHdr(scene, pathTraced(base, 256, 0)), full = renderHdr(scene, pathTraced(base, 256, 4));
    for (const GiMethod& m : giMethods()) {
        if (m.pipeline != MethodPipeline::Deferred || m.name == "lightmap") continue;
        SCOPED_TRACE(m.name);
        RenderSettings s = base;
        s.gi = m.name;
        const ImageF img = renderHdr(scene, s);
        ASSERT_TRUE(allFinite(img));
        const bool baseline = m.name == "none" || m.name == "ssao";
        const ImageF& reference = baseline ? direct : full;
        const double litMean = channelMean(img, lit, true), shadedMean = channelMean(img, shaded, true);
        const double litReference = channelMean(reference, lit, true), shadedReference = channelMean(reference, shaded, true);
        std::printf("[ measured ] %s: sunlit floor %.3f (path tracer %.3f), shaded floor %.4f (%.4f)\n", m.name.c_str(),
                    litMean, litReference, shadedMean, shadedReference);
        EXPECT_NEAR(litMean, litReference, (baseline ? 0.05 : 0.15) * litReference);
        if (baseline) {
            EXPECT_NEAR(shadedMean, shadedReference, 0.15 * shadedReference);
        }
        EXPECT_LT(shadedMean, 0.25 * litMean);
    }
}

// No method counts the sky twice: with the environment a light of the direct pass, each deferred
// GI method's image of the roof under a constant sky has the path tracer's mean (within 10%: the
// methods' own indirect error), where counting the sky's direct light twice adds most of it again;
// the baselines without indirect light (none, ssao) stay below it.
TEST(EnvironmentLight, EveryMethodCountsTheSkyOnce) {
    const Scene scene = roofScene();
    RenderSettings base = environmentLit("none");
    base.background = glm::vec3(0.8f, 0.9f, 1.0f);
    const ImageF reference = renderHdr(scene, pathTraced(base, 256, 4));
    const std::vector<bool> all(size_t(kSize * kSize), true);
    const double target = channelMean(reference, all, true);
    for (const GiMethod& m : giMethods()) {
        if (m.pipeline != MethodPipeline::Deferred) continue;
        SCOPED_TRACE(m.name);
        RenderSettings s = base;
        s.gi = m.name;
        const double mean = channelMean(renderHdr(scene, s), all, true);
        std::printf("[ measured ] %s: mean %.4f, path tracer %.4f (%.3f)\n", m.name.c_str(), mean, target, mean / target);
        if (m.name == "none" || m.name == "ssao") {
            EXPECT_LT(mean, target);
        } else {
            EXPECT_NEAR(mean, target, 0.1 * target);
        }
    }
}

}  // namespace
}  // namespace gis::test
