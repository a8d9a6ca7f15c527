#include "sdf_test_util.h"

#include "render_test_util.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace gis::test {

SeedGrid uniformSeeds(int n, int count, uint32_t rng) {
    SeedGrid g{n, std::vector<uint8_t>(size_t(n) * n * n, 0), std::vector<glm::vec3>(size_t(n) * n * n)};
    std::mt19937 gen(rng);
    std::uniform_int_distribution<int> cell(0, n - 1);
    for (int i = 0; i < count; ++i) g.seed[g.index(cell(gen), cell(gen), cell(gen))] = 1;
    return g;
}

SeedGrid clusteredSeeds(int n, int clusters, int perCluster, float sigma, uint32_t rng) {
    SeedGrid g{n, std::vector<uint8_t>(size_t(n) * n * n, 0), std::vector<glm::vec3>(size_t(n) * n * n)};
    std::mt19937 gen(rng);
    std::uniform_real_distribution<float> centre(0.0f, float(n));
    std::normal_distribution<float> spread(0.0f, sigma);
    for (int c = 0; c < clusters; ++c) {
        const glm::vec3 m(centre(gen), centre(gen), centre(gen));
        for (int i = 0; i < perCluster; ++i) {
            glm::ivec3 p(glm::floor(m + glm::vec3(spread(gen), spread(gen), spread(gen))));
            p = glm::clamp(p, glm::ivec3(0), glm::ivec3(n - 1));
            g.seed[g.index(p.x, p.y, p.z)] = 1;
        }
    }
    return g;
}

namespace {

// 1D squared distance transform of f (Felzenszwalb & Huttenlocher 2012): the lower envelope of the
// parabolas (x - q)^2 + f(q).
void transform1d(std::vector<double>& f, std::vector<int>& v, std::vector<double>& z, std::vector<double>& out) {
    const int n = int(f.size());
    const double inf = std::numeric_limits<double>::infinity();
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] == inf) continue;
        while (k >= 0) {
            const double s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
            if (s <= z[k]) {
                --k;
                continue;
            }
            break;
        }
        ++k;
        v[k] = q;
        z[k] = k == 0 ? -inf : ((f[q] + double(q) * q) - (f[v[k - 1]] + double(v[k - 1]) * v[k - 1])) / (2.0 * (q - v[k - 1]));
        z[k + 1] = inf;
    }
    if (k < 0) {
        std::fill(out.begin(), out.end(), inf);
        return;
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (z[j + 1] < q) ++j;
        out[q] = double(q - v[j]) * (q - v[j]) + f[v[j]];
    }
}

}  // namespace

std::vector<double> exactDistance(const SeedGrid& g) {
    const int n = g.n;
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> d(g.seed.size());
    for (size_t i = 0; i < d.size(); ++i) d[i] = g.seed[i] ? 0.0 : inf;
    std::vector<double> f(n), out(n), z(n + 1);
    std::vector<int> v(n);
    const size_t strides[3] = {1, size_t(n), size_t(n) * n};
    for (int axis = 0; axis < 3; ++axis) {
        const size_t s = strides[axis], a = strides[(axis + 1) % 3], b = strides[(axis + 2) % 3];
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const size_t base = i * a + j * b;
                for (int q = 0; q < n; ++q) f[q] = d[base + q * s];
                transform1d(f, v, z, out);
                for (int q = 0; q < n; ++q) d[base + q * s] = out[q];
            }
    }
    for (double& x : d) x = std::sqrt(x);
    return d;
}

std::vector<double> bruteForceDistance(const SeedGrid& g) {
    const int n = g.n;
    std::vector<glm::ivec3> seeds;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                if (g.seed[g.index(x, y, z)]) seeds.push_back({x, y, z});
    std::vector<double> d(g.seed.size(), std::numeric_limits<double>::infinity());
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                for (const glm::ivec3& s : seeds) {
                    const glm::dvec3 e = glm::dvec3(s - glm::ivec3(x, y, z));
                    d[g.index(x, y, z)] = std::min(d[g.index(x, y, z)], std::sqrt(glm::dot(e, e)));
                }
    return d;
}

SeedTextures uploadSeeds(const SeedGrid& g, const gl::MemoryScope& scope) {
    context();  // the test binary's headless GL context, current from here on
    const int n = g.n;
    std::vector<uint8_t> occupancy(g.seed.size() * 4, 0), normals(g.seed.size() * 4, 0);
    for (size_t i = 0; i < g.seed.size(); ++i) {
        occupancy[i * 4 + 3] = g.seed[i] ? 255 : 0;
        for (int c = 0; c < 3; ++c)
            normals[i * 4 + c] = uint8_t(std::lround(glm::clamp(g.normal[i][c] * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f));
        normals[i * 4 + 3] = 255;
    }
    SeedTextures t;
    t.occupancy = gl::createTexture3D(scope, GL_RGBA8, n, n, n);
    glTextureSubImage3D(t.occupancy.id(), 0, 0, 0, 0, n, n, n, GL_RGBA, GL_UNSIGNED_BYTE, occupancy.data());
    t.normals = gl::createTexture3D(scope, GL_RGBA8, n, n, n);
    glTextureSubImage3D(t.normals.id(), 0, 0, 0, 0, n, n, n, GL_RGBA, GL_UNSIGNED_BYTE, normals.data());
    return t;
}

}  // namespace gis::test
