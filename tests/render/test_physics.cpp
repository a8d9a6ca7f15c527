// Physical checks that need no golden image: each compares the rasterizer's linear radiance with a
// closed-form answer. A white Lambertian surface has BRDF 1/pi, so its outgoing radiance is E/pi
// where E is the irradiance the light delivers to it.
#include <glm/gtc/matrix_transform.hpp>

#include "lights.h"
#include "gi/memory_budget.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A 10 m white floor at y = 0, a camera above and in front of it, no ambient.
Scene floorScene() {
    Scene s;
    s.name = "floor";
    s.materials.push_back(lambert(glm::vec3(1.0f)));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 10.0f, 0);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 3, 3), glm::vec3(0)));
    return s;
}

RenderSettings plainSettings() {
    RenderSettings r;
    r.width = r.height = 128;
    r.ambient = glm::vec3(0.0f);
    return r;
}

// World point where the ray through the centre of pixel (x, y) meets the plane y = 0.
bool floorPointOfPixel(const Scene& scene, const RenderSettings& s, int x, int y, glm::vec3& p) {
    CameraMatrices m = cameraMatrices(scene, s.camera, float(s.width) / float(s.height));
    glm::vec2 ndc((x + 0.5f) / s.width * 2.0f - 1.0f, 1.0f - (y + 0.5f) / s.height * 2.0f);
    glm::vec4 a = m.invViewProj * glm::vec4(ndc, -1.0f, 1.0f), b = m.invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
    glm::dvec3 o = glm::dvec3(a) / double(a.w), e = glm::dvec3(b) / double(b.w);
    glm::dvec3 d = e - o;
    if (std::abs(d.y) < 1e-9) return false;
    double t = -o.y / d.y;
    if (t <= 0.0) return false;
    p = glm::vec3(o + d * t);
    return true;
}

Light pointLight(glm::vec3 position, float intensity) {
    Light l;
    l.type = LightType::Point;
    l.position = position;
    l.intensity = intensity;
    return l;
}

TEST(Physics, WhiteLambertUnderDirectionalLightIsEOverPi) {
    Scene s = floorScene();
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::vec3(0, -1, 0);
    sun.intensity = 2.0f;  // irradiance at normal incidence, W/m^2
    s.lights.push_back(sun);
    finalizeScene(s);
    RenderSettings r = plainSettings();
    ImageF img = renderHdr(s, r);
    const double expected = 2.0 / kPi;
    int checked = 0;
    for (int y = 0; y < r.height; y += 3)
        for (int x = 0; x < r.width; x += 3) {
            glm::vec3 p;
            if (!floorPointOfPixel(s, r, x, y, p) || std::abs(p.x) > 4.5f || std::abs(p.z) > 4.5f) continue;
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(img.at(x, y)[c], expected, 0.01 * expected) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 500);
}

// E = I cos(theta) / d^2 for a point light of radiant intensity I: checked at every floor pixel
// within 60 degrees of the light's nadir, and the 1/d^2 law by raising the light from 1 m to 2 m.
double pointLightRadiance(glm::vec3 light, float intensity, glm::vec3 p) {
    glm::dvec3 d = glm::dvec3(light) - glm::dvec3(p);
    double dist = glm::length(d);
    return intensity * (d.y / dist) / (dist * dist) / kPi;
}

TEST(Physics, PointLightFallsOffAsInverseSquare) {
    double centre[2];
    for (int k = 0; k < 2; ++k) {
        const float height = k == 0 ? 1.0f : 2.0f;
        Scene s = floorScene();
        const glm::vec3 lightPos(0, height, 0);
        s.lights.push_back(pointLight(lightPos, 2.0f));
        finalizeScene(s);
        RenderSettings r = plainSettings();
        ImageF img = renderHdr(s, r);
        int checked = 0;
        for (int y = 0; y < r.height; y += 2)
            for (int x = 0; x < r.width; x += 2) {
                glm::vec3 p;
                if (!floorPointOfPixel(s, r, x, y, p)) continue;
                const glm::vec3 toLight = lightPos - p;
                if (toLight.y / glm::length(toLight) < 0.5f || std::abs(p.x) > 4.5f || std::abs(p.z) > 4.5f) continue;
                const double expected = pointLightRadiance(lightPos, 2.0f, p);
                ASSERT_NEAR(img.at(x, y)[1], expected, 0.01 * expected) << "pixel " << x << "," << y << " height " << height;
                ++checked;
            }
        EXPECT_GT(checked, 100);
        glm::ivec2 c = projectToPixel(s, r, glm::vec3(0));
        glm::vec3 p;
        ASSERT_TRUE(floorPointOfPixel(s, r, c.x, c.y, p));
        centre[k] = img.at(c.x, c.y)[0] / pointLightRadiance(lightPos, 2.0f, p) * (2.0 / (height * height) / kPi);
    }
    EXPECT_NEAR(centre[0] / centre[1], 4.0, 0.04);  // twice the distance, a quarter of the light
}

// The lighting pass reads up to kUniformBlockLights lights from a uniform block and more from a
// storage buffer: n point lights of intensity I/n at one spot light the floor as one light of I,
// on both sides of that switch (the sum of n terms, within float rounding).
TEST(Physics, ManyLightsSumToOneOnBothLightBufferPaths) {
    auto render = [](int n) {
        Scene s = floorScene();
        for (int i = 0; i < n; ++i) s.lights.push_back(pointLight(glm::vec3(0, 1.5f, 0), 2.0f / float(n)));
        finalizeScene(s);
        RenderSettings r = plainSettings();
        r.width = r.height = 48;
        r.shadows = false;  // 6 cube layers per light would only slow this down
        return renderHdr(s, r);
    };
    const ImageF one = render(1);
    for (int n : {kUniformBlockLights, kUniformBlockLights + 20}) {
        const ImageF many = render(n);
        double worst = 0.0;
        for (size_t i = 0; i < one.rgba.size(); ++i)
            worst = std::max(worst, std::abs(double(many.rgba[i]) - one.rgba[i]) / std::max(1e-3, double(one.rgba[i])));
        EXPECT_LT(worst, 1e-3) << n << " lights";
    }
}

// An occluder between light and floor: the point under it receives no direct light while a point
// outside its shadow is fully lit - for each kind of shadow map (directional, spot, point cube).
class ShadowTest : public ::testing::TestWithParam<LightType> {};

TEST_P(ShadowTest, ShadowedPointGetsNoDirectLight) {
    Scene s = floorScene();
    s.materials.push_back(lambert(glm::vec3(0.5f)));
    addQuad(s, glm::vec3(0, 1.5f, 0), glm::vec3(0, 1, 0), 0.5f, 1);  // occluder, seen from above
    Light l;
    l.type = GetParam();
    l.position = glm::vec3(0, 3, 0);
    l.direction = glm::vec3(0, -1, 0);
    l.intensity = 5.0f;
    l.outerConeAngle = glm::radians(40.0f);
    l.innerConeAngle = glm::radians(30.0f);
    s.lights.push_back(l);
    // Look from the side so the floor under the occluder is visible.
    s.cameras[0] = lookAtCamera(glm::vec3(0, 1.0f, 4.0f), glm::vec3(0, 0, 0), 50.0f);
    finalizeScene(s);
    RenderSettings r = plainSettings();
    ImageF img = renderHdr(s, r);
    const glm::ivec2 under = projectToPixel(s, r, glm::vec3(0, 0, 0));
    const glm::ivec2 outside = projectToPixel(s, r, glm::vec3(1.2f, 0, 0.3f));
    for (int c = 0; c < 3; ++c) EXPECT_LT(meanAround(img, under.x, under.y, 1, c), 1e-6) << "channel " << c;
    EXPECT_GT(meanAround(img, outside.x, outside.y, 0, 0), 0.05);

    r.shadows = false;  // the same point is lit when shadows are off: the zero came from the shadow
    ImageF unshadowed = renderHdr(s, r);
    EXPECT_GT(meanAround(unshadowed, under.x, under.y, 1, 0), 0.05);
}

INSTANTIATE_TEST_SUITE_P(AllLightTypes, ShadowTest,
                         ::testing::Values(LightType::Directional, LightType::Spot, LightType::Point),
                         [](const auto& info) {
                             return std::string(info.param == LightType::Directional ? "Directional"
                                                : info.param == LightType::Spot      ? "Spot"
                                                                                     : "Point");
                         });

// An 80 m floor under a roof with a 20 cm slit, the sun straight down: one map over the scene has
// texels of 8 cm, and its filter dims the strip of sun the slit lets through. The map the shadow
// pass fits around the camera (a quarter of the scene's diameter along the view) resolves it: the
// strip's middle gets the full sun (E / pi on white), the floor beside it none.
Scene sunThroughASlit() {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(1.0f)));
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 80.0f, 0);
    const float slit = 0.2f, roof = 12.0f;
    for (float side : {-1.0f, 1.0f}) addQuad(s, glm::vec3(side * 0.5f * (roof + slit), 3.0f, 0), glm::vec3(0, 1, 0), roof, 0);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::vec3(0, -1, 0);
    sun.intensity = 2.0f;
    s.lights.push_back(sun);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 1.6f, 3.0f), glm::vec3(0, 0, -1.0f), 60.0f));
    finalizeScene(s);
    return s;
}

TEST(Physics, ASunThroughANarrowSlitIsSharpInALargeScene) {
    const Scene s = sunThroughASlit();
    RenderSettings r = plainSettings();
    const ImageF img = renderHdr(s, r);
    const double full = 2.0 / kPi;
    for (float z : {0.0f, -1.0f, -2.0f}) {
        const glm::ivec2 middle = projectToPixel(s, r, glm::vec3(0, 0, z));
        const glm::ivec2 beside = projectToPixel(s, r, glm::vec3(0.35f, 0, z));
        std::printf("[ measured ] z %.0f: the strip's middle %.4f, beside it %.4f (E/pi %.4f)\n", z,
                    meanAround(img, middle.x, middle.y, 0), meanAround(img, beside.x, beside.y, 0), full);
        EXPECT_NEAR(meanAround(img, middle.x, middle.y, 0), full, 0.03 * full) << "z " << z;
        EXPECT_LT(meanAround(img, beside.x, beside.y, 0), 0.01 * full) << "z " << z;
    }
}

// The map around the camera follows it on a grid of its own texels: a still view renders no map,
// a move within a texel renders none either, a move of a metre renders it again; the scene's map
// stays (the volume's light injection reads it, and a camera move keeps the volume).
TEST(Physics, TheSunsMapAroundTheCameraFollowsItAndAStillViewRendersNothing) {
    context();
    const Scene s = sunThroughASlit();
    Renderer r(s, plainSettings());
    const Pass* shadows = nullptr;
    for (const auto& p : r.passes())
        if (std::string(p->name()) == "shadows") shadows = p.get();
    ASSERT_NE(shadows, nullptr);
    auto moveBy = [&r](glm::vec3 d) {
        CameraMatrices m = r.camera();
        m.position += d;
        m.view = glm::translate(m.view, -d);
        m.viewProj = m.proj * m.view;
        m.invViewProj = glm::inverse(m.viewProj);
        r.setCamera(m);
        r.renderFrame();
    };
    r.renderFrame();
    EXPECT_FALSE(shadows->reusedLastFrame()) << "the first frame renders the maps";
    r.renderFrame();
    EXPECT_TRUE(shadows->settled());
    moveBy(glm::vec3(1e-4f, 0.0f, 0.0f));
    EXPECT_TRUE(shadows->reusedLastFrame()) << "a move within a texel of the camera's map";
    moveBy(glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_FALSE(shadows->reusedLastFrame()) << "a move of a metre";
    EXPECT_TRUE(shadows->settled());
}

TEST(Physics, SpotConeIsFullInsideInnerAndDarkOutsideOuter) {
    Scene s = floorScene();
    Light l;
    l.type = LightType::Spot;
    l.position = glm::vec3(0, 2, 0);
    l.direction = glm::vec3(0, -1, 0);
    l.intensity = 3.0f;
    l.innerConeAngle = glm::radians(20.0f);
    l.outerConeAngle = glm::radians(30.0f);
    s.lights.push_back(l);
    finalizeScene(s);
    RenderSettings r = plainSettings();
    ImageF img = renderHdr(s, r);
    const glm::vec3 inside(2.0f * std::tan(glm::radians(10.0f)), 0, 0);
    const glm::vec3 outside(2.0f * std::tan(glm::radians(35.0f)), 0, 0);
    glm::ivec2 pi = projectToPixel(s, r, inside), po = projectToPixel(s, r, outside);
    glm::vec3 p;
    ASSERT_TRUE(floorPointOfPixel(s, r, pi.x, pi.y, p));
    EXPECT_NEAR(img.at(pi.x, pi.y)[0], pointLightRadiance(l.position, 3.0f, p), 0.01 * pointLightRadiance(l.position, 3.0f, p));
    EXPECT_EQ(img.at(po.x, po.y)[0], 0.0f);
}

TEST(Physics, RendersAreDeterministic) {
    Scene s = makeBuiltinScene("cornell");
    RenderSettings r = plainSettings();
    context();
    std::vector<float> hdr[2];
    std::vector<uint8_t> ldr[2];
    for (int k = 0; k < 2; ++k) {
        Renderer renderer(s, r);
        renderer.renderFrame();
        hdr[k] = renderer.readHdr().rgba;
        ldr[k] = renderer.readLdr().rgba;
    }
    EXPECT_TRUE(hdr[0] == hdr[1]);
    EXPECT_TRUE(ldr[0] == ldr[1]);
}

// Stability at the extremes of scale and brightness: the Cornell box scaled by 1e-3 and 1e3 (camera,
// lights and clip planes with it, light intensity by scale^2 so irradiance is unchanged), and a
// light 1e6 times too bright. Every pixel must stay finite and the image must look the same.
Scene scaledCornell(float scale) { return scaledScene(makeBuiltinScene("cornell"), scale); }

double meanChannel(const ImageF& img, int c) {
    double sum = 0.0;
    for (size_t i = 0; i < img.rgba.size() / 4; ++i) sum += img.rgba[i * 4 + c];
    return sum / double(img.rgba.size() / 4);
}

TEST(Extremes, HugeAndTinyScenesAndBrightLightsStayFinite) {
    RenderSettings r = plainSettings();
    r.width = r.height = 96;
    const ImageF reference = renderHdr(scaledCornell(1.0f), r);
    const double refMean = meanChannel(reference, 0);
    ASSERT_GT(refMean, 0.01);
    for (float scale : {1e-3f, 1e3f}) {
        ImageF img = renderHdr(scaledCornell(scale), r);
        for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v)) << "scale " << scale;
        EXPECT_NEAR(meanChannel(img, 0), refMean, 0.03 * refMean) << "scale " << scale;
    }
    Scene bright = makeBuiltinScene("cornell");
    for (Light& l : bright.lights) l.intensity *= 1e6f;
    r.hdr32 = false;
    Renderer renderer(bright, r);
    renderer.renderFrame();
    const ImageF img = renderer.readHdr();
    for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v)) << "1e6 x light in RGBA16F";
    const ImageU8 ldr = renderer.readLdr();
    EXPECT_GT(ldr.rgba[(size_t(r.height / 2) * r.width + r.width / 2) * 4], 200);  // saturates to white, not black
}

}  // namespace
}  // namespace gis::test

namespace gis::test {
namespace {

// The memory budget's estimate (renderer/gi/memory_budget.cpp) restates the passes' formats; it must
// stay equal to what the ledger counts once they exist, or the refusal guards the wrong number.
TEST(MemoryBudget, EstimateMatchesTheLedger) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    for (const char* gi : {"none", "ssao", "ssao-half-temporal", "pathtrace", "ao-reference"}) {
        for (bool hdr32 : {false, true}) {
            RenderSettings s;
            // Large enough that a missed target (SSAO history at half resolution: 256 KiB) shows.
            s.width = 256;
            s.height = 256;
            s.gi = std::string(gi).rfind("ssao", 0) == 0 ? "ssao" : gi;
            s.hdr32 = hdr32;
            if (std::string(gi) == "ssao-half-temporal") {
                setParam(s, "ssao.half-res", "true");
                setParam(s, "ssao.temporal", "true");
            }
            if (hdr32) s.view = "gbuffer.normal";  // the debug-view target (and the G-buffer for standalone methods)
            const uint64_t estimate = estimateGpuMemory(scene, s).total();
            Renderer renderer(scene, s);
            const double ledger = double(renderer.memory().total());
            // The path tracer's BVH and triangle buffers are left out of the estimate (small next
            // to images); everything else is exact.
            EXPECT_NEAR(double(estimate), ledger, 0.01 * ledger + 16 * 1024) << gi << (hdr32 ? " hdr32" : "");
        }
    }
}

// With emitters as lights the direct pass adds its ReSTIR reservoirs (two sets and the still
// view's accumulation, about 100 bytes a pixel); with emitters.mode=gi it has none.
TEST(MemoryBudget, EstimateCountsTheEmitterLights) {
    context();
    const Scene scene = makeBuiltinScene("cornell-area");
    for (const char* mode : {"lights", "gi"}) {
        RenderSettings s;
        s.width = s.height = 256;
        s.gi = "none";
        setParam(s, "emitters.mode", mode);
        const uint64_t estimate = estimateGpuMemory(scene, s).total();
        Renderer renderer(scene, s);
        const double ledger = double(renderer.memory().total());
        // The ray scene the reservoirs' visibility rays trace is left out (a few hundred triangles).
        EXPECT_NEAR(double(estimate), ledger, 0.01 * ledger + 16 * 1024) << mode;
    }
}

// An environment map's textures (its radiance with mips, the prefiltered specular chain and the
// sampling CDFs; the split-sum table every environment has) are in the estimate, sized from the
// file's header before the map is decoded.
TEST(MemoryBudget, EstimateCountsTheEnvironmentMap) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings s;
    s.width = s.height = 64;
    s.gi = "none";
    const uint64_t without = estimateGpuMemory(scene, s).total();
    s.environment = std::string(GIS_SOURCE_DIR) + "/assets/environments/sky_sun.hdr";
    const uint64_t estimate = estimateGpuMemory(scene, s).total();
    EXPECT_GT(estimate, without + 64 * 1024);
    Renderer renderer(scene, s);
    const double ledger = double(renderer.memory().total());
    EXPECT_NEAR(double(estimate), ledger, 0.01 * ledger + 16 * 1024);
}

}  // namespace
}  // namespace gis::test
