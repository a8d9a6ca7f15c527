// Environment maps: equirectangular Radiance .hdr images of the light arriving from infinitely far
// away, what `--background R,G,B` is the constant case of. The CPU half: loading (stb_image's
// stbi_loadf, as the Khronos sample viewer and Cycles take them), the direction <-> texel mapping
// every consumer shares, the 9-coefficient spherical-harmonic projection of the map (the diffuse
// irradiance of Ramamoorthi and Hanrahan 2001, "An Efficient Representation for Irradiance
// Environment Maps"), and the luminance distribution a path tracer importance-samples it with.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gis {

struct EnvironmentMap {
    std::string name;               // the file, or "constant R,G,B"
    int width = 0, height = 0;      // equirectangular: width spans azimuth, height polar angle
    std::vector<glm::vec3> texels;  // linear radiance, rows from +Y (top) to -Y
    const glm::vec3& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

// Throws gis::Error with one line for a missing, unreadable, non-regular, oversized, truncated,
// corrupt or non-Radiance file, or radiance that is negative, NaN, Inf or more than kMaxRadiance
// (scene/limits.h).
EnvironmentMap loadEnvironmentMap(const std::string& path);
// The same for a file's bytes already in memory (the fuzzer's entry); `name` names it in messages.
EnvironmentMap decodeEnvironmentMap(const std::string& bytes, const std::string& name);
// The same radiance from every direction: --background and the default sky as a map.
EnvironmentMap constantEnvironment(glm::vec3 radiance);
// A map's width and height from its header alone (the memory budget's estimate, before the map is
// decoded); nothing for a file loadEnvironmentMap would refuse, which then says why.
std::optional<glm::ivec2> environmentMapSize(const std::string& path);

// Blender's mapping (its Environment Texture node with the default mapping), in glTF axes, so a
// map lights a scene here as it does a Cycles render of the same file: +Y up, the top row the
// zenith, u = 0.5 + atan2(z, x) / 2pi (the centre column looks down +X, u = 0.25 down -Z),
// v = acos(y) / pi. Directions in the map's own frame: environmentToMap turns a world one into it.
// shaders/environment.glsl declares the same mapping for the GPU.
glm::vec2 directionToEquirect(glm::vec3 direction);  // [0, 1)^2
glm::vec3 equirectToDirection(glm::vec2 uv);         // its inverse (unit length)
// The map turned by `rotationDegrees` about +Y, right-handed (90 turns its centre column from +X
// to -Z): the direction in the map's frame that world direction `d` reads (--environment-rotation).
glm::vec3 environmentToMap(glm::vec3 d, float rotationDegrees);
float texelSolidAngle(const EnvironmentMap& map, int y);  // steradians of any texel in row y
glm::vec3 sampleNearest(const EnvironmentMap& map, glm::vec3 direction);  // in the map's frame
// The map's next mip level (half each way, at least one texel): each texel the mean of the texels it
// covers weighted by their solid angle, so every level keeps the map's mean radiance over the sphere.
// A box filter (glGenerateMipmap) weighs a row near a pole as much as one at the horizon: a sun
// high in the sky lost much of its light at the levels a wide cone or a sparse probe ray reads.
EnvironmentMap nextMipLevel(const EnvironmentMap& level);

// Radiance projected onto the real spherical harmonics up to band 2 (Y00, Y1-1, Y10, Y11, Y2-2,
// Y2-1, Y20, Y21, Y22), integrated over every texel's solid angle; in the map's frame, as are the
// sampler's directions (a rotated map's readers turn their directions into it).
using Sh9 = std::array<glm::vec3, 9>;
Sh9 projectSh9(const EnvironmentMap& map);
std::array<float, 9> shBasis(glm::vec3 direction);
// Irradiance E(n) = integral of L(w) max(0, n.w) dw from the projection, the cosine lobe's band
// weights pi, 2pi/3, pi/4 applied (Ramamoorthi and Hanrahan 2001, eq. 8).
glm::vec3 shIrradiance(const Sh9& sh, glm::vec3 normal);

// Piecewise-constant distribution over the texels proportional to luminance x solid angle: a
// marginal CDF over rows and a conditional CDF per row (Pharr, Jakob and Humphreys, PBRT 3rd ed.,
// 13.6.7 and 14.2.4). sample() maps two uniform numbers to a direction and its solid-angle pdf.
class EnvironmentSampler {
public:
    explicit EnvironmentSampler(const EnvironmentMap& map);
    struct Sample {
        glm::vec3 direction;
        float pdf;  // per steradian
    };
    Sample sample(glm::vec2 u) const;
    float pdf(glm::vec3 direction) const;
    const std::vector<float>& marginalCdf() const { return marginal_; }      // height + 1 entries
    const std::vector<float>& conditionalCdf() const { return conditional_; }  // height x (width + 1)

private:
    int width_, height_;
    std::vector<float> marginal_, conditional_, rowWeight_, texelWeight_;
    float total_ = 0.0f;
};

}  // namespace gis
