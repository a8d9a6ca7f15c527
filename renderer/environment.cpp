#include "environment.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>

#include <stb_image.h>

#include "scene/limits.h"
#include "error.h"
#include "scene/user_file.h"

namespace gis {

namespace {

constexpr float kPi = 3.14159265358979f;

// The largest side a header may declare: stb_image reads no more, and no GPU's textures are larger.
constexpr long long kMaxMapSide = 1 << 16;
// A whole file: stb_image takes its length as an int; a map of the largest side is far less.
constexpr uint64_t kMaxMapFileBytes = uint64_t(1) << 30;

// Why the pixel data after the header cannot be the whole image, following the scanline layout
// stb_image's reader takes (flat RGBE, or the new-style run-length encoding of Radiance's RGBE
// format); empty when it can. stb fills missing bytes with zeros and reports success on a truncated
// file, and a scanline without the run-length marker makes it decode the rest as flat pixels.
std::string pixelDataProblem(const std::string& bytes, size_t at, long long width, long long height) {
    const std::string truncated = "is truncated (" + std::to_string(width) + "x" + std::to_string(height) +
                                  " pixels declared, the file ends first)";
    auto byte = [&](size_t i) { return (unsigned char)bytes[i]; };
    auto need = [&](size_t n) { return at + n <= bytes.size(); };
    const bool rle = width >= 8 && width < 32768 && need(4) && byte(at) == 2 && byte(at + 1) == 2 && !(byte(at + 2) & 0x80);
    if (!rle) return bytes.size() - at >= size_t(width) * size_t(height) * 4 ? "" : truncated;
    for (long long row = 0; row < height; ++row) {
        if (!need(4)) return truncated;
        if (byte(at) != 2 || byte(at + 1) != 2 || (long long)(byte(at + 2) << 8 | byte(at + 3)) != width)
            return "is corrupt: scanline " + std::to_string(row) + " does not start with the run-length marker (2, 2, " +
                   std::to_string(width) + ") of the first";
        at += 4;
        for (int channel = 0; channel < 4; ++channel)
            for (long long x = 0; x < width;) {
                if (!need(1)) return truncated;
                int count = byte(at++);
                size_t payload = size_t(count);
                if (count > 128) count -= 128, payload = 1;
                if (count == 0 || x + count > width)
                    return "is corrupt: a run of scanline " + std::to_string(row) + " overflows its width";
                if (!need(payload)) return truncated;
                at += payload;
                x += count;
            }
    }
    return "";
}

// Every Radiance file starts "#?" (#?RADIANCE or #?RGBE).
bool hasRadianceSignature(const std::string& bytes) { return bytes.rfind("#?", 0) == 0; }

// "-?DIGITS" as a number; false when it is no whole number. A value past long long is kept as the
// largest, which any range check refuses.
bool wholeNumber(const std::string& text, long long& value) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec == std::errc::result_out_of_range) value = std::numeric_limits<long long>::max();
    return ptr == end && ptr != text.data() && ec != std::errc::invalid_argument;
}

struct Header {
    bool complete = false;  // the resolution line was read to its end
    std::string problem;    // empty: the sizes below are the image's
    size_t dataStart = 0;
    long long width = 0, height = 0;
};

// The header's end and the resolution line ("-Y H +X W", the only layout stb_image reads).
Header parseHeader(const std::string& bytes) {
    Header h;
    h.problem = "the header has no \"-Y HEIGHT +X WIDTH\" resolution line (truncated, or another layout)";
    size_t at = 0;
    for (bool blank = false; !blank;) {
        const size_t eol = bytes.find('\n', at);
        if (eol == std::string::npos) return h;
        blank = eol == at;
        at = eol + 1;
    }
    const size_t eol = bytes.find('\n', at);
    if (eol == std::string::npos) return h;
    h.complete = true;
    std::istringstream line(bytes.substr(at, eol - at));
    std::string y, hText, x, wText, rest;
    if (!(line >> y >> hText >> x >> wText) || (line >> rest) || y != "-Y" || x != "+X" ||
        !wholeNumber(hText, h.height) || !wholeNumber(wText, h.width))
        return h;
    if (h.width < 1 || h.height < 1 || h.width > kMaxMapSide || h.height > kMaxMapSide) {
        h.problem = "the resolution line's size " + wText + "x" + hText + " is out of range (each side in [1, " +
                    std::to_string(kMaxMapSide) + "])";
        return h;
    }
    h.problem.clear();
    h.dataStart = eol + 1;
    return h;
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
    // The whole header, however long, and no more: the pixels may be hundreds of megabytes.
    try {
        const std::string bytes = readUserFile(path, kMaxMapFileBytes, "environment map", [](const std::string& b) {
            return !hasRadianceSignature(b) || parseHeader(b).complete;
        });
        const Header h = parseHeader(bytes);
        if (!hasRadianceSignature(bytes) || !h.problem.empty()) return std::nullopt;
        return glm::ivec2(int(h.width), int(h.height));
    } catch (const Error&) {
        return std::nullopt;  // loadEnvironmentMap says why
    }
}

EnvironmentMap loadEnvironmentMap(const std::string& path) {
    return decodeEnvironmentMap(readUserFile(path, kMaxMapFileBytes, "environment map"), path);
}

EnvironmentMap decodeEnvironmentMap(const std::string& bytes, const std::string& path) {
    const std::string what = "environment map '" + path + "'";
    if (bytes.size() > kMaxMapFileBytes) throw Error(what + " is too large");
    if (!hasRadianceSignature(bytes))
        throw Error(what + " is not a Radiance .hdr file (no #?RADIANCE or #?RGBE header)");
    const Header header = parseHeader(bytes);
    if (!header.problem.empty()) throw Error(what + ": " + header.problem);
    const std::string problem = pixelDataProblem(bytes, header.dataStart, header.width, header.height);
    if (!problem.empty()) throw Error(what + " " + problem);
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h,
                               &channels, 3),
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
        const std::string texel = "texel " + std::to_string(i % size_t(w)) + "," + std::to_string(i / size_t(w));
        // Each channel alone: the sum of three finite texels near the float maximum is inf.
        if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b) || glm::any(glm::lessThan(c, glm::vec3(0.0f))))
            throw Error(what + ": " + texel + " is not a finite non-negative radiance");
        const float peak = std::max({c.r, c.g, c.b});
        if (peak > kMaxRadiance) {
            char text[160];
            std::snprintf(text, sizeof text, " has radiance %g, more than the %g the renderer takes", double(peak),
                          double(kMaxRadiance));
            throw Error(what + ": " + texel + text);
        }
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
    const float u = std::atan2(d.z, d.x) / (2.0f * kPi) + 0.5f;
    const float v = std::acos(std::clamp(d.y / std::max(glm::length(d), 1e-30f), -1.0f, 1.0f)) / kPi;
    return {u >= 1.0f ? 0.0f : u, std::min(v, std::nextafter(1.0f, 0.0f))};
}

namespace {
// The direction at column coordinate u and height cosTheta: equirectToDirection's, and the
// sampler's, which draws cos(theta) uniformly inside a texel.
glm::vec3 equirectDirection(float u, float cosTheta) {
    const float phi = (u - 0.5f) * 2.0f * kPi, s = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    return {s * std::cos(phi), cosTheta, s * std::sin(phi)};
}
}  // namespace

glm::vec3 equirectToDirection(glm::vec2 uv) { return equirectDirection(uv.x, std::cos(uv.y * kPi)); }

glm::vec3 environmentToMap(glm::vec3 d, float rotationDegrees) {
    const float a = rotationDegrees * (kPi / 180.0f), c = std::cos(a), s = std::sin(a);
    return {c * d.x - s * d.z, d.y, s * d.x + c * d.z};
}

float texelSolidAngle(const EnvironmentMap& map, int y) { return wedgeSolidAngle(y, map.width, map.height); }

EnvironmentMap nextMipLevel(const EnvironmentMap& level) {
    EnvironmentMap next;
    next.name = level.name;
    next.width = std::max(1, level.width / 2);
    next.height = std::max(1, level.height / 2);
    next.texels.resize(size_t(next.width) * size_t(next.height));
    std::vector<double> rowSteradians(size_t(level.height));
    for (int y = 0; y < level.height; ++y) rowSteradians[size_t(y)] = texelSolidAngle(level, y);
    // Texel (x, y) covers the finer columns [x W / w, (x + 1) W / w) and rows likewise: every finer
    // texel once, an odd size's last one in the last coarse texel.
    for (int y = 0; y < next.height; ++y) {
        const int y0 = y * level.height / next.height, y1 = (y + 1) * level.height / next.height;
        for (int x = 0; x < next.width; ++x) {
            const int x0 = x * level.width / next.width, x1 = (x + 1) * level.width / next.width;
            glm::dvec3 sum(0.0);
            double weight = 0.0;
            for (int fy = y0; fy < y1; ++fy) {
                const double sr = rowSteradians[size_t(fy)];
                for (int fx = x0; fx < x1; ++fx) sum += sr * glm::dvec3(level.at(fx, fy));
                weight += sr * double(x1 - x0);
            }
            next.texels[size_t(y) * size_t(next.width) + size_t(x)] = glm::vec3(weight > 0.0 ? sum / weight : glm::dvec3(0.0));
        }
    }
    return next;
}

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
    // nx x ny sub-texels with their exact solid angles, each axis subdivided on its own until the
    // sphere gets at least 256 sample columns and 128 rows (a 1x1 constant map needs them; a large
    // map gets one sample a texel). One n for both axes, taken from the width, gave a 1 x 65536 map
    // 256 x 16.7M samples. Now the samples are at most max(W, 256) x max(H, 128). Double sums: a 4K
    // map has 8M terms.
    const int nx = std::clamp(256 / std::max(map.width, 1), 1, 256), ny = std::clamp(128 / std::max(map.height, 1), 1, 128);
    const int subW = map.width * nx, subH = map.height * ny;
    std::array<glm::dvec3, 9> sum{};
    for (int y = 0; y < subH; ++y) {
        const double dw = wedgeSolidAngle(y, subW, subH);
        for (int x = 0; x < subW; ++x) {
            const glm::vec3 d = equirectToDirection({(float(x) + 0.5f) / float(subW), (float(y) + 0.5f) / float(subH)});
            const std::array<float, 9> b = shBasis(d);
            const glm::dvec3 l = glm::dvec3(map.at(x / nx, y / ny)) * dw;
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
    const float c0 = std::cos(kPi * float(y) / float(height_)), c1 = std::cos(kPi * float(y + 1) / float(height_));
    const glm::vec3 d = equirectDirection((float(x) + fx) / float(width_), c0 + (c1 - c0) * fy);
    return {d, texelWeight_[size_t(y) * size_t(width_) + size_t(x)] / total_ / wedgeSolidAngle(y, width_, height_)};
}

float EnvironmentSampler::pdf(glm::vec3 direction) const {
    const glm::vec2 uv = directionToEquirect(direction);
    const int x = std::min(int(uv.x * float(width_)), width_ - 1), y = std::min(int(uv.y * float(height_)), height_ - 1);
    return texelWeight_[size_t(y) * size_t(width_) + size_t(x)] / total_ / wedgeSolidAngle(y, width_, height_);
}

}  // namespace gis
