#include "probes/probe_math.h"

#include <algorithm>
#include <cmath>

namespace gis::probes {

namespace {
constexpr float kPi = 3.14159265358979f;
}

int irradianceVec4s(Storage s) {
    switch (s) {
    case Storage::Sh1: return 4;
    case Storage::Sh2: return 9;
    case Storage::Octahedral: return kOctIrradianceSize * kOctIrradianceSize;
    }
    return 9;
}
int64_t irradianceBytesPerProbe(Storage s) { return int64_t(irradianceVec4s(s)) * 16; }
int64_t distanceBytesPerProbe() { return int64_t(kOctDistanceSize) * kOctDistanceSize * 8; }
int64_t bytesPerProbe(Storage s) { return irradianceBytesPerProbe(s) + distanceBytesPerProbe() + kStateBytesPerProbe; }

const char* storageName(Storage s) {
    switch (s) {
    case Storage::Sh1: return "sh1";
    case Storage::Sh2: return "sh2";
    case Storage::Octahedral: return "octahedral";
    }
    return "?";
}

glm::vec3 ProbeGrid::position(int index) const {
    const int x = index % counts.x, y = (index / counts.x) % counts.y, z = index / (counts.x * counts.y);
    return first + glm::vec3(x, y, z) * step;
}

int probeIndexNear(const ProbeGrid& g, const glm::vec3& p) {
    const glm::ivec3 c = glm::clamp(glm::ivec3(glm::round((p - g.first) / g.step)), glm::ivec3(0), g.counts - 1);
    return c.x + g.counts.x * (c.y + g.counts.y * c.z);
}

ProbeGrid fitProbeGrid(const Aabb& bounds, float spacing) {
    if (!(spacing > 0.0f) || !std::isfinite(spacing))
        throw Error("probe spacing " + std::to_string(spacing) + " gives no probe grid (it must be > 0)");
    ProbeGrid g;
    if (bounds.empty()) return g;  // no geometry: one probe at the origin sees the sky
    const glm::vec3 extent = bounds.extent();
    if (!std::isfinite(extent.x + extent.y + extent.z + bounds.min.x + bounds.min.y + bounds.min.z))
        throw Error("probes: cannot fit a probe grid to non-finite scene bounds");
    const float largest = std::max(extent.x, std::max(extent.y, extent.z));
    if (!(largest > 0.0f)) {  // a point-like scene: one probe beside it
        g.first = bounds.center();
        return g;
    }
    const float cell = spacing * largest;
    double total = 1.0;
    for (int a = 0; a < 3; ++a) {
        // Cell centres: n cells of extent/n <= cell each; a flat axis gets one probe.
        const double n = std::max(1.0, std::ceil(double(extent[a]) / double(cell) - 1e-4));
        total *= n;
        if (total > double(kMaxProbes))
            throw Error("probe spacing " + std::to_string(spacing) + " would place more than " +
                        std::to_string(kMaxProbes) + " probes; raise the spacing");
        g.counts[a] = int(n);
        g.step[a] = extent[a] > 0.0f ? extent[a] / float(n) : cell;
        g.first[a] = bounds.min[a] + 0.5f * (extent[a] > 0.0f ? g.step[a] : 0.0f);
    }
    return g;
}

ProbeGrid fitProbeGrid(const Aabb& bounds, float spacing, const Aabb& air) {
    ProbeGrid g = fitProbeGrid(bounds, spacing);
    if (bounds.empty() || air.empty()) return g;
    for (int a = 0; a < 3; ++a) {
        if (air.min[a] < bounds.min[a]) {
            g.first[a] -= g.step[a];
            ++g.counts[a];
        }
        if (air.max[a] > bounds.max[a]) ++g.counts[a];
    }
    if (int64_t(g.counts.x) * g.counts.y * g.counts.z > kMaxProbes)
        throw Error("probe spacing " + std::to_string(spacing) + " would place more than " + std::to_string(kMaxProbes) +
                    " probes with the layers outside the scene; raise the spacing");
    return g;
}

glm::vec3 fibonacciDirection(int k, int n) {
    const float golden = 2.39996323f;  // pi (3 - sqrt 5)
    const float z = 1.0f - (2.0f * float(k) + 1.0f) / float(n);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = golden * float(k);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

std::array<float, 9> shBasis(const glm::vec3& d) {
    return {0.282095f,
            0.488603f * d.y,
            0.488603f * d.z,
            0.488603f * d.x,
            1.092548f * d.x * d.y,
            1.092548f * d.y * d.z,
            0.315392f * (3.0f * d.z * d.z - 1.0f),
            1.092548f * d.x * d.z,
            0.546274f * (d.x * d.x - d.y * d.y)};
}

int shBand(int c) { return c == 0 ? 0 : (c < 4 ? 1 : 2); }

std::vector<glm::vec3> projectSh(const std::vector<glm::vec3>& dirs, const std::vector<glm::vec3>& radiance,
                                 int coefficients) {
    std::vector<glm::vec3> c(size_t(coefficients), glm::vec3(0.0f));
    for (size_t i = 0; i < dirs.size(); ++i) {
        const auto y = shBasis(dirs[i]);
        for (int k = 0; k < coefficients; ++k) c[size_t(k)] += radiance[i] * y[size_t(k)];
    }
    const float w = 4.0f * kPi / float(std::max<size_t>(dirs.size(), 1));
    for (auto& v : c) v *= w;
    return c;
}

glm::vec3 shIrradianceOverPi(const std::vector<glm::vec3>& c, const glm::vec3& n) {
    const auto y = shBasis(n);
    glm::vec3 e(0.0f);
    for (size_t k = 0; k < c.size() && k < 9; ++k) e += kShCosine[shBand(int(k))] * c[k] * y[k];
    return glm::max(e, glm::vec3(0.0f)) / kPi;  // L1/L2 ring below zero behind strong lights
}

glm::vec2 octEncode(const glm::vec3& d) {
    const glm::vec3 a = d / (std::abs(d.x) + std::abs(d.y) + std::abs(d.z));
    glm::vec2 p(a.x, a.y);
    if (a.z < 0.0f)
        p = (1.0f - glm::abs(glm::vec2(p.y, p.x))) * glm::vec2(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    return p * 0.5f + 0.5f;
}

glm::vec3 octDecode(glm::vec2 uv) {
    const glm::vec2 p = uv * 2.0f - 1.0f;
    glm::vec3 d(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (d.z < 0.0f) {
        const glm::vec2 q = (1.0f - glm::abs(glm::vec2(d.y, d.x))) *
                            glm::vec2(d.x >= 0.0f ? 1.0f : -1.0f, d.y >= 0.0f ? 1.0f : -1.0f);
        d.x = q.x, d.y = q.y;
    }
    return glm::normalize(d);
}

std::vector<glm::vec3> projectOctahedral(const std::vector<glm::vec3>& dirs, const std::vector<glm::vec3>& radiance,
                                         int size) {
    std::vector<glm::vec3> map(size_t(size * size), glm::vec3(0.0f));
    for (int t = 0; t < size * size; ++t) {
        const glm::vec3 n = octDecode((glm::vec2(t % size, t / size) + 0.5f) / float(size));
        glm::vec3 sum(0.0f);
        float weights = 0.0f;
        for (size_t i = 0; i < dirs.size(); ++i) {
            const float w = std::max(0.0f, glm::dot(n, dirs[i]));
            sum += w * radiance[i];
            weights += w;
        }
        map[size_t(t)] = weights > 0.0f ? sum / weights : glm::vec3(0.0f);
    }
    return map;
}

namespace {
// A texel outside the map maps to its mirror across the nearest edge (how the octahedron folds).
glm::ivec2 octWrap(glm::ivec2 t, int n) {
    if (t.x < 0 || t.x >= n) t = {std::clamp(t.x, 0, n - 1), n - 1 - t.y};
    if (t.y < 0 || t.y >= n) t = {n - 1 - t.x, std::clamp(t.y, 0, n - 1)};
    return t;
}
}  // namespace

glm::vec3 octSample(const std::vector<glm::vec3>& map, int size, const glm::vec3& dir) {
    const glm::vec2 p = octEncode(dir) * float(size) - 0.5f;
    const glm::ivec2 base(int(std::floor(p.x)), int(std::floor(p.y)));
    const glm::vec2 f = p - glm::vec2(base);
    glm::vec3 result(0.0f);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const glm::ivec2 t = octWrap(base + glm::ivec2(i, j), size);
            const float w = (i ? f.x : 1.0f - f.x) * (j ? f.y : 1.0f - f.y);
            result += w * map[size_t(t.y * size + t.x)];
        }
    return result;
}

glm::vec3 probeIrradianceOverPi(Storage s, const std::vector<glm::vec3>& payload, const glm::vec3& n) {
    if (s == Storage::Octahedral) return octSample(payload, kOctIrradianceSize, n);
    return shIrradianceOverPi(payload, n);
}

}  // namespace gis::probes
