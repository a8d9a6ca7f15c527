// The path-traced reference against an external renderer (Blender Cycles, shared/assets/reference)
// and against closed-form answers.
#include <cstdio>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_util.h"

namespace gis::test {
namespace {

const std::string kReference = std::string(GIS_SHARED_DIR) + "/assets/reference";

// Cycles' references are 256x256 at 2048 spp. The path tracer renders 64x64 (a quarter of the
// resolution) and the reference is box-downsampled 4x4 to match, so each compared pixel averages
// 16 reference pixels: the reference's own noise there is ~0.25% (README of the references).
constexpr int kSize = 64;
constexpr int kSpp = 256;
constexpr double kImageTolerance = 0.02;
constexpr double kRegionTolerance = 0.02;

struct CyclesCase {
    const char* scene;    // folder under scenes/ and refs/
    const char* pass;     // full, direct, bounce1
    int maxBounces;
};

void PrintTo(const CyclesCase& c, std::ostream* os) { *os << c.scene << "/" << c.pass; }

class MatchesCycles : public ::testing::TestWithParam<CyclesCase> {};

double sum3(const float* p) { return double(p[0]) + p[1] + p[2]; }

TEST_P(MatchesCycles, ImageAndFaceMeansWithinTwoPercent) {
    const CyclesCase& c = GetParam();
    const Scene scene = loadGltfFile(kReference + "/scenes/" + c.scene + "/" + c.scene + ".gltf");
    const ImageF ref = downsample(readExr(kReference + "/refs/" + c.scene + "/" + c.pass + ".exr"), 256 / kSize);
    RenderSettings r;
    r.width = r.height = kSize;
    r.gi = "pathtrace";
    setParam(r, "--spp", std::to_string(kSpp));
    r.samplesPerFrame = 32;
    setParam(r, "pathtrace.bounces", std::to_string(c.maxBounces));
    const ImageF img = renderHdr(scene, r);

    // Faces seen at pixel centres, edges masked: per-region means compare like with like.
    const std::vector<PixelHit> hits = castPixels(scene, 0, kSize, kSize, nullptr);
    const std::vector<bool> keep = interiorPixels(hits, kSize, kSize, 1, 0);
    struct Sum { double ours = 0, cycles = 0; int n = 0; };
    std::map<int, Sum> regions;
    Sum image;
    double relErrSum = 0.0;
    int relErrCount = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const double a = sum3(img.at(x, y)), b = sum3(ref.at(x, y));
            image.ours += a;
            image.cycles += b;
            if (b > 1e-3) {
                relErrSum += std::abs(a - b) / b;
                ++relErrCount;
            }
            const size_t i = size_t(y) * kSize + x;
            if (!keep[i]) continue;
            Sum& s = regions[hits[i].region];
            s.ours += a;
            s.cycles += b;
            ++s.n;
        }
    const double imageErr = std::abs(image.ours - image.cycles) / image.cycles;
    std::printf("%s/%s: image mean ours %.5f cycles %.5f (error %.2f%%); mean per-pixel relative error %.2f%% "
                "(noise-dominated at %d spp)\n",
                c.scene, c.pass, image.ours / (3.0 * kSize * kSize), image.cycles / (3.0 * kSize * kSize),
                100.0 * imageErr, 100.0 * relErrSum / std::max(relErrCount, 1), kSpp);
    EXPECT_LT(imageErr, kImageTolerance);
    int compared = 0;
    for (const auto& [region, s] : regions) {
        if (s.n < 20 || s.cycles / s.n < 3e-3) continue;  // slivers; faces in full shadow
        const double err = std::abs(s.ours - s.cycles) / s.cycles;
        std::printf("  region %2d/%d  %4d px  ours %.5f  cycles %.5f  error %.2f%%\n", region / 8, region % 8, s.n,
                    s.ours / (3.0 * s.n), s.cycles / (3.0 * s.n), 100.0 * err);
        EXPECT_LT(err, kRegionTolerance) << "draw " << region / 8 << " face " << region % 8;
        ++compared;
    }
    EXPECT_GE(compared, 5);
}

INSTANTIATE_TEST_SUITE_P(
    CornellBoxes, MatchesCycles,
    ::testing::Values(CyclesCase{"cornell_box", "full", 64}, CyclesCase{"cornell_box", "direct", 0},
                      CyclesCase{"cornell_box", "bounce1", 1}, CyclesCase{"cornell_point", "full", 64},
                      CyclesCase{"cornell_point", "direct", 0}, CyclesCase{"cornell_point", "bounce1", 1}),
    [](const auto& info) { return std::string(info.param.scene) + "_" + info.param.pass; });

// A UV sphere of radius r at the origin, smooth normals.
void addSphere(Scene& s, float radius, int material, int rings = 24, int segments = 48) {
    Primitive p;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float theta = glm::pi<float>() * i / rings, phi = 2.0f * glm::pi<float>() * j / segments;
            Vertex v;
            v.normal = glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            v.position = v.normal * radius;
            p.vertices.push_back(v);
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = i * (segments + 1) + j, b = a + segments + 1;
            for (uint32_t idx : {a, a + 1, b, b, a + 1, b + 1}) p.indices.push_back(idx);
        }
    p.material = material;
    s.primitives.push_back(p);
    s.draws.push_back({int(s.primitives.size()) - 1, glm::mat4(1.0f)});
}

// White furnace: a white Lambertian sphere under a uniform white sky reflects exactly the sky's
// radiance (every bounce keeps all energy; paths end only by escaping), so every pixel is 1.
TEST(PathTrace, FurnaceSphereReturnsSkyRadiance) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(1.0f)));
    addSphere(s, 1.0f, 0);
    s.background = glm::vec3(1.0f);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 0, 3.5f), glm::vec3(0), 40.0f));
    finalizeScene(s);
    RenderSettings r;
    r.width = r.height = 24;
    r.gi = "pathtrace";
    setParam(r, "--spp", std::to_string(1024));
    r.samplesPerFrame = 128;
    setParam(r, "pathtrace.bounces", std::to_string(64));
    const ImageF img = renderHdr(s, r);
    double worst = 0.0, mean = 0.0;
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x)
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(img.at(x, y)[c] - 1.0));
                mean += img.at(x, y)[c] / (3.0 * r.width * r.height);
            }
    std::printf("furnace: mean %.5f, worst pixel off by %.4f\n", mean, worst);
    EXPECT_NEAR(mean, 1.0, 0.02);
    EXPECT_LT(worst, 0.02);
}

ImageF renderCornell(int spp, uint32_t seed = 0) {
    RenderSettings r;
    r.width = r.height = 32;
    r.gi = "pathtrace";
    setParam(r, "--spp", std::to_string(spp));
    r.samplesPerFrame = 64;
    r.seed = seed;
    return renderHdr(makeBuiltinScene("cornell-area"), r);
}

double rmse(const ImageF& a, const ImageF& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); ++i)
        if (i % 4 != 3) sum += double(a.rgba[i] - b.rgba[i]) * (a.rgba[i] - b.rgba[i]);
    return std::sqrt(sum / (a.rgba.size() * 0.75));
}

TEST(PathTrace, DeterministicWithAFixedSeed) {
    const ImageF a = renderCornell(8), b = renderCornell(8), c = renderCornell(8, 7);
    EXPECT_TRUE(a.rgba == b.rgba);
    EXPECT_FALSE(a.rgba == c.rgba);  // the seed matters
}

// Monte Carlo error falls as 1/sqrt(spp): four times the samples, half the error. Against a
// reference with 16x the larger sample count, the expected RMSE ratio between 16 and 64 spp is
// sqrt((4 + 1/16) / (1 + 1/16)) = 1.96 (the reference's own variance adds to both).
TEST(PathTrace, ConvergesAsOneOverSqrtSpp) {
    const ImageF ref = renderCornell(1024, 99);
    const double e16 = rmse(renderCornell(16), ref), e64 = rmse(renderCornell(64), ref);
    std::printf("RMSE vs 1024 spp: 16 spp %.5f, 64 spp %.5f, ratio %.2f (expected 1.96)\n", e16, e64, e16 / e64);
    EXPECT_GT(e16 / e64, 1.6);
    EXPECT_LT(e16 / e64, 2.4);
}

}  // namespace
}  // namespace gis::test

namespace gis::test {
namespace {

// DamagedHelmet under a uniform white sky (shared/assets/reference/refs/DamagedHelmet_sky): a
// textured, normal-mapped, metallic asset that Cycles shades with Blender's Principled BSDF, not
// our GGX + Lambert - so this measures, and bounds loosely, rather than asserting a match.
TEST(PathTrace, DamagedHelmetUnderWhiteSkyAgainstCycles) {
    const std::string shared = GIS_SHARED_DIR;
    Scene s = loadGltfFile(shared + "/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf");
    s.background = glm::vec3(1.0f);
    s.cameras.clear();
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 0, 3.2f), glm::vec3(0), 40.0f));
    const int size = 64;
    RenderSettings r;
    r.width = r.height = size;
    r.gi = "pathtrace";
    setParam(r, "--spp", std::to_string(128));
    r.samplesPerFrame = 32;
    setParam(r, "pathtrace.bounces", std::to_string(64));
    const ImageF img = renderHdr(s, r);
    const ImageF ref = downsample(readExr(shared + "/assets/reference/refs/DamagedHelmet_sky/full.exr"), 256 / size);
    // Helmet pixels only: the sky reads exactly 1 in both.
    double ours = 0.0, cycles = 0.0;
    int n = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float* p = ref.at(x, y);
            if (std::abs(p[0] - 1.0f) < 1e-4f && std::abs(p[1] - 1.0f) < 1e-4f && std::abs(p[2] - 1.0f) < 1e-4f) continue;
            ours += sum3(img.at(x, y));
            cycles += sum3(p);
            ++n;
        }
    const double err = std::abs(ours - cycles) / cycles;
    std::printf("DamagedHelmet_sky full: %d helmet pixels, mean ours %.4f cycles %.4f, error %.1f%%\n", n,
                ours / (3.0 * n), cycles / (3.0 * n), 100.0 * err);
    EXPECT_GT(n, size * size / 4);
    EXPECT_LT(err, 0.06);  // measured 3.3%: Principled BSDF vs GGX + Lambert, textures resampled to 1024
}

}  // namespace
}  // namespace gis::test

namespace gis::test {
namespace {

RayCounts pathTracerRays(const Scene& scene, int size, int spp, int bounces, double* mraysPerSecond = nullptr) {
    context();
    RenderSettings r;
    r.width = r.height = size;
    r.gi = "pathtrace";
    setParam(r, "pathtrace.spp", std::to_string(spp));
    setParam(r, "pathtrace.bounces", std::to_string(bounces));
    r.samplesPerFrame = 2;
    Renderer renderer(scene, r);
    do renderer.renderFrame();
    while (!renderer.converged());
    for (const PassTiming& t : renderer.timings(0))
        if (t.pass == "pathtrace" && t.rays) {
            if (mraysPerSecond) *mraysPerSecond = t.megaRaysPerSecond();
            return *t.rays;
        }
    ADD_FAILURE() << "the pathtrace pass reported no ray counts";
    return {};
}

// Throughput (`--timings`' Mrays/s) is only as honest as its counts: one camera ray per pixel and
// sample exactly, and shadow and bounce rays within what the path's structure allows.
TEST(PathTrace, CountsTheRaysItTraces) {
    const Scene cornell = makeBuiltinScene("cornell");  // closed box, one point light, no emitters
    double mrays = 0.0;
    const RayCounts direct = pathTracerRays(cornell, 16, 4, 0, &mrays);
    const uint64_t samples = 16 * 16 * 4;
    EXPECT_EQ(direct.primary, samples);
    // bounces = 0: every camera ray hits the box; its one shadow ray goes where N.L > 0, and the
    // continuation ray is traced only to look for emission.
    EXPECT_GT(direct.shadow, samples / 2);
    EXPECT_LE(direct.shadow, samples);
    EXPECT_LE(direct.bounce, samples);
    EXPECT_GT(mrays, 0.0);

    const RayCounts deep = pathTracerRays(cornell, 16, 4, 8);
    EXPECT_EQ(deep.primary, samples);
    EXPECT_GT(deep.bounce, 2 * direct.bounce);  // paths go on bouncing in a closed box
    EXPECT_LE(deep.shadow, samples * 9);        // at most one per vertex: one light, no emitters
    EXPECT_LE(deep.bounce, samples * 9);

    Scene empty = makeBuiltinScene("cornell");
    empty.cameras[0] = lookAtCamera(glm::vec3(0, 0, 100), glm::vec3(0, 0, 200));  // looking away: all miss
    const RayCounts miss = pathTracerRays(empty, 8, 2, 4);
    EXPECT_EQ(miss.primary, 8u * 8u * 2u);
    EXPECT_EQ(miss.bounce, 0u);
    EXPECT_EQ(miss.shadow, 0u);
}

}  // namespace
}  // namespace gis::test
