// `--gi lightmap` (issue #41): the bake against what a surface must receive, the light kept on its
// side of a wall, the cache, the atlas at every scale and a density past the atlases refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "error.h"
#include "gi/lightmap/lightmap_settings.h"
#include "gi/method.h"
#include "render_test_util.h"
#include "renderer.h"

using namespace gis;
using namespace gis::test;

namespace {

RenderSettings lightmapSettings(int size, int texels, int samples) {
    RenderSettings s;
    s.width = s.height = size;
    s.gi = "lightmap";
    s.hdr32 = true;
    s.ambient = glm::vec3(0.0f);
    setParam(s, "lightmap.texels", std::to_string(texels));
    setParam(s, "lightmap.samples", std::to_string(samples));
    setParam(s, "lightmap.cache", "false");
    return s;
}

// Renders until the bake is done; returns the lighting contract's indirect.diffuse.
ImageF bakedIndirect(Renderer& r) {
    do r.renderFrame();
    while (!r.converged());
    EXPECT_EQ(r.nonFiniteReport(), "");
    return readTextureFloat(r.frameTexture("indirect.diffuse"), r.settings().width, r.settings().height);
}

std::vector<std::string> lightmapStats(const Renderer& r) {
    for (const auto& pass : r.passes())
        if (std::string(pass->name()) == "lightmap") return pass->stats();
    return {};
}

bool statsSay(const Renderer& r, const std::string& text) {
    for (const std::string& line : lightmapStats(r))
        if (line.find(text) != std::string::npos) return true;
    return false;
}

// A floor of 4 x 4 units seen from above, under `background` alone.
Scene floorScene() {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.5f)));
    addQuad(s, glm::vec3(0.0f), glm::vec3(0, 1, 0), 4.0f, 0);
    s.cameras.push_back(lookAtCamera({0.0f, 6.0f, 0.01f}, {0, 0, 0}, 60.0f));
    finalizeScene(s);
    return s;
}

// The floor with a wall standing on it along z (two faces 0.1 apart, taller and longer than the
// floor is wide, so no light goes round it) and a point light low on the -x side: the +x side
// gets no light in truth, neither direct nor bounced.
Scene wallOnAFloor() {
    Scene s = floorScene();
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    addQuad(s, glm::vec3(-0.05f, 0.0f, 0.0f), glm::vec3(-1, 0, 0), 6.0f, 1);
    addQuad(s, glm::vec3(0.05f, 0.0f, 0.0f), glm::vec3(1, 0, 0), 6.0f, 1);
    Light light;
    light.type = LightType::Point;
    light.intensity = 4.0f;
    light.position = {-1.0f, 0.5f, 0.0f};
    s.lights.push_back(light);
    finalizeScene(s);
    return s;
}

}  // namespace

// Under a uniform sky of radiance L an open upward plane receives E = pi L: the bake's
// indirect.diffuse (E / pi) is L.
TEST(Lightmap, APlaneUnderAUniformSkyGetsTheSkysIrradiance) {
    context();
    RenderSettings s = lightmapSettings(64, 1024, 16);
    s.background = glm::vec3(0.5f);
    const Scene scene = floorScene();
    Renderer r(scene, s);
    const ImageF indirect = bakedIndirect(r);
    const double centre = meanAround(indirect, 32, 32, 8);
    std::printf("LIGHTMAP plane under a sky of 0.5: indirect.diffuse %.4f\n", centre);
    EXPECT_NEAR(centre, 0.5, 0.01);
}

// The wall's lit side and its dark side right beside it, one texel (15 cm here) from the wall:
// the dark side stays below 1% of the lit side. The floor's texels run under the wall and its
// texels are wider than the wall is thick; before classify.comp, the lookup's bilinear taps and
// the denoiser carried the lit side's light under and across it.
TEST(Lightmap, AWallOnAFloorKeepsTheLightOnItsSide) {
    context();
    const Scene scene = wallOnAFloor();
    RenderSettings s = lightmapSettings(128, 4096, 64);
    Renderer r(scene, s);
    const ImageF indirect = bakedIndirect(r);
    double lit = 0.0, dark = 0.0;
    for (float z : {-1.5f, -0.5f, 0.5f, 1.5f}) {
        const glm::ivec2 l = projectToPixel(scene, s, {-0.15f, 0.0f, z}), d = projectToPixel(scene, s, {0.15f, 0.0f, z});
        lit += meanAround(indirect, l.x, l.y, 1) + meanAround(indirect, l.x, l.y, 1, 1) + meanAround(indirect, l.x, l.y, 1, 2);
        dark += meanAround(indirect, d.x, d.y, 1) + meanAround(indirect, d.x, d.y, 1, 1) + meanAround(indirect, d.x, d.y, 1, 2);
    }
    std::printf("LIGHTMAP wall on a floor: dark side %.5f, lit side %.5f (%s)\n", dark, lit,
                lightmapStats(r).empty() ? "" : lightmapStats(r)[0].c_str());
    ASSERT_GT(lit, 0.0);
    EXPECT_LE(dark, 0.01 * lit);
}

// A finished bake is written under its content id; the same scene's next renderer reads it and
// traces nothing; a light edited (a different content id) bakes again.
TEST(Lightmap, TheSecondRunReadsTheCacheAndAnEditedLightBakesAgain) {
    context();
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "gis-lightmap-cache-test";
    std::filesystem::remove_all(folder);
    const char* before = std::getenv("GIS_LIGHTMAP_CACHE");
    const std::string saved = before ? before : "";
    setenv("GIS_LIGHTMAP_CACHE", folder.c_str(), 1);
    Scene scene = wallOnAFloor();
    RenderSettings s = lightmapSettings(32, 1024, 8);
    setParam(s, "lightmap.cache", "true");
    ImageF first;
    {
        Renderer r(scene, s);
        first = bakedIndirect(r);
        EXPECT_TRUE(statsSay(r, "cache: written")) << lightmapStats(r).back();
    }
    {
        Renderer r(scene, s);
        r.renderFrame();
        EXPECT_TRUE(r.converged()) << "the cached bake is complete after one frame";
        EXPECT_TRUE(statsSay(r, "cache: read")) << lightmapStats(r).back();
        for (const auto& pass : r.passes()) {
            if (std::string(pass->name()) != "lightmap") continue;
            EXPECT_EQ(pass->raysTraced()->total(), 0u) << "no path traced";
        }
        for (const PassTiming& t : r.timings(0))
            EXPECT_TRUE(t.pass != "lightmap" || t.samples == 0) << "--timings: a bake read is no sample made";
        const ImageF again = readTextureFloat(r.frameTexture("indirect.diffuse"), 32, 32);
        EXPECT_EQ(again.rgba, first.rgba) << "the cached bake looks up as the baked one";
    }
    scene.lights[0].intensity *= 2.0f;
    {
        Renderer r(scene, s);
        r.renderFrame();
        EXPECT_TRUE(statsSay(r, "cache: miss")) << lightmapStats(r).back();
        EXPECT_FALSE(r.converged());
    }
    if (before) setenv("GIS_LIGHTMAP_CACHE", saved.c_str(), 1);
    else unsetenv("GIS_LIGHTMAP_CACHE");
    std::filesystem::remove_all(folder);
}

// The density follows from lightmap.texels over the surfaces' area: the Cornell box at x1e-3 and
// x1e3 gets the atlas it gets at x1, texel for texel.
TEST(Lightmap, TheAtlasDoesNotDependOnTheUnitOfLength) {
    const Scene cornell = makeBuiltinScene("cornell");
    const LightmapSettings defaults;
    const lightmap::Atlas unit = lightmapAtlas(cornell, defaults);
    for (float scale : {1e-3f, 1e3f}) {
        const lightmap::Atlas scaled = lightmapAtlas(scaledScene(cornell, scale), defaults);
        EXPECT_EQ(scaled.atlasSizes, unit.atlasSizes) << "scale " << scale;
        ASSERT_EQ(scaled.charts.size(), unit.charts.size()) << "scale " << scale;
        for (size_t c = 0; c < unit.charts.size(); ++c) {
            const lightmap::Chart &a = unit.charts[c], &b = scaled.charts[c];
            EXPECT_TRUE(a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height)
                << "scale " << scale << " chart " << c << ": " << b.width << "x" << b.height << " at " << b.x << ","
                << b.y << " against " << a.width << "x" << a.height << " at " << a.x << "," << a.y;
        }
    }
}

// A density whose texels need more than the atlases is refused before anything is built, in one
// message naming the parameter that asked for it.
TEST(Lightmap, ADensityPastTheAtlasesIsOneErrorNamingIt) {
    context();
    RenderSettings s = lightmapSettings(32, 1024, 1);
    setParam(s, "lightmap.texels-per-metre", "100000");
    const Scene scene = makeBuiltinScene("cornell");
    try {
        Renderer r(scene, s);
        FAIL() << "built a lightmap at 1e5 texels per unit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lightmap.texels-per-metre"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
}

// The texels the atlas puts on the surfaces and the regions classify.comp splits them into are the
// same at x1e-3 and x1e3 as at x1 (the rays it traces are a texel long, in world units).
TEST(Lightmap, TheTexelsAndTheirRegionsDoNotDependOnTheUnitOfLength) {
    context();
    const Scene cornell = makeBuiltinScene("cornell");
    for (int texels : {4096, 16384}) {
    const RenderSettings s = lightmapSettings(32, texels, 1);
    std::string unit;
    for (float scale : {1.0f, 1e-3f, 1e3f}) {
        const Scene scaled = scaledScene(cornell, scale);  // the renderer keeps a reference to its scene
        Renderer r(scaled, s);
        r.renderFrame();
        std::string line = lightmapStats(r).at(0);
        line = line.substr(0, line.find(" texels per unit"));
        line = line.substr(0, line.rfind(','));  // the density itself scales
        std::printf("LIGHTMAP x%g: %s\n", scale, line.c_str());
        if (scale == 1.0f) unit = line;
        else EXPECT_EQ(line, unit) << "scale " << scale;
    }
    }
}

namespace {
bool isMagenta(const float* p) { return p[0] == 1.0f && p[1] == 0.0f && p[2] == 1.0f; }
bool isCyan(const float* p) { return p[0] == 0.0f && p[1] == 1.0f && p[2] == 1.0f; }
bool isBlack(const float* p) { return p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f; }
float brightest(const float* p) { return std::max(p[0], std::max(p[1], p[2])); }

template <typename Test>
int countPixels(const ImageF& image, Test test) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) n += test(image.at(x, y)) ? 1 : 0;
    return n;
}
}  // namespace

// lightmap.seams: the charts' edges in magenta, the rest grey. On the Cornell box every wall is one
// chart: its rim is marked, its middle is not.
TEST(Lightmap, TheSeamsViewMarksTheChartsEdgesOnly) {
    RenderSettings s = lightmapSettings(64, 1024, 4);
    s.view = "lightmap.seams";
    const ImageF image = renderHdr(makeBuiltinScene("cornell"), s);
    const auto isGrey = [](const float* p) { return p[0] == p[1] && p[1] == p[2] && p[0] >= 0.25f && p[0] <= 0.75f; };
    const int pixels = image.width * image.height, edges = countPixels(image, isMagenta),
              grey = countPixels(image, isGrey);
    EXPECT_GT(edges, pixels / 50) << "the walls' rims are chart edges";
    EXPECT_LT(edges, pixels / 2);
    EXPECT_GT(grey, pixels / 2);
    EXPECT_EQ(countPixels(image, [&](const float* p) { return !isMagenta(p) && !isGrey(p) && !isBlack(p); }), 0)
        << "every surface pixel an edge or the grey light (black: no surface)";
    EXPECT_FALSE(isMagenta(image.at(image.width / 2, image.height / 4))) << "the back wall's middle is one chart";
}

// lightmap.atlas: the atlas's layers across the image, chart borders magenta, the Cornell floor's
// texels under the blocks (inside geometry) cyan, every other chart texel its normalised light.
TEST(Lightmap, TheAtlasViewShowsTheChartsTheirBordersAndTheTexelsInsideGeometry) {
    RenderSettings s = lightmapSettings(128, 4096, 4);
    s.view = "lightmap.atlas";
    const ImageF image = renderHdr(makeBuiltinScene("cornell"), s);
    const int borders = countPixels(image, isMagenta), inside = countPixels(image, isCyan);
    // Normalised light: its brightest channel is 1.
    const int lit = countPixels(image, [](const float* p) { return !isMagenta(p) && !isCyan(p) && brightest(p) > 0.99f; });
    EXPECT_GT(borders, 100);
    EXPECT_GT(inside, 10) << "the blocks stand on the floor's texels";
    EXPECT_GT(lit, borders) << "the charts' insides show their light";
}

// lightmap.mode=all: the bake holds the lights' direct light too (sampled at each texel as the
// path tracer samples them at a vertex, MIS against the texel's ray) and the frame draws none of its own:
// no emitter pass, no shadow maps. The image is the one the lighting pass lights itself, but for
// the lights' specular highlights, the shadows at the texels' resolution and the denoiser's blur of
// 64 paths (512 bring cornell-area's thirds within 2% of the path tracer): per third of the image
// within 8%. A bake that misses the direct light is several times darker; a frame that also draws
// it, twice as bright where it falls.
TEST(Lightmap, ABakeOfAllTheLightDrawsNoLightOfItsOwnAndKeepsTheImage) {
    for (const char* name : {"cornell", "cornell-area"}) {
        const Scene scene = makeBuiltinScene(name);
        context();
        ImageF images[2];
        for (int all = 0; all < 2; ++all) {
            RenderSettings s = lightmapSettings(64, 4096, 64);
            setParam(s, "lightmap.mode", all ? "all" : "indirect");
            Renderer r(scene, s);
            bakedIndirect(r);
            images[all] = r.readHdr();
            EXPECT_EQ(statsSay(r, "all the light"), all == 1) << name;
            bool emitterPass = false;
            for (const auto& pass : r.passes()) emitterPass = emitterPass || std::string(pass->name()) == "emitters";
            const int64_t shadowBytes = r.memory().bytesByOwner.count("shadows") ? r.memory().bytesByOwner.at("shadows") : 0;
            if (all) {
                EXPECT_FALSE(emitterPass) << name << ": the frame still draws the emitters' light";
                EXPECT_LT(shadowBytes, 65536) << name << ": shadow maps made";
            }
        }
        ASSERT_TRUE(allFinite(images[1]));
        for (int third = 0; third < 3; ++third) {
            double sum[2] = {0.0, 0.0};
            for (int i = 0; i < 2; ++i)
                for (int y = 0; y < 64; ++y)
                    for (int x = third * 64 / 3; x < (third + 1) * 64 / 3; ++x)
                        for (int c = 0; c < 3; ++c) sum[i] += images[i].at(x, y)[c];
            std::printf("LIGHTMAP-TABLE mode all %s third %d: %.4f of the lit frame's\n", name, third, sum[1] / sum[0]);
            EXPECT_NEAR(sum[1] / sum[0], 1.0, 0.08) << name << " third " << third;
        }
    }
}

// Seams in a real bake: the Cornell box's chart borders are all creases (nothing to stitch: the
// light differs across them in truth); the mirror scene's spheres are smooth surfaces split into
// charts, and their seams are stitched to a few percent of the light (the CPU stitcher's own
// measure; tests/lightmap/test_seams.cpp checks the stitcher), without moving the image's light.
TEST(Lightmap, SmoothSurfacesSeamsAreStitchedAndABoxHasNone) {
    context();
    {
        const Scene cornell = makeBuiltinScene("cornell");
        Renderer r(cornell, lightmapSettings(32, 4096, 4));
        bakedIndirect(r);
        EXPECT_TRUE(statsSay(r, "seams: none")) << "a box's chart borders are creases";
    }
    const Scene mirror = makeBuiltinScene("mirror");
    double mean[2] = {0.0, 0.0};
    for (int stitch = 0; stitch < 2; ++stitch) {
        RenderSettings s = lightmapSettings(48, 4096, 16);
        setParam(s, "lightmap.stitch", stitch ? "true" : "false");
        Renderer r(mirror, s);
        const ImageF indirect = bakedIndirect(r);
        ASSERT_TRUE(allFinite(indirect));
        for (float v : indirect.rgba) mean[stitch] += v;
        float before = -1.0f, after = -1.0f;
        for (const std::string& line : lightmapStats(r))
            if (const size_t at = line.find("largest gap "); at != std::string::npos) {
                before = std::stof(line.substr(at + 12));
                after = std::stof(line.substr(line.find("before, ") + 8));
            }
        if (stitch) {
            std::printf("LIGHTMAP-TABLE seams mirror: largest gap %.3f of the seams' mean light before, %.3f after\n",
                        before, after);
            EXPECT_TRUE(after >= 0.0f && after < 0.25f * before) << "gap " << before << " before, " << after << " after";
        } else {
            EXPECT_TRUE(statsSay(r, "not stitched"));
        }
    }
    EXPECT_NEAR(mean[1] / mean[0], 1.0, 0.01) << "stitching moves light along seams, not into or out of the image";
}

// The same seams in the image, as a user sees them: the mirror box with its spheres made white and
// Lambertian (smooth surfaces cut into many charts), at the default density and paths. On a
// sphere's pixels, the step in indirect.diffuse to the neighbouring pixels is hardly larger where
// a chart edge crosses (lightmap.seams' magenta) than elsewhere on the sphere; unstitched it is
// nearly twice as large. And no pixel of theirs is black.
TEST(Lightmap, NoSeamShowsInTheImageAcrossASmoothSurface) {
    Scene spheres = makeBuiltinScene("mirror");
    for (size_t m = spheres.materials.size() - 2; m < spheres.materials.size(); ++m)
        spheres.materials[m] = lambert(glm::vec3(0.8f));
    constexpr int kSize = 128;
    RenderSettings s = lightmapSettings(kSize, 16384, 64);  // the medium preset, the default
    setParam(s, "lightmap.cache", "true");  // one bake for the three images (the stitch runs after it)
    s.view = "lightmap.seams";
    const ImageF edges = renderHdr(spheres, s);
    const std::vector<PixelHit> hits = castPixels(spheres, 0, kSize, kSize, nullptr);
    const auto sphereOf = [&](int x, int y) { return hits[size_t(y * kSize + x)].region / 8; };
    double ratio[2] = {0.0, 0.0};
    for (int stitch = 0; stitch < 2; ++stitch) {
        s.view = "indirect.diffuse";
        setParam(s, "lightmap.stitch", stitch ? "true" : "false");
        const ImageF light = renderHdr(spheres, s);
        ASSERT_TRUE(allFinite(light));
        const auto luminance = [&](int x, int y) {
            const float* p = light.at(x, y);
            return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        };
        // Mean step to the four neighbours, at chart-edge pixels and at the others, on pixels whose
        // 3 x 3 neighbourhood is one sphere; relative to that sphere pixels' mean light.
        double step[2] = {0.0, 0.0}, count[2] = {0.0, 0.0}, sum = 0.0, pixels = 0.0;
        int black = 0;  // a sphere's pixel without light: its atlas triangle covered no texel centre
        for (int y = 1; y + 1 < kSize; ++y)
            for (int x = 1; x + 1 < kSize; ++x) {
                const int sphere = sphereOf(x, y);
                if (sphere < 3) continue;
                black += luminance(x, y) == 0.0 ? 1 : 0;
                bool inside = true;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) inside = inside && sphereOf(x + dx, y + dy) == sphere;
                if (!inside) continue;
                const double l = luminance(x, y);
                const double d = std::abs(luminance(x + 1, y) - l) + std::abs(luminance(x - 1, y) - l) +
                                 std::abs(luminance(x, y + 1) - l) + std::abs(luminance(x, y - 1) - l);
                const int seam = isMagenta(edges.at(x, y)) ? 1 : 0;
                step[seam] += d / 4.0, count[seam] += 1.0, sum += l, pixels += 1.0;
            }
        EXPECT_EQ(black, 0) << "black pixels on the spheres";
        ASSERT_GT(count[1], 50.0) << "chart edges on the spheres";
        ASSERT_GT(count[0], 300.0);
        const double mean = sum / pixels;
        ratio[stitch] = (step[1] / count[1]) / (step[0] / count[0]);
        std::printf("LIGHTMAP-TABLE seams in the image, white spheres, %s: step at chart edges %.4f, elsewhere "
                    "%.4f of the spheres' mean light (%.0f and %.0f pixels): %.2fx\n",
                    stitch ? "stitched" : "not stitched", step[1] / count[1] / mean, step[0] / count[0] / mean,
                    count[1], count[0], ratio[stitch]);
    }
    EXPECT_LT(ratio[1], 1.25) << "a seam shows where chart edges cross the spheres";
    EXPECT_GT(ratio[0], ratio[1]) << "stitching is what hides the seams";
}

// A light edited after the bake: the last lightmap stays on show, marked stale, while the next
// bake runs (its first paths would be noise), and the new one replaces it when done.
TEST(Lightmap, AnEditKeepsTheLastLightmapMarkedStaleUntilTheNextBakeIsDone) {
    context();
    Scene scene = wallOnAFloor();
    Renderer r(scene, lightmapSettings(32, 1024, 8));
    const Pass* lightmap = nullptr;
    for (const auto& pass : r.passes())
        if (std::string(pass->name()) == "lightmap") lightmap = pass.get();
    ASSERT_NE(lightmap, nullptr);
    EXPECT_FALSE(lightmap->progress().stale) << "the first bake has nothing older to show";
    const ImageF before = bakedIndirect(r);
    scene.lights[0].intensity *= 4.0f;
    r.lightsChanged();
    r.renderFrame();
    ASSERT_FALSE(r.converged());
    EXPECT_TRUE(lightmap->progress().stale);
    EXPECT_LT(lightmap->progress().done, lightmap->progress().target);
    EXPECT_EQ(readTextureFloat(r.frameTexture("indirect.diffuse"), 32, 32).rgba, before.rgba)
        << "the last lightmap is shown while the next bakes";
    const ImageF after = bakedIndirect(r);
    EXPECT_FALSE(lightmap->progress().stale);
    double sum[2] = {0.0, 0.0};
    for (size_t i = 0; i < after.rgba.size(); i += 4) sum[0] += before.rgba[i], sum[1] += after.rgba[i];
    EXPECT_NEAR(sum[1] / sum[0], 4.0, 0.4) << "the new bake holds the brighter light";
}

// lightmap.directional: a floor whose normal map tilts its shading normal by 30 degrees towards
// +x and -x in stripes, lit only indirectly by a sunlit wall on its +x side. The stripes facing the
// wall get more of its light than those facing away (about twice); without the direction the two
// read the same.
TEST(Lightmap, ADirectionalBakeLightsANormalMapByWhereTheLightComesFrom) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.5f)));
    s.materials.push_back(lambert(glm::vec3(0.9f)));
    Image stripes;
    stripes.width = 8;
    stripes.height = 1;
    for (int x = 0; x < 8; ++x) {
        const float tilt = (x % 2 ? 1.0f : -1.0f) * 0.5f;  // sin 30 degrees along the tangent
        for (float c : {tilt, 0.0f, 0.866f, 1.0f}) stripes.rgba8.push_back(uint8_t(std::lround((c * 0.5f + 0.5f) * 255.0f)));
    }
    s.images.push_back(stripes);
    s.materials[0].normalTexture = 0;
    addQuad(s, glm::vec3(0.0f), glm::vec3(0, 1, 0), 2.0f, 0);
    addQuad(s, glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(-1, 0, 0), 2.0f, 1);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(1.0f, -0.2f, 0.0f));
    sun.intensity = 3.0f;
    s.lights.push_back(sun);
    s.cameras.push_back(lookAtCamera({-0.2f, 2.5f, 0.01f}, {-0.2f, 0.0f, 0.0f}, 50.0f));
    finalizeScene(s);
    context();
    double ratio[2] = {0.0, 0.0};
    for (int directional = 0; directional < 2; ++directional) {
        RenderSettings r = lightmapSettings(48, 2048, 32);
        setParam(r, "lightmap.directional", directional ? "true" : "false");
        Renderer renderer(s, r);
        const ImageF indirect = bakedIndirect(renderer);
        const ImageF normal = readTextureFloat(renderer.frameTexture("gbuffer.normal"), 48, 48);
        double sum[2] = {0.0, 0.0}, count[2] = {0.0, 0.0};
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 48; ++x) {
                const float* n = normal.at(x, y);
                if (n[1] < 0.8f || std::abs(n[0]) < 0.4f) continue;  // the floor's stripes, not their blends
                const int side = n[0] > 0.0f ? 1 : 0;  // facing the wall
                sum[side] += indirect.at(x, y)[0];
                count[side] += 1.0;
            }
        ASSERT_GT(count[0], 30.0);
        ASSERT_GT(count[1], 30.0);
        ratio[directional] = (sum[1] / count[1]) / (sum[0] / count[0]);
        std::printf("LIGHTMAP-TABLE directional %d: stripes facing the wall / facing away = %.3f\n", directional,
                    ratio[directional]);
    }
    EXPECT_NEAR(ratio[0], 1.0, 0.1) << "without the direction a normal map changes nothing";
    EXPECT_GT(ratio[1], 1.3) << "with it the stripes facing the lit wall get more of its light";
}

// An alpha-masked plane (a checker of holes) in front of a wall, a point light between them, every
// light baked (lightmap.mode=all): the wall is bright, the plane's front dark. Through the holes the
// G-buffer sees the wall, and so must the lookup: the plane's light there (drawn at a nearer depth
// than the wall's) would paint the wall dark through every hole.
TEST(Lightmap, AnAlphaMaskedSurfacesHolesShowTheLightBehindThem) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.9f)));  // the wall
    Material leaf = lambert(glm::vec3(0.8f, 0.1f, 0.1f));
    leaf.alphaMode = AlphaMode::Mask;
    leaf.baseColorTexture = 0;
    s.materials.push_back(leaf);
    Image checker;
    checker.width = checker.height = 4;
    for (int i = 0; i < 16; ++i)
        for (uint8_t c : {uint8_t(255), uint8_t(255), uint8_t(255), uint8_t(((i % 4) + (i / 4)) % 2 ? 255 : 0)})
            checker.rgba8.push_back(c);
    s.images.push_back(checker);
    addQuad(s, glm::vec3(0.0f), glm::vec3(0, 0, 1), 4.0f, 0);
    addQuad(s, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0, 0, 1), 2.0f, 1);
    Light light;
    light.type = LightType::Point;
    light.intensity = 2.0f;
    light.position = {0.0f, 0.0f, 0.5f};
    s.lights.push_back(light);
    s.cameras.push_back(lookAtCamera({0.0f, 0.0f, 4.0f}, {0, 0, 0}, 50.0f));
    finalizeScene(s);
    context();
    RenderSettings r = lightmapSettings(64, 2048, 8);
    setParam(r, "lightmap.mode", "all");
    Renderer renderer(s, r);
    const ImageF indirect = bakedIndirect(renderer);
    const ImageF base = readTextureFloat(renderer.frameTexture("gbuffer.baseColor"), 64, 64);
    double hole = 0.0, leafLight = 0.0, holes = 0.0, leaves = 0.0;
    for (int y = 16; y < 48; ++y)  // the plane's middle, away from its rim
        for (int x = 16; x < 48; ++x) {
            const bool wall = base.at(x, y)[1] > 0.5f;  // white, not the red leaf
            (wall ? hole : leafLight) += indirect.at(x, y)[0];
            (wall ? holes : leaves) += 1.0;
        }
    ASSERT_GT(holes, 100.0);
    ASSERT_GT(leaves, 100.0);
    std::printf("LIGHTMAP-TABLE cut-outs: through the holes %.4f, on the plane %.4f\n", hole / holes, leafLight / leaves);
    EXPECT_GT(hole / holes, 5.0 * leafLight / leaves) << "the holes show the plane's light, not the wall's";
}

// lightmap.rebake=hold: after an edit the stale lightmap stays and no path is traced (the renderer
// settles on it) until the parameter is set back to auto, which bakes the edited scene.
TEST(Lightmap, AHeldReBakeKeepsTheStaleLightmapUntilItIsLetGo) {
    context();
    Scene scene = wallOnAFloor();
    RenderSettings s = lightmapSettings(32, 1024, 8);
    setParam(s, "lightmap.rebake", "hold");
    Renderer r(scene, s);
    const Pass* lightmap = nullptr;
    for (const auto& pass : r.passes())
        if (std::string(pass->name()) == "lightmap") lightmap = pass.get();
    ASSERT_NE(lightmap, nullptr);
    const ImageF before = bakedIndirect(r);  // the first bake is never held: nothing older to show
    const uint64_t rays = lightmap->raysTraced()->total();
    scene.lights[0].intensity *= 4.0f;
    r.lightsChanged();
    for (int i = 0; i < 3; ++i) r.renderFrame();
    EXPECT_TRUE(lightmap->progress().stale);
    EXPECT_TRUE(r.settled()) << "a held re-bake leaves nothing to render";
    EXPECT_TRUE(r.converged()) << "a held re-bake is all rendering can give: a viewer, a script's converge, bench end";
    EXPECT_TRUE(lightmap->progress().held);
    EXPECT_EQ(lightmap->raysTraced()->total(), rays) << "no path traced while held";
    EXPECT_EQ(readTextureFloat(r.frameTexture("indirect.diffuse"), 32, 32).rgba, before.rgba);
    setParam(s, "lightmap.rebake", "auto");
    r.setLiveSettings(s);
    const ImageF after = bakedIndirect(r);
    EXPECT_FALSE(lightmap->progress().stale);
    double sum[2] = {0.0, 0.0};
    for (size_t i = 0; i < after.rgba.size(); i += 4) sum[0] += before.rgba[i], sum[1] += after.rgba[i];
    EXPECT_NEAR(sum[1] / sum[0], 4.0, 0.4);
}

// Every light baked, with the direction kept, at x1e-3 and x1e3: the image the x1 scene gives
// (the punctual light's falloff scales with the scene as scaledScene scales its intensity).
TEST(Lightmap, ABakeOfAllTheLightWithItsDirectionHoldsAtEveryScale) {
    const Scene base = makeBuiltinScene("cornell");
    context();
    double mean[3] = {0.0, 0.0, 0.0};
    const float scales[3] = {1.0f, 1e-3f, 1e3f};
    for (int i = 0; i < 3; ++i) {
        const Scene scene = scaledScene(base, scales[i]);
        RenderSettings s = lightmapSettings(32, 1024, 16);
        setParam(s, "lightmap.mode", "all");
        setParam(s, "lightmap.directional", "true");
        Renderer r(scene, s);
        bakedIndirect(r);
        const ImageF image = r.readHdr();
        ASSERT_TRUE(allFinite(image)) << "scale " << scales[i];
        for (size_t k = 0; k < image.rgba.size(); k += 4) mean[i] += image.rgba[k] + image.rgba[k + 1] + image.rgba[k + 2];
        std::printf("LIGHTMAP-TABLE mode all, directional, scale %g: mean %.5f\n", double(scales[i]), mean[i] / 1024.0);
    }
    EXPECT_NEAR(mean[1] / mean[0], 1.0, 0.03);
    EXPECT_NEAR(mean[2] / mean[0], 1.0, 0.03);
}
