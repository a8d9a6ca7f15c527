// Environment maps on the CPU: loading the shipped sky and the one-line errors for bad files, the
// SH9 irradiance against brute-force integration, and importance sampling against uniform
// sampling (same mean, lower variance).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "cli_util.h"
#include "environment.h"
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

}  // namespace
}  // namespace gis::test
