#include "environment.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <stb_image.h>

#include "scene/scene.h"  // gis::Error

namespace gis {

namespace {

constexpr float kPi = 3.14159265358979f;

// Whether the pixel data after the header holds the whole image, following the scanline
// layout stb_image's reader takes (flat RGBE, or the new-style run-length encoding of Radiance's
// RGBE format): stb fills missing bytes with zeros and can report success on a truncated file.
bool pixelDataComplete(const std::vector<unsigned char>& bytes, size_t at, long width, long height) {
    auto need = [&](size_t n) { return at + n <= bytes.size(); };
    const bool rle = width >= 8 && width < 32768 && need(4) && bytes[at] == 2 && bytes[at + 1] == 2 &&
                     !(bytes[at + 2] & 0x80);
    if (!rle) return bytes.size() - at >= size_t(width) * size_t(height) * 4;
    for (long row = 0; row < height; ++row) {
        if (!need(4)) return false;
        at += 4;  // 2, 2, width high, width low
        for (int channel = 0; channel < 4; ++channel)
            for (long x = 0; x < width;) {
                if (!need(1)) return false;
                int count = bytes[at++];
                size_t payload = size_t(count);
                if (count > 128) count -= 128, payload = 1;
                if (count == 0 || !need(payload)) return false;
                at += payload;
                x += count;
            }
    }
    return true;
}

// Every Radiance file starts "#?" (#?RADIANCE or #?RGBE).
bool hasRadianceSignature(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 2 && bytes[0] == '#' && bytes[1] == '?';
}

// The header's end and the resolution line ("-Y H +X W", the only layout stb_image reads).
bool parseHeader(const std::vector<unsigned char>& bytes, size_t& dataStart, long& width, long& height) {
    size_t at = 0;
    bool blank = false;
    while (!blank) {
        const size_t eol = size_t(std::find(bytes.begin() + long(at), bytes.end(), '\n') - bytes.begin());
        if (eol >= bytes.size()) return false;
        blank = eol == at;
        at = eol + 1;
    }
    const size_t eol = size_t(std::find(bytes.begin() + long(at), bytes.end(), '\n') - bytes.begin());
    if (eol >= bytes.size()) return false;
    const std::string line(bytes.begin() + long(at), bytes.begin() + long(eol));
    char y[3] = {}, x[3] = {};
    if (std::sscanf(line.c_str(), "%2s %ld %2s %ld", y, &height, x, &width) != 4) return false;
    dataStart = eol + 1;
    return std::string(y) == "-Y" && std::string(x) == "+X" && width > 0 && height > 0 && width <= (1 << 16) &&
           height <= (1 << 16);
}

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Row y of a width x height map is the band between two polar angles split into `width` equal
// wedges: the exact solid angle of each of its texels (the rows sum to 4 pi).
float wedgeSolidAngle(int y, int width, int height) {
    const float c0 = std::cos(kPi * float(y) / float(height)), c1 = std::cos(kPi * float(y + 1) / float(height));
    return 2.0f * kPi / float(width) * (c0 - c1);
}

}  // namespace

std::optional<glm::ivec2> environmentMapSize(const std::string& path) {
    // A header is a few lines; its resolution line ends it.
    constexpr size_t kHeaderBytes = 64 * 1024;
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes(kHeaderBytes);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    bytes.resize(size_t(in.gcount()));
    size_t dataStart = 0;
    long width = 0, height = 0;
    if (!hasRadianceSignature(bytes) || !parseHeader(bytes, dataStart, width, height))
        return std::nullopt;
    return glm::ivec2(int(width), int(height));
}

EnvironmentMap loadEnvironmentMap(const std::string& path) {
    const std::string what = "environment map '" + path + "'";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(what + " does not exist");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(what + " is not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(what + ": cannot read (" + std::strerror(errno) + ")");
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!hasRadianceSignature(bytes))
        throw Error(what + " is not a Radiance .hdr file (no #?RADIANCE or #?RGBE header)");
    size_t dataStart = 0;
    long headerW = 0, headerH = 0;
    if (!parseHeader(bytes, dataStart, headerW, headerH))
        throw Error(what + ": the header has no \"-Y HEIGHT +X WIDTH\" resolution line (truncated, or another layout)");
    if (!pixelDataComplete(bytes, dataStart, headerW, headerH))
        throw Error(what + " is truncated (" + std::to_string(headerW) + "x" + std::to_string(headerH) +
                    " pixels declared, the file ends first)");
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(bytes.data(), int(std::min<size_t>(bytes.size(), 1u << 30)), &w, &h, &channels, 3),
        &stbi_image_free);
    if (!pixels) throw Error(what + ": cannot decode (" + std::string(stbi_failure_reason()) + ")");
    if (w < 1 || h < 1) throw Error(what + " is empty");
    EnvironmentMap map;
    map.name = path;
    map.width = w;
    map.height = h;
    map.texels.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < map.texels.size(); ++i) {
        const glm::vec3 c(pixels.get()[i * 3], pixels.get()[i * 3 + 1], pixels.get()[i * 3 + 2]);
        if (!std::isfinite(c.r + c.g + c.b) || glm::any(glm::lessThan(c, glm::vec3(0.0f))))
            throw Error(what + ": texel " + std::to_string(i % size_t(w)) + "," + std::to_string(i / size_t(w)) +
                        " is not a finite non-negative radiance");
        map.texels[i] = c;
    }
    return map;
}

EnvironmentMap constantEnvironment(glm::vec3 radiance) {
    EnvironmentMap map;
    char name[96];
    std::snprintf(name, sizeof name, "constant %g,%g,%g", radiance.r, radiance.g, radiance.b);
    map.name = name;
    map.width = map.height = 1;
    map.texels.assign(1, radiance);
    return map;
}

glm::vec2 directionToEquirect(glm::vec3 d) {
    const float phi = std::atan2(d.x, -d.z);
    const float u = phi / (2.0f * kPi) + 0.5f;
    const float v = std::acos(std::clamp(d.y / std::max(glm::length(d), 1e-30f), -1.0f, 1.0f)) / kPi;
    return {u >= 1.0f ? 0.0f : u, std::min(v, std::nextafter(1.0f, 0.0f))};
}

glm::vec3 equirectToDirection(glm::vec2 uv) {
    const float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
    const float s = std::sin(theta);
    return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

float texelSolidAngle(const EnvironmentMap& map, int y) { return wedgeSolidAngle(y, map.width, map.height); }

glm::vec3 sampleNearest(const EnvironmentMap& map, glm::vec3 direction) {
    const glm::vec2 uv = directionToEquirect(direction);
    return map.at(std::min(int(uv.x * float(map.width)), map.width - 1), std::min(int(uv.y * float(map.height)), map.height - 1));
}

std::array<float, 9> shBasis(glm::vec3 d) {
    const float x = d.x, y = d.y, z = d.z;
    return {0.282095f,
            0.488603f * y,
            0.488603f * z,
            0.488603f * x,
            1.092548f * x * y,
            1.092548f * y * z,
            0.315392f * (3.0f * z * z - 1.0f),
            1.092548f * x * z,
            0.546274f * (x * x - y * y)};
}

Sh9 projectSh9(const EnvironmentMap& map) {
    // Each texel's radiance over its solid angle against the basis integrated over the texel:
    // n x n sub-texels with their exact solid angles, n chosen so the sphere gets at least 256
    // sample columns (a 1x1 constant map needs it; a large map gets n = 1). Double sums: a 4K map
    // has 8M terms.
    const int n = std::clamp(256 / std::max(map.width, 1), 1, 256);
    const int subW = map.width * n, subH = map.height * n;
    std::array<glm::dvec3, 9> sum{};
    for (int y = 0; y < subH; ++y) {
        const double dw = wedgeSolidAngle(y, subW, subH);
        for (int x = 0; x < subW; ++x) {
            const glm::vec3 d = equirectToDirection({(float(x) + 0.5f) / float(subW), (float(y) + 0.5f) / float(subH)});
            const std::array<float, 9> b = shBasis(d);
            const glm::dvec3 l = glm::dvec3(map.at(x / n, y / n)) * dw;
            for (int k = 0; k < 9; ++k) sum[size_t(k)] += l * double(b[size_t(k)]);
        }
    }
    Sh9 sh;
    for (int k = 0; k < 9; ++k) sh[size_t(k)] = glm::vec3(sum[size_t(k)]);
    return sh;
}

glm::vec3 shIrradiance(const Sh9& sh, glm::vec3 n) {
    const std::array<float, 9> b = shBasis(glm::normalize(n));
    const float band[9] = {kPi, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f,
                           kPi / 4.0f, kPi / 4.0f, kPi / 4.0f, kPi / 4.0f, kPi / 4.0f};
    glm::vec3 e(0.0f);
    for (int k = 0; k < 9; ++k) e += band[k] * b[size_t(k)] * sh[size_t(k)];
    return glm::max(e, glm::vec3(0.0f));
}

EnvironmentSampler::EnvironmentSampler(const EnvironmentMap& map) : width_(map.width), height_(map.height) {
    texelWeight_.resize(size_t(width_) * size_t(height_));
    rowWeight_.assign(size_t(height_), 0.0f);
    conditional_.assign(size_t(height_) * size_t(width_ + 1), 0.0f);
    marginal_.assign(size_t(height_ + 1), 0.0f);
    // A black map would have no distribution: sample by solid angle (uniform on the sphere) instead.
    double all = 0.0;
    for (const glm::vec3& t : map.texels) all += luminance(t);
    for (int y = 0; y < height_; ++y) {
        const float dw = texelSolidAngle(map, y);
        float* cdf = &conditional_[size_t(y) * size_t(width_ + 1)];
        for (int x = 0; x < width_; ++x) {
            const float w = (all > 0.0 ? luminance(map.at(x, y)) : 1.0f) * dw;
            texelWeight_[size_t(y) * size_t(width_) + size_t(x)] = w;
            cdf[x + 1] = cdf[x] + w;
        }
        rowWeight_[size_t(y)] = cdf[width_];
        marginal_[size_t(y + 1)] = marginal_[size_t(y)] + rowWeight_[size_t(y)];
    }
    total_ = marginal_[size_t(height_)];
}

namespace {
// The first index i with cdf[i + 1] > target (cdf ascending from 0), skipping empty cells.
int findInterval(const float* cdf, int n, float target) {
    const float* it = std::upper_bound(cdf + 1, cdf + n + 1, target);
    return std::clamp(int(it - cdf) - 1, 0, n - 1);
}
}  // namespace

EnvironmentSampler::Sample EnvironmentSampler::sample(glm::vec2 u) const {
    const int y = findInterval(marginal_.data(), height_, u.y * total_);
    const float* cdf = &conditional_[size_t(y) * size_t(width_ + 1)];
    const float rowTarget = u.y * total_ - marginal_[size_t(y)];  // reuse the leftover of u.y
    const float row = rowWeight_[size_t(y)];
    const int x = findInterval(cdf, width_, u.x * row);
    // Uniform in solid angle inside the texel (azimuth uniform, cos(theta) uniform), so the pdf is
    // the texel's probability over its solid angle everywhere in it.
    // The fractions stay clear of the texel's edges, where float rounding of the CDF would put
    // the direction in the neighbour whose pdf is another.
    constexpr float kEdge = 1e-4f;
    const float fx = std::clamp(row > 0.0f ? (u.x * row - cdf[x]) / std::max(cdf[x + 1] - cdf[x], 1e-30f) : 0.5f,
                                kEdge, 1.0f - kEdge);
    const float fy = std::clamp(row > 0.0f ? rowTarget / row : 0.5f, kEdge, 1.0f - kEdge);
    const float phi = ((float(x) + fx) / float(width_) - 0.5f) * 2.0f * kPi;
    const float c0 = std::cos(kPi * float(y) / float(height_)), c1 = std::cos(kPi * float(y + 1) / float(height_));
    const float cosTheta = c0 + (c1 - c0) * fy, sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const glm::vec3 d(sinTheta * std::sin(phi), cosTheta, -sinTheta * std::cos(phi));
    return {d, texelWeight_[size_t(y) * size_t(width_) + size_t(x)] / total_ / wedgeSolidAngle(y, width_, height_)};
}

float EnvironmentSampler::pdf(glm::vec3 direction) const {
    const glm::vec2 uv = directionToEquirect(direction);
    const int x = std::min(int(uv.x * float(width_)), width_ - 1), y = std::min(int(uv.y * float(height_)), height_ - 1);
    return texelWeight_[size_t(y) * size_t(width_) + size_t(x)] / total_ / wedgeSolidAngle(y, width_, height_);
}

}  // namespace gis
