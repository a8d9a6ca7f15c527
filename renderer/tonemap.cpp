#include "tonemap.h"

#include <algorithm>
#include <cmath>

namespace gis {

namespace {
float saturate(float x) { return std::min(std::max(x, 0.0f), 1.0f); }
float finiteOrZero(float x) { return std::isfinite(x) ? x : 0.0f; }
}  // namespace

float linearToSrgb(float c) {
    c = saturate(c);
    return c < 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float c) {
    c = saturate(c);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec3 acesFitted(glm::vec3 c) {
    // The shader's matrices, written as GLSL writes them (column by column).
    const glm::mat3 inputMat(0.59719f, 0.07600f, 0.02840f,
                             0.35458f, 0.90834f, 0.13383f,
                             0.04823f, 0.01566f, 0.83777f);
    const glm::mat3 outputMat(1.60475f, -0.10208f, -0.00327f,
                              -0.53108f, 1.10813f, -0.07276f,
                              -0.07367f, -0.00605f, 1.07602f);
    c = inputMat * c;
    const glm::vec3 a = c * (c + 0.0245786f) - 0.000090537f;
    const glm::vec3 b = c * (0.983729f * c + 0.4329510f) + 0.238081f;
    const glm::vec3 r = outputMat * (a / b);
    return {saturate(r.x), saturate(r.y), saturate(r.z)};
}

glm::vec3 toneMap(glm::vec3 radiance, const DisplaySettings& display) {
    const float scale = std::exp2(display.exposureEV);
    glm::vec3 c(finiteOrZero(radiance.x), finiteOrZero(radiance.y), finiteOrZero(radiance.z));
    c *= scale;
    if (display.tonemap == Tonemapper::Aces) return acesFitted(glm::max(c, glm::vec3(0.0f)));
    return {saturate(c.x), saturate(c.y), saturate(c.z)};
}

ImageF toneMapImage(const ImageF& radiance, const DisplaySettings& display) {
    ImageF out = radiance;
    for (size_t i = 0; i + 3 < out.rgba.size(); i += 4) {
        const glm::vec3 c = toneMap({out.rgba[i], out.rgba[i + 1], out.rgba[i + 2]}, display);
        out.rgba[i] = c.x;
        out.rgba[i + 1] = c.y;
        out.rgba[i + 2] = c.z;
    }
    return out;
}

ImageF encodeSrgbImage(const ImageF& displayLinear) {
    ImageF out = displayLinear;
    for (size_t i = 0; i + 3 < out.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) out.rgba[i + c] = linearToSrgb(out.rgba[i + c]);
    return out;
}

ImageU8 toLdrImage(const ImageF& radiance, const DisplaySettings& display) {
    ImageU8 out;
    out.width = radiance.width;
    out.height = radiance.height;
    out.rgba.resize(radiance.rgba.size());
    for (size_t i = 0; i + 3 < radiance.rgba.size(); i += 4) {
        const glm::vec3 c = toneMap({radiance.rgba[i], radiance.rgba[i + 1], radiance.rgba[i + 2]}, display);
        // An RGBA8 render target stores round(v * 255).
        for (int k = 0; k < 3; ++k) out.rgba[i + k] = uint8_t(std::lround(linearToSrgb(c[k]) * 255.0f));
        out.rgba[i + 3] = 255;
    }
    return out;
}

ImageF decodeSrgbImage(const ImageU8& srgb) {
    float table[256];
    for (int v = 0; v < 256; ++v) table[v] = srgbToLinear(float(v) / 255.0f);
    ImageF out;
    out.width = srgb.width;
    out.height = srgb.height;
    out.rgba.resize(srgb.rgba.size());
    for (size_t i = 0; i + 3 < srgb.rgba.size(); i += 4) {
        for (int c = 0; c < 3; ++c) out.rgba[i + c] = table[srgb.rgba[i + c]];
        out.rgba[i + 3] = float(srgb.rgba[i + 3]) / 255.0f;
    }
    return out;
}

}  // namespace gis
