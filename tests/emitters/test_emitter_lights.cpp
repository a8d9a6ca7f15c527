// The emitter-light module (renderer/emitters/): ReSTIR DI against closed forms and the path
// tracer, its reuse, its absence when there is nothing to light, and extreme inputs.
#include <glm/gtc/matrix_transform.hpp>

#include "emitters/emitter_lights.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kEmitterHeight = 1.0f, kEmitterSize = 0.5f;

// A 4 m white Lambert floor at y = 0 under a one-sided square emitter facing down, seen from the side.
Scene emitterFloorScene(float radiance = 4.0f) {
    Scene s;
    s.name = "emitter-floor";
    s.materials.push_back(lambert(glm::vec3(1.0f)));
    Material lamp = lambert(glm::vec3(0.0f));
    lamp.emissive = glm::vec3(radiance);
    s.materials.push_back(lamp);
    addQuad(s, glm::vec3(0), glm::vec3(0, 1, 0), 4.0f, 0);
    addQuad(s, glm::vec3(0, kEmitterHeight, 0), glm::vec3(0, -1, 0), kEmitterSize, 1);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 2.0f, 1.2f), glm::vec3(0)));
    return s;
}

// The floor scene with a box-like occluder (two quads) between the emitter and part of the floor.
Scene shadowedScene() {
    Scene s = emitterFloorScene();
    s.materials.push_back(lambert(glm::vec3(0.5f), true));
    addQuad(s, glm::vec3(0.25f, 0.4f, 0.1f), glm::vec3(0, 1, 0), 0.4f, 2);
    addQuad(s, glm::vec3(-0.35f, 0.25f, -0.2f), glm::vec3(1, 0, 0), 0.5f, 2);
    return s;
}

// The form factor from a floor point to a parallel rectangle [x0, x1] x [z0, z1] (coordinates
// relative to the point) at height h: signed sums of the corner form factor (Howell's catalogue,
// C-11: a differential area parallel to a rectangle whose normal passes through a corner), which
// is odd in both sides.
double cornerFormFactor(double a, double b, double h) {
    const double X = a / h, Y = b / h, ax = std::sqrt(1 + X * X), ay = std::sqrt(1 + Y * Y);
    return (X / ax * std::atan(Y / ax) + Y / ay * std::atan(X / ay)) / (2 * kPi);
}

// Radiance of a white Lambert floor point p under the emitter quad (side kEmitterSize, centred on
// the y axis at height h, radiance Le facing down): Le times the form factor.
double analyticFloorRadiance(double Le, glm::dvec2 p, double h = kEmitterHeight) {
    const double e = 0.5 * kEmitterSize, x0 = -e - p.x, x1 = e - p.x, z0 = -e - p.y, z1 = e - p.y;
    return Le * (cornerFormFactor(x1, z1, h) - cornerFormFactor(x0, z1, h) - cornerFormFactor(x1, z0, h) +
                 cornerFormFactor(x0, z0, h));
}

// The floor (y = 0) point the centre of pixel (x, y) sees.
glm::dvec2 floorPoint(const Scene& scene, const RenderSettings& s, int x, int y) {
    const CameraMatrices m = cameraMatrices(scene, s.camera, float(s.width) / float(s.height));
    const glm::vec2 ndc((x + 0.5f) / s.width * 2.0f - 1.0f, 1.0f - (y + 0.5f) / s.height * 2.0f);
    const glm::dvec4 a = glm::dvec4(m.invViewProj * glm::vec4(ndc, -1.0f, 1.0f));
    const glm::dvec4 b = glm::dvec4(m.invViewProj * glm::vec4(ndc, 1.0f, 1.0f));
    const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
    const glm::dvec3 p = o + d * (-o.y / d.y);
    return {p.x, p.z};
}

// Mean rendered and analytic floor radiance (channel c) over the square of half-size r pixels
// around the pixel that sees floor point q.
std::pair<double, double> floorMeans(const Scene& scene, const RenderSettings& s, const ImageF& img, double Le,
                                     glm::vec3 q, int r, int c = 0) {
    const glm::ivec2 px = projectToPixel(scene, s, q);
    double rendered = 0, analytic = 0;
    int n = 0;
    for (int y = px.y - r; y <= px.y + r; ++y)
        for (int x = px.x - r; x <= px.x + r; ++x) {
            rendered += img.at(x, y)[c];
            analytic += analyticFloorRadiance(Le, floorPoint(scene, s, x, y));
            ++n;
        }
    return {rendered / n, analytic / n};
}

RenderSettings restirSettings(int size = 64) {
    RenderSettings r;
    r.width = r.height = size;
    r.ambient = glm::vec3(0.0f);
    r.specular = SpecularModel::None;
    setParam(r, "emitters.mode", "lights");
    return r;
}

bool hasPass(const Renderer& renderer, const std::string& name) {
    for (const auto& p : renderer.passes())
        if (p->name() == name) return true;
    return false;
}

double imageMean(const ImageF& img, int c = 0) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) sum += img.at(x, y)[c];
    return sum / (double(img.width) * img.height);
}

// Per-pixel variance over `frames` single-frame estimates (accumulate = 0) after `warmup` frames,
// averaged over the pixels that receive light.
double perFrameVariance(const Scene& scene, RenderSettings s, int warmup, int frames) {
    context();
    s.hdr32 = true;
    setParam(s, "emitters.accumulate", "0");
    Renderer renderer(scene, s);
    for (int i = 0; i < warmup; ++i) renderer.renderFrame();
    std::vector<double> sum(size_t(s.width) * s.height), sum2(sum.size());
    for (int f = 0; f < frames; ++f) {
        renderer.renderFrame();
        const ImageF img = renderer.readHdr();
        for (size_t i = 0; i < sum.size(); ++i) {
            const double v = img.rgba[i * 4];
            sum[i] += v;
            sum2[i] += v * v;
        }
    }
    double variance = 0;
    int lit = 0;
    for (size_t i = 0; i < sum.size(); ++i) {
        const double mean = sum[i] / frames;
        if (mean <= 1e-3) continue;
        variance += std::max(0.0, sum2[i] / frames - mean * mean);
        ++lit;
    }
    return lit ? variance / lit : 0.0;
}

TEST(EmitterLights, ConvergedFloorRadianceIsTheFormFactorValue) {
    const Scene scene = emitterFloorScene();
    RenderSettings s = restirSettings();
    const ImageF img = renderHdr(scene, s);
    // Under the emitter and at two points off to the side.
    for (glm::vec3 q : {glm::vec3(0), glm::vec3(0.6f, 0, 0.2f), glm::vec3(-0.5f, 0, -0.7f)})
        for (int ch = 0; ch < 3; ++ch) {
            const auto [rendered, analytic] = floorMeans(scene, s, img, 4.0, q, 2, ch);
            EXPECT_NEAR(rendered, analytic, 0.02 * analytic) << q.x << "," << q.z << " channel " << ch;
        }
    // The biased mode on an unshadowed floor has nothing to be biased about: the same value.
    setParam(s, "emitters.unbiased", "false");
    const ImageF biased = renderHdr(scene, s);
    const auto [rendered, analytic] = floorMeans(scene, s, biased, 4.0, glm::vec3(0), 2);
    EXPECT_NEAR(rendered, analytic, 0.02 * analytic);
}

TEST(EmitterLights, UnbiasedMeanEqualsThePathTracersDirectLight) {
    const Scene scene = shadowedScene();
    RenderSettings s = restirSettings();
    // Temporal and spatial reuse correlate frames and neighbours: many frames for a tight mean.
    setParam(s, "emitters.accumulate", "256");
    const ImageF restir = renderHdr(scene, s);
    RenderSettings pt = s;
    pt.gi = "pathtrace";
    pt.samplesPerFrame = 16;
    setParam(pt, "pathtrace.spp", "512");
    setParam(pt, "pathtrace.bounces", "0");  // direct light only
    const ImageF reference = renderHdr(scene, pt);
    ASSERT_TRUE(allFinite(restir));
    const double a = imageMean(restir), b = imageMean(reference);
    EXPECT_NEAR(a, b, 0.02 * b) << "ReSTIR " << a << " vs path tracer " << b;
    // Each half of the image (the shadowed and the open part) on its own, too.
    ImageF ra = downsample(restir, 32), rb = downsample(reference, 32);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            EXPECT_NEAR(ra.at(x, y)[0], rb.at(x, y)[0], 0.03 * rb.at(x, y)[0] + 1e-4) << x << "," << y;
}

// The biased mode weighs other pixels' domains by their unshadowed target, so a neighbour that
// cannot see a sample still takes its share of it: the image is darker wherever neighbours' views
// of the emitter differ, which under the broad penumbrae of this scene is most of the floor. The
// bound, stated in the README: never brighter, at most 55% darker here (measured -47.6%, worst
// quadrant -64%; the 1/sum-M weights before this module's rework: -46.2%).
TEST(EmitterLights, BiasedMeanStaysWithinItsStatedBound) {
    const Scene scene = shadowedScene();
    RenderSettings s = restirSettings();
    setParam(s, "emitters.unbiased", "false");
    setParam(s, "emitters.accumulate", "256");
    const ImageF restir = renderHdr(scene, s);
    RenderSettings pt = restirSettings();
    pt.gi = "pathtrace";
    pt.samplesPerFrame = 16;
    setParam(pt, "pathtrace.spp", "512");
    setParam(pt, "pathtrace.bounces", "0");
    const ImageF reference = renderHdr(scene, pt);
    const double a = imageMean(restir), b = imageMean(reference);
    ImageF ra = downsample(restir, 32), rb = downsample(reference, 32);
    double worst = 0.0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) worst = std::max(worst, 1.0 - ra.at(x, y)[0] / rb.at(x, y)[0]);
    std::printf("biased: mean %+.2f%% of the path tracer's, worst quadrant %.2f%%\n", 100.0 * (a / b - 1.0),
                100.0 * worst);
    EXPECT_LE(a, 1.02 * b) << "biased toward dark only";
    EXPECT_GT(a, 0.45 * b);
}

TEST(EmitterLights, TemporalReuseCutsPerFrameVarianceFourTimes) {
    const Scene scene = shadowedScene();
    // Biased combination: temporal reuse then traces no ray more than no reuse (equal rays).
    RenderSettings s = restirSettings(48);
    setParam(s, "emitters.unbiased", "false");
    setParam(s, "emitters.spatial", "0");
    setParam(s, "emitters.candidates", "2");
    RenderSettings noReuse = s;
    setParam(noReuse, "emitters.temporal", "false");
    const double withHistory = perFrameVariance(scene, s, 24, 24);
    const double without = perFrameVariance(scene, noReuse, 24, 24);
    std::printf("per-frame variance: %.4g without temporal reuse, %.4g with (%.1fx)\n", without, withHistory,
                without / withHistory);
    EXPECT_GT(without, 4.0 * withHistory);
}

TEST(EmitterLights, NoEmittersMeansNoPassAndTheSameImage) {
    Scene scene = emitterFloorScene();
    scene.materials[1].emissive = glm::vec3(0.0f);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1, 0.2f));
    sun.intensity = 2.0f;
    scene.lights.push_back(sun);
    for (const char* gi : {"none", "vct"}) {
        RenderSettings lights = restirSettings(), gi_ = restirSettings();
        lights.gi = gi_.gi = gi;
        setParam(gi_, "emitters.mode", "gi");
        context();
        Renderer a(scene, lights);
        EXPECT_FALSE(hasPass(a, "emitters")) << gi;
        const ImageF ia = renderHdr(scene, lights), ib = renderHdr(scene, gi_);
        EXPECT_EQ(ia.rgba, ib.rgba) << gi;
    }
    // And with emitters the pass is there (the check above can fail).
    context();
    Renderer withEmitters(emitterFloorScene(), restirSettings());
    EXPECT_TRUE(hasPass(withEmitters, "emitters"));
}

TEST(EmitterLights, ModesGiAndOffRunNoPass) {
    context();
    for (const char* mode : {"gi", "off"}) {
        RenderSettings s = restirSettings();
        setParam(s, "emitters.mode", mode);
        Renderer r(emitterFloorScene(), s);
        EXPECT_FALSE(hasPass(r, "emitters")) << mode;
    }
    // off: the floor gets no emitter light; gi with --gi none neither (no volume carries it).
    RenderSettings off = restirSettings();
    setParam(off, "emitters.mode", "off");
    const Scene scene = emitterFloorScene();
    const ImageF img = renderHdr(scene, off);
    const glm::ivec2 c = projectToPixel(scene, off, glm::vec3(0));
    EXPECT_EQ(meanAround(img, c.x, c.y, 2), 0.0);
}

TEST(EmitterLights, AutoRunsOnlyForEmissionThatLights) {
    // The floor scene's emitter lights it; shrunk to a 1 cm square of the same radiance its
    // emission is a surface detail (below the floor --lighting auto uses) and auto runs nothing.
    Scene dim = emitterFloorScene();
    for (Vertex& v : dim.primitives[1].vertices) v.position = glm::vec3(0, kEmitterHeight, 0) + 0.02f * (v.position - glm::vec3(0, kEmitterHeight, 0));
    finalizeScene(dim);
    RenderSettings automatic = restirSettings();
    setParam(automatic, "emitters.mode", "auto");
    context();
    EXPECT_TRUE(hasPass(Renderer(emitterFloorScene(), automatic), "emitters"));
    EXPECT_FALSE(hasPass(Renderer(dim, automatic), "emitters"));
    EXPECT_TRUE(hasPass(Renderer(dim, restirSettings()), "emitters")) << "lights forces the pass";
    EXPECT_EQ(emitterLightSettings(RenderSettings()).mode, int(EmitterMode::Auto)) << "the default";
}

// emitters.environment=auto (the default) is what each method declares; true and false override it,
// and only an environment that sends light makes the pass.
TEST(EmitterLights, EnvironmentLightAutoIsTheMethodsChoice) {
    Scene sky = emitterFloorScene();
    sky.background = glm::vec3(0.5f);
    Scene dark = sky;
    dark.background = glm::vec3(0.0f);
    for (const GiMethod& m : giMethods()) {
        SCOPED_TRACE(m.name);
        RenderSettings s;
        s.gi = m.name;
        EXPECT_EQ(environmentLightChosen(s), m.environmentLightByDefault);
        EXPECT_EQ(environmentIsLight(sky, s), m.environmentLightByDefault);
        EXPECT_FALSE(environmentIsLight(dark, s));
        setParam(s, "emitters.environment", "false");
        EXPECT_FALSE(environmentIsLight(sky, s));
        setParam(s, "emitters.environment", "true");
        EXPECT_TRUE(environmentIsLight(sky, s));
    }
    int byDefault = 0;
    for (const char* name : {"sdf", "probes", "hddagi"}) byDefault += giMethod(name).environmentLightByDefault ? 1 : 0;
    EXPECT_EQ(byDefault, 3) << "the methods whose pages measured it closer to Cycles";
    EXPECT_FALSE(giMethod("vct").environmentLightByDefault) << "its slab walls take no sky (emitters README)";
    EXPECT_FALSE(giMethod("none").environmentLightByDefault) << "it would lose the ambient that stands for its indirect light";
}

TEST(EmitterLights, MovingCameraLeavesNoTrail) {
    // The occluders seen from one camera, then a camera moved sideways: the first frame after the
    // move must be as close to the converged image there as a renderer that started there (one
    // frame: what the disoccluded pixels should look like) or that has run there for a while (the
    // pixels whose history is kept). History taken from the wrong surface makes it worse than both.
    const Scene scene = shadowedScene();
    RenderSettings s = restirSettings();
    setParam(s, "emitters.accumulate", "0");
    Scene moved = scene;
    moved.cameras[0] = lookAtCamera(glm::vec3(0.9f, 1.2f, 1.2f), glm::vec3(0.1f, 0.1f, 0));
    const ImageF truth = renderHdr(moved, restirSettings());
    context();
    s.hdr32 = true;
    Renderer renderer(scene, s);
    for (int i = 0; i < 16; ++i) renderer.renderFrame();
    renderer.setCamera(cameraMatrices(moved, 0, 1.0f));
    renderer.renderFrame();
    const ImageF afterMove = renderer.readHdr();
    Renderer fresh(moved, s);
    fresh.renderFrame();
    const ImageF first = fresh.readHdr();
    for (int i = 0; i < 16; ++i) fresh.renderFrame();
    const ImageF steady = fresh.readHdr();
    auto meanAbsError = [&truth](const ImageF& img) {
        double e = 0;
        for (size_t i = 0; i < img.rgba.size(); i += 4) e += std::abs(img.rgba[i] - truth.rgba[i]);
        return e / double(img.rgba.size() / 4);
    };
    const double moveError = meanAbsError(afterMove), freshError = meanAbsError(first),
                 steadyError = meanAbsError(steady);
    std::printf("mean |error| after the move %.4g, first frame %.4g, after 17 frames %.4g\n", moveError, freshError,
                steadyError);
    EXPECT_LT(moveError, 1.1 * std::max(freshError, steadyError));
}

// Extremes: finite, never a black frame, and the floor's value where it has one.
TEST(EmitterLights, VeryBrightEmitterStaysFinite) {
    const Scene scene = emitterFloorScene(1e6f);
    const RenderSettings s = restirSettings();
    const ImageF img = renderHdr(scene, s);
    ASSERT_TRUE(allFinite(img));
    const auto [rendered, analytic] = floorMeans(scene, s, img, 1e6, glm::vec3(0), 2);
    EXPECT_NEAR(rendered, analytic, 0.02 * analytic);
}

// The counting guards (GIS_CHECK_FINITE, set for every test): a NaN that reaches a guard (here a
// sun of NaN irradiance, which no loader lets through) is counted and named with its pass, not
// hidden as a black pixel.
TEST(EmitterLights, NanReachingAGuardIsCountedNotHidden) {
    ASSERT_TRUE(countingNonFinite()) << "ctest sets GIS_CHECK_FINITE=1";
    context();
    RenderSettings s = restirSettings(32);
    s.hdr32 = true;
    Scene broken = emitterFloorScene();
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1, 0.2f));
    sun.intensity = std::nanf("");
    broken.lights.push_back(sun);
    Renderer renderer(broken, s);
    renderer.renderFrame();
    const std::string report = renderer.nonFiniteReport();
    std::printf("%s\n", report.c_str());
    EXPECT_NE(report.find("pass '"), std::string::npos) << "nothing counted";
    Renderer sane(emitterFloorScene(), s);
    sane.renderFrame();
    EXPECT_EQ(sane.nonFiniteReport(), "");
}

TEST(EmitterLights, HundredThousandEmissiveTrianglesLightTheFloor) {
    // The emitter as a 224 x 224 grid of quads (100352 triangles) of the same size and radiance.
    Scene scene = emitterFloorScene();
    scene.primitives.pop_back();
    scene.draws.pop_back();
    const int n = 224;
    Primitive p;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            Vertex v;
            v.position = glm::vec3((float(i) / n - 0.5f) * kEmitterSize, kEmitterHeight, (float(j) / n - 0.5f) * kEmitterSize);
            v.normal = glm::vec3(0, -1, 0);
            p.vertices.push_back(v);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            // Counter-clockwise seen from below (the emitting side).
            for (uint32_t idx : {a, b, c, b, d, c}) p.indices.push_back(idx);
        }
    p.material = 1;
    scene.primitives.push_back(p);
    scene.draws.push_back({int(scene.primitives.size()) - 1, glm::mat4(1.0f)});
    const RenderSettings s = restirSettings();
    const ImageF img = renderHdr(scene, s);
    ASSERT_TRUE(allFinite(img));
    const auto [rendered, analytic] = floorMeans(scene, s, img, 4.0, glm::vec3(0), 2);
    EXPECT_NEAR(rendered, analytic, 0.02 * analytic);
}

TEST(EmitterLights, EmitterFacingAwayLightsNothingAndTheFrameIsNotBlack) {
    Scene scene = emitterFloorScene();
    std::vector<uint32_t>& idx = scene.primitives[1].indices;  // flipped: it emits upwards, into the void
    for (size_t t = 0; t + 2 < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
    for (Vertex& v : scene.primitives[1].vertices) v.normal = glm::vec3(0, 1, 0);
    scene.cameras[0] = lookAtCamera(glm::vec3(0, 2.5f, 1.5f), glm::vec3(0));  // sees its lit side
    const RenderSettings s = restirSettings();
    const ImageF img = renderHdr(scene, s);
    ASSERT_TRUE(allFinite(img));
    const glm::ivec2 floor = projectToPixel(scene, s, glm::vec3(1.0f, 0, 0.5f));
    EXPECT_EQ(meanAround(img, floor.x, floor.y, 1), 0.0);
    const glm::ivec2 lamp = projectToPixel(scene, s, glm::vec3(0, kEmitterHeight, 0));
    EXPECT_NEAR(meanAround(img, lamp.x, lamp.y, 1), 4.0, 1e-3);
}

TEST(EmitterLights, RadianceDoesNotDependOnTheSceneScale) {
    const Scene scene = emitterFloorScene();
    const RenderSettings s = restirSettings();
    // The analytic value of the unscaled scene at the same pixels (radiance has no unit of length).
    const ImageF reference = renderHdr(scene, s);
    const auto [unscaled, analytic] = floorMeans(scene, s, reference, 4.0, glm::vec3(0), 2);
    for (float scale : {1e-3f, 1e3f}) {
        const Scene scaled = scaledScene(scene, scale);
        const ImageF img = renderHdr(scaled, s);
        ASSERT_TRUE(allFinite(img)) << scale;
        const glm::ivec2 c = projectToPixel(scaled, s, glm::vec3(0));
        EXPECT_NEAR(meanAround(img, c.x, c.y, 2), analytic, 0.02 * analytic) << scale;
    }
    EXPECT_NEAR(unscaled, analytic, 0.02 * analytic);
}

TEST(EmitterLights, ParametersAreOneListedTable) {
    RenderSettings s;
    setParam(s, "emitters.candidates", "16");
    EXPECT_EQ(emitterLightSettings(s).candidates, 16);
    EXPECT_THROW(setParam(s, "emitters.candidates", "0"), Error);
    EXPECT_THROW(setParam(s, "emitters.nonsense", "1"), Error);
    EXPECT_THROW(setParam(s, "emitters.mode", "sometimes"), Error);
    // The mode rebuilds (passes differ); the reuse parameters are live.
    RenderSettings other = s;
    setParam(other, "emitters.mode", "gi");  // the default is lights
    EXPECT_TRUE(requiresRebuild(s, other));
    other = s;
    setParam(other, "emitters.spatial", "5");
    EXPECT_FALSE(requiresRebuild(s, other));
    // A new background is live, unless the environment is a light of the pass: it then decides
    // whether the pass exists and lights the GI volume.
    other = s;
    other.background = glm::vec3(0.5f);
    EXPECT_FALSE(requiresRebuild(s, other));
    setParam(s, "emitters.environment", "true");
    other = s;
    other.background = glm::vec3(0.5f);
    EXPECT_TRUE(requiresRebuild(s, other));
}

}  // namespace
}  // namespace gis::test
