// Probe GI's storage and math on the CPU: the probe grid fitted to the scene, spherical-Fibonacci
// ray directions, spherical harmonics (L1, L2) with the cosine-lobe convolution of Ramamoorthi &
// Hanrahan 2001, and octahedral maps. shaders/probes/probe_common.glsl is the GPU twin of every
// function here (same constants, same layouts); the tests check the math here and read the GPU's
// probes back through the same evaluation.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace gis::probes {

enum class Storage { Sh1, Sh2, Octahedral };  // probes.storage: sh1 | sh2 | octahedral

constexpr int kOctIrradianceSize = 6;   // texels per edge of a probe's irradiance map
constexpr int kOctDistanceSize = 14;    // texels per edge of a probe's distance-moment map
// What one probe holds on the GPU, by part. Irradiance: one RGBA32F vec4 per SH coefficient or per
// octahedral texel (the SSBO is sampled by hand, so the maps need no border texels); distance: two
// floats (mean, mean^2) per texel; state: two vec4 (relocation offset and state; update count).
int irradianceVec4s(Storage s);
int64_t irradianceBytesPerProbe(Storage s);
int64_t distanceBytesPerProbe();
constexpr int64_t kStateBytesPerProbe = 32;
int64_t bytesPerProbe(Storage s);
const char* storageName(Storage s);

// The grid: probes at cell centres of the scene's bounds cut into cells no wider than
// spacing * (largest extent), so no probe sits on the bounds (where walls usually are) and a
// spacing at or above the scene's size gives one probe. Spacing is relative so the same setting
// gives the same grid at any scene scale.
struct ProbeGrid {
    glm::vec3 first{0.0f};   // world position of probe (0, 0, 0)
    glm::vec3 step{1.0f};    // world distance between neighbours along each axis (>0 even with one probe)
    glm::ivec3 counts{1};
    int count() const { return counts.x * counts.y * counts.z; }
    glm::vec3 position(int index) const;
};
constexpr int kMaxProbes = 1 << 18;
// The index of the probe nearest to p (clamped to the grid).
int probeIndexNear(const ProbeGrid& g, const glm::vec3& p);
// Throws gis::Error with a clear message for a degenerate or oversized grid (non-finite bounds,
// spacing <= 0, more than kMaxProbes probes). Empty bounds give one probe at the origin.
ProbeGrid fitProbeGrid(const Aabb& bounds, float spacing);
// The same grid with one more layer of probes, half a cell outside, on each face of `bounds` that
// `air` reaches beyond (volume/volume_fit.h: sceneAirBounds): behind such a face the scene is solid,
// so the fitted grid's outermost probes are inside it and its surfaces are lit from outside. The
// fitted probes keep their places, and a room (no air) keeps its grid.
ProbeGrid fitProbeGrid(const Aabb& bounds, float spacing, const Aabb& air);

// Direction k of n spread evenly over the sphere (spherical Fibonacci: the golden-angle spiral
// of Vogel, equal-area in z).
glm::vec3 fibonacciDirection(int k, int n);

// Real SH basis, bands 0..2 (9 values; L1 uses the first 4), in the order
// Y00, Y1-1 (y), Y10 (z), Y11 (x), Y2-2 (xy), Y2-1 (yz), Y20, Y21 (xz), Y22 (x^2 - y^2).
std::array<float, 9> shBasis(const glm::vec3& d);
// The clamped-cosine kernel's band factors A_l: pi, 2pi/3, pi/4 (irradiance E = sum A_l L_lm Y_lm).
constexpr float kShCosine[3] = {3.14159265f, 2.09439510f, 0.78539816f};
int shBand(int coefficient);  // 0, 1 or 2

// Radiance samples over the sphere (uniform directions) projected onto SH: L_lm = 4pi/n sum L Y_lm.
std::vector<glm::vec3> projectSh(const std::vector<glm::vec3>& dirs, const std::vector<glm::vec3>& radiance, int coefficients);
// Irradiance E(n) / pi from SH radiance coefficients: the cosine-weighted mean incoming radiance,
// the lighting contract's indirect.diffuse.
glm::vec3 shIrradianceOverPi(const std::vector<glm::vec3>& coefficients, const glm::vec3& n);

// Octahedral mapping of the unit sphere onto [0, 1]^2 (and back).
glm::vec2 octEncode(const glm::vec3& d);
glm::vec3 octDecode(glm::vec2 uv);
// The cosine-weighted mean radiance (E / pi) each texel's direction receives, from the samples.
std::vector<glm::vec3> projectOctahedral(const std::vector<glm::vec3>& dirs, const std::vector<glm::vec3>& radiance, int size);
// Bilinear lookup with the octahedral edge wrap (the mirror rule at the map's border).
glm::vec3 octSample(const std::vector<glm::vec3>& map, int size, const glm::vec3& dir);

// E / pi in direction n from one probe's irradiance payload (irradianceVec4s(s) RGB entries).
glm::vec3 probeIrradianceOverPi(Storage s, const std::vector<glm::vec3>& payload, const glm::vec3& n);

}  // namespace gis::probes
