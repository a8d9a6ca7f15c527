// Environment maps on the CPU: loading the shipped sky and the one-line errors for bad files, the
// SH9 irradiance against brute-force integration, and importance sampling against uniform
// sampling (same mean, lower variance).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <random>

#include "cli_util.h"
#include "environment.h"
#include "scene/limits.h"
#include "scene/scene.h"

namespace gis::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
const std::string kSky = std::string(GIS_SOURCE_DIR) + "/assets/environments/sky_sun.hdr";

std::string loadError(const std::string& path) {
    try {
        loadEnvironmentMap(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// Radiance files written byte by byte: a header, then either flat RGBE or new-style run-length
// scanlines (2, 2, width; each channel as literal runs of up to 128 bytes).
std::string hdrHeader(int width, int height, const std::string& extra = "") {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n" + extra + "\n-Y " + std::to_string(height) + " +X " +
           std::to_string(width) + "\n";
}
std::string flatHdr(int width, int height, const unsigned char rgbe[4], const std::string& extra = "") {
    std::string s = hdrHeader(width, height, extra);
    for (int i = 0; i < width * height; ++i) s.append(reinterpret_cast<const char*>(rgbe), 4);
    return s;
}
std::string rleHdr(int width, int height, const unsigned char rgbe[4]) {
    std::string s = hdrHeader(width, height);
    for (int y = 0; y < height; ++y) {
        s += {char(2), char(2), char(width >> 8), char(width & 255)};
        for (int c = 0; c < 4; ++c)
            for (int x = 0; x < width; x += 128) {
                const int n = std::min(128, width - x);
                s += char(n);
                s.append(size_t(n), char(rgbe[c]));
            }
    }
    return s;
}
std::string writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}
const unsigned char kGrey[4] = {128, 128, 128, 129};  // 0.5 x 2^1 = 1.0

// E(n) by summing every texel (the map is piecewise constant, so this is its exact irradiance up to
// the cosine's variation inside a texel).
glm::dvec3 bruteIrradiance(const EnvironmentMap& map, glm::vec3 n) {
    glm::dvec3 e(0.0);
    for (int y = 0; y < map.height; ++y) {
        // Subdivide each texel 4x4 so the cosine is integrated finely too.
        for (int x = 0; x < map.width; ++x)
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const float v0 = (float(y) + sy / 4.0f) / float(map.height), v1 = v0 + 0.25f / float(map.height);
                    const glm::vec3 d = equirectToDirection({(float(x) + (sx + 0.5f) / 4.0f) / float(map.width), 0.5f * (v0 + v1)});
                    const double dw = 2.0 * kPi / (map.width * 4.0) * (std::cos(kPi * v0) - std::cos(kPi * v1));
                    e += glm::dvec3(map.at(x, y)) * dw * std::max(0.0, double(glm::dot(n, d)));
                }
    }
    return e;
}

TEST(Environment, ShippedSkyLoads) {
    const EnvironmentMap sky = loadEnvironmentMap(kSky);
    EXPECT_EQ(sky.width, 128);
    EXPECT_EQ(sky.height, 64);
    float peak = 0.0f;
    for (const glm::vec3& t : sky.texels) peak = std::max(peak, t.r);
    EXPECT_GT(peak, 50.0f) << "the sun disc";
    // The sun's direction (the default sun's: elevation 50, azimuth 30 degrees) is its brightest texel.
    const float e = glm::radians(kDefaultSunElevationDegrees), a = glm::radians(kDefaultSunAzimuthDegrees);
    const glm::vec3 toSun(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
    EXPECT_GT(sampleNearest(sky, toSun).r, 0.3f * peak);
}

// Blender's mapping (Blender 3.4, Cycles' Environment Texture node, default mapping: a map whose
// texels encode their own (u, v), rendered there), in glTF axes: u = 0.5 + atan2(z, x) / 2pi,
// v from the top = acos(y) / pi. So a map lights a scene here as in a Cycles render of it.
TEST(Environment, MappingIsBlenders) {
    struct Case {
        const char* name;
        glm::vec3 d;
        float u, v;
    };
    for (const Case& c : {Case{"+X", {1, 0, 0}, 0.5f, 0.5f}, Case{"-Z", {0, 0, -1}, 0.25f, 0.5f},
                          Case{"+Z", {0, 0, 1}, 0.75f, 0.5f}, Case{"-X", {-1, 0, 0}, 0.0f, 0.5f},
                          Case{"up", {0, 1, 0}, -1.0f, 0.0f}}) {
        SCOPED_TRACE(c.name);
        const glm::vec2 uv = directionToEquirect(c.d);
        EXPECT_NEAR(uv.y, c.v, 1e-6f);
        if (c.u < 0.0f) continue;  // up has no azimuth
        EXPECT_NEAR(uv.x, c.u, 1e-6f);
        EXPECT_NEAR(glm::length(equirectToDirection(uv) - c.d), 0.0f, 1e-6f) << "the inverse";
    }
    // Both ways round, over the sphere and over the image (the poles' azimuth aside).
    std::mt19937 rng(5);
    std::normal_distribution<float> g;
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        // Float acos near the poles: a few ulps of y there are 1e-5 of angle.
        EXPECT_NEAR(glm::length(equirectToDirection(directionToEquirect(d)) - d), 0.0f, 1e-5f) << i;
        const glm::vec2 uv((float(i % 40) + 0.5f) / 40.0f, (float(i / 40) + 0.5f) / 25.0f);
        const glm::vec2 back = directionToEquirect(equirectToDirection(uv));
        EXPECT_NEAR(back.x, uv.x, 2e-6f) << i;
        EXPECT_NEAR(back.y, uv.y, 2e-6f) << i;
    }
}

// --environment-rotation about +Y, right-handed: 90 turns the centre column from +X to -Z, which
// is the mapping gisandbox had before it took Blender's (u = 0.5 + atan2(x, -z) / 2pi): the shipped
// sky was re-generated for that, and the rotation gives an old map its old look.
TEST(Environment, RotationNinetyIsTheEarlierMapping) {
    EXPECT_NEAR(directionToEquirect(environmentToMap({0, 0, -1}, 90.0f)).x, 0.5f, 1e-6f);
    EXPECT_NEAR(directionToEquirect(environmentToMap({0, 0, 1}, -90.0f)).x, 0.5f, 1e-6f);
    std::mt19937 rng(6);
    std::normal_distribution<float> g;
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        const float earlier = std::atan2(d.x, -d.z) / float(2.0 * kPi) + 0.5f;
        const float u = directionToEquirect(environmentToMap(d, 90.0f)).x;
        EXPECT_NEAR(std::remainder(u - earlier, 1.0f), 0.0f, 2e-6f) << i;
        EXPECT_EQ(environmentToMap(d, 90.0f).y, d.y);
        EXPECT_NEAR(glm::length(environmentToMap(environmentToMap(d, 37.0f), -37.0f) - d), 0.0f, 1e-6f) << i;
    }
}

double meanOverTheSphere(const EnvironmentMap& map) {
    double sum = 0.0, steradians = 0.0;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const glm::vec3 L = map.at(x, y);
            sum += texelSolidAngle(map, y) * (L.r + L.g + L.b) / 3.0;
            steradians += texelSolidAngle(map, y);
        }
    return sum / steradians;
}

// Every mip level keeps the map's mean radiance over the sphere, down to one texel: each coarse
// texel weighs the finer ones by their solid angle. GL's box filter lost a fifth of the shipped
// sky's mean at 8x4 texels (its sun high in the sky), the level a 32-ray probe's miss reads.
TEST(Environment, MipLevelsKeepTheMeanOverTheSphere) {
    for (const EnvironmentMap& map : {loadEnvironmentMap(kSky), constantEnvironment(glm::vec3(0.5f, 1.0f, 2.0f))}) {
        const double mean = meanOverTheSphere(map);
        EnvironmentMap level = map;
        while (level.width > 1 || level.height > 1) {
            level = nextMipLevel(level);
            SCOPED_TRACE(std::to_string(level.width) + "x" + std::to_string(level.height));
            EXPECT_NEAR(meanOverTheSphere(level) / mean, 1.0, 1e-5);
        }
    }
    // Odd sizes: the last coarse texel takes the odd row and column, so coarse texels of equal solid
    // angle cover unequal finer ones and the mean holds only roughly (exactly for a constant map).
    EnvironmentMap odd;
    odd.width = 5;
    odd.height = 3;
    for (int i = 0; i < 15; ++i) odd.texels.push_back(glm::vec3(float(i * i % 7) + 0.25f));
    const EnvironmentMap half = nextMipLevel(odd);
    EXPECT_EQ(half.width, 2);
    EXPECT_EQ(half.height, 1);
    EXPECT_NEAR(meanOverTheSphere(half) / meanOverTheSphere(odd), 1.0, 1e-2);
    for (glm::vec3& texel : odd.texels) texel = glm::vec3(0.75f);
    for (const glm::vec3& texel : nextMipLevel(odd).texels) EXPECT_NEAR(texel.g, 0.75f, 1e-6f);
}

TEST(Environment, BadFilesAreOneClearError) {
    const std::string dir = tempDir("environment_bad");
    EXPECT_NE(loadError(dir + "/none.hdr").find("does not exist"), std::string::npos);
    {
        std::ofstream f(dir + "/picture.hdr", std::ios::binary);
        f << "\x89PNG\r\n\x1a\n not an hdr";
    }
    EXPECT_NE(loadError(dir + "/picture.hdr").find("is not a Radiance .hdr file"), std::string::npos)
        << loadError(dir + "/picture.hdr");
    const auto size = std::filesystem::file_size(kSky);
    std::ifstream in(kSky, std::ios::binary);
    std::string bytes(size, '\0');
    in.read(bytes.data(), std::streamsize(size));
    for (size_t keep : {size_t(40), size / 2, size - 3}) {
        SCOPED_TRACE(keep);
        const std::string cut = dir + "/cut.hdr";
        std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(keep));
        const std::string why = loadError(cut);
        EXPECT_FALSE(why.empty()) << "a truncated file must not load";
        EXPECT_EQ(why.find('\n'), std::string::npos) << why;
        EXPECT_NE(why.find("cut.hdr"), std::string::npos) << why;
    }
    EXPECT_TRUE(loadError(kSky).empty()) << loadError(kSky);
}

TEST(Environment, ConstantMapIsTheBackground) {
    const glm::vec3 l(0.4f, 0.3f, 0.2f);
    const EnvironmentMap c = constantEnvironment(l);
    const Sh9 sh = projectSh9(c);
    for (glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, -2, 3))}) {
        const glm::vec3 e = shIrradiance(sh, n);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(e[k], kPi * l[k], 1e-4 * kPi) << "E = pi L for a constant map";
    }
    const EnvironmentSampler sampler(c);
    EXPECT_NEAR(sampler.pdf(glm::vec3(0, 0, -1)), 1.0 / (4.0 * kPi), 1e-5);
}

TEST(Environment, ShIrradianceMatchesIntegrationWithinOnePercent) {
    // A non-uniform map whose radiance lies in bands 0-2 (sky above, darker ground, brighter
    // towards +X): SH9 holds it exactly, so any error is the projection's or the mapping's.
    EnvironmentMap map;
    map.width = 128;
    map.height = 64;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const glm::vec3 d = equirectToDirection({(x + 0.5f) / map.width, (y + 0.5f) / map.height});
            map.texels.push_back(glm::vec3(1.0f + 0.6f * d.y + 0.3f * d.x * d.x, 0.8f + 0.5f * d.x * d.z, 0.7f - 0.4f * d.z));
        }
    const Sh9 sh = projectSh9(map);
    double worst = 0.0;
    for (glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1),
                        glm::normalize(glm::vec3(1, 1, 1)), glm::normalize(glm::vec3(-2, 0.5f, 1))}) {
        const glm::dvec3 truth = bruteIrradiance(map, n);
        const glm::vec3 e = shIrradiance(sh, n);
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(e[k] - truth[k]) / truth[k]);
    }
    std::printf("SH9 irradiance vs integration, band-limited map: worst relative error %.5f\n", worst);
    EXPECT_LT(worst, 0.01);
    // The shipped sky has a sun: SH9 is a low-pass view of it, printed for the record.
    const EnvironmentMap sky = loadEnvironmentMap(kSky);
    const glm::dvec3 up = bruteIrradiance(sky, glm::vec3(0, 1, 0));
    const glm::vec3 upSh = shIrradiance(projectSh9(sky), glm::vec3(0, 1, 0));
    std::printf("shipped sky, up-facing irradiance: integrated %.4f, SH9 %.4f\n", up.g, upSh.g);
}

TEST(Environment, ImportanceSamplingSameMeanLowerVariance) {
    // Irradiance of an up-facing surface under the shipped sky, estimated with uniform sphere
    // sampling and with the luminance sampler; both unbiased, the sampler far less noisy.
    const EnvironmentMap sky = loadEnvironmentMap(kSky);
    const EnvironmentSampler sampler(sky);
    const glm::vec3 n(0, 1, 0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    const int count = 200000;
    double su = 0, su2 = 0, si = 0, si2 = 0;
    for (int i = 0; i < count; ++i) {
        const float z = 1.0f - 2.0f * u01(rng), phi = 2.0f * float(kPi) * u01(rng), r = std::sqrt(std::max(0.0f, 1 - z * z));
        const glm::vec3 d(r * std::cos(phi), z, r * std::sin(phi));
        const double fu = double(sampleNearest(sky, d).g) * std::max(0.0f, glm::dot(n, d)) * 4.0 * kPi;
        su += fu, su2 += fu * fu;
        const EnvironmentSampler::Sample s = sampler.sample({u01(rng), u01(rng)});
        EXPECT_NEAR(s.pdf, sampler.pdf(s.direction), 1e-3f * s.pdf + 1e-6f)
            << i << " dir " << s.direction.x << "," << s.direction.y << "," << s.direction.z << " uv "
            << directionToEquirect(s.direction).x * sky.width << "," << directionToEquirect(s.direction).y * sky.height;
        const double fi = s.pdf > 0 ? double(sampleNearest(sky, s.direction).g) * std::max(0.0f, glm::dot(n, s.direction)) / s.pdf : 0.0;
        si += fi, si2 += fi * fi;
        if (HasFailure()) return;
    }
    const double mu = su / count, mi = si / count;
    const double vu = su2 / count - mu * mu, vi = si2 / count - mi * mi;
    const double sigma = std::sqrt(vu / count + vi / count);
    const double truth = bruteIrradiance(sky, n).g;
    std::printf("up-facing irradiance: integrated %.4f, uniform %.4f (variance %.3f), importance %.4f (variance %.4f)\n",
                truth, mu, vu, mi, vi);
    EXPECT_NEAR(mu, mi, 4.0 * sigma);
    EXPECT_NEAR(mi, truth, 4.0 * std::sqrt(vi / count) + 1e-3 * truth);
    EXPECT_LT(vi, 0.25 * vu);
}

// A scanline whose marker is 1, 1 instead of 2, 2 (same length): stb_image falls back to flat
// pixels from there and decoded stale bytes, a grey map turned magenta with exit 0.
TEST(Environment, ACorruptRunLengthScanlineIsRefused) {
    const std::string dir = tempDir("environment_rle");
    std::string bytes = rleHdr(16, 4, kGrey);
    const std::string good = writeFile(dir + "/good.hdr", bytes);
    for (const glm::vec3& t : loadEnvironmentMap(good).texels) EXPECT_EQ(t, glm::vec3(1.0f));
    const size_t second = hdrHeader(16, 4).size() + (bytes.size() - hdrHeader(16, 4).size()) / 4;
    ASSERT_EQ(bytes[second], 2);
    bytes[second] = bytes[second + 1] = 1;
    const std::string why = loadError(writeFile(dir + "/bad.hdr", bytes));
    EXPECT_NE(why.find("scanline 1"), std::string::npos) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
}

// Sizes the parser cannot take say so (they said the resolution line was missing).
TEST(Environment, ResolutionOutOfRangeSaysWhatIsWrong) {
    const std::string dir = tempDir("environment_size");
    for (const char* size : {"-Y 100000 +X 100000", "-Y 0 +X 4", "-Y -3 +X 4", "-Y 4 +X 99999999999999999999"}) {
        SCOPED_TRACE(size);
        const std::string why = loadError(writeFile(dir + "/s.hdr", "#?RADIANCE\n\n" + std::string(size) + "\n"));
        EXPECT_NE(why.find("out of range"), std::string::npos) << why;
        EXPECT_EQ(why.find("no \"-Y"), std::string::npos) << why;
    }
}

// The memory pre-check's size comes from the whole header, however long (it read 64 KiB).
TEST(Environment, SizeOfAMapWithALongHeader) {
    const std::string dir = tempDir("environment_long_header");
    const std::string comment = "# " + std::string(100000, 'x') + "\n";
    const std::string path = writeFile(dir + "/long.hdr", flatHdr(4, 2, kGrey, comment));
    EXPECT_TRUE(loadError(path).empty()) << loadError(path);
    const std::optional<glm::ivec2> size = environmentMapSize(path);
    ASSERT_TRUE(size.has_value());
    EXPECT_EQ(*size, glm::ivec2(4, 2));
}

// A 1 x 4096 map took seconds (1x16384: 41 s, 1x65536 hung): the projection sampled 256 columns in
// every one of its rows. Its work is bounded by the map's texels now, and E = pi L still holds.
TEST(Environment, ShProjectionOfANarrowMapIsQuickAndRight) {
    EnvironmentMap map;
    map.width = 1;
    map.height = 4096;
    map.texels.assign(size_t(map.height), glm::vec3(0.5f));
    const auto t0 = std::chrono::steady_clock::now();
    const Sh9 sh = projectSh9(map);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(seconds, 1.0);
    for (glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(1, -2, 3))})
        EXPECT_NEAR(shIrradiance(sh, n).g, kPi * 0.5, 1e-3 * kPi);
}

// RGBE exponent 255 (about 1.7e38) loaded, and the SH projection and the sampling CDF overflowed
// to inf (black pixels, exit 0): texels past kMaxRadiance are refused; at the limit both are finite.
TEST(Environment, TexelsPastTheRadianceLimitAreRefused) {
    const std::string dir = tempDir("environment_huge");
    const unsigned char huge[4] = {200, 200, 200, 255};
    const std::string why = loadError(writeFile(dir + "/huge.hdr", flatHdr(4, 2, huge)));
    EXPECT_NE(why.find("texel 0,0"), std::string::npos) << why;
    EXPECT_NE(why.find("1e+18"), std::string::npos) << why;
    EnvironmentMap map;
    map.width = 8;
    map.height = 4;
    map.texels.assign(32, glm::vec3(kMaxRadiance));
    for (const glm::vec3& c : projectSh9(map)) EXPECT_TRUE(std::isfinite(c.r + c.g + c.b));
    const EnvironmentSampler sampler(map);
    EXPECT_TRUE(std::isfinite(sampler.marginalCdf().back()));
    EXPECT_TRUE(std::isfinite(sampler.pdf(glm::vec3(0, 1, 0))));
}

// A FIFO blocked the loader (opening it waits for a writer) and a sparse file of gigabytes beginning
// "#?" (the was 6 GB; 2 GiB is past the limit too) was read whole before any check: both
// are refused before a byte is read.
TEST(Environment, FifoAndHugeFilesAreRefusedBeforeReading) {
    const std::string dir = tempDir("environment_fifo");
    const std::string fifo = dir + "/fifo.hdr";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Both readers: the memory pre-check's size and the load.
    auto result = std::async(std::launch::async, [&] { return environmentMapSize(fifo) ? "" : loadError(fifo); });
    if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
        std::ofstream unblock(fifo);
        ADD_FAILURE() << "loading a FIFO blocked";
    }
    const std::string why = result.get();
    EXPECT_NE(why.find("is not a regular file"), std::string::npos) << why;
    const std::string sparse = writeFile(dir + "/sparse.hdr", "#?RADIANCE\n");
    ASSERT_EQ(::truncate(sparse.c_str(), off_t(2) << 30), 0);
    const auto t0 = std::chrono::steady_clock::now();
    const std::string big = loadError(sparse);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    EXPECT_NE(big.find("too large"), std::string::npos) << big;
}

}  // namespace
}  // namespace gis::test
