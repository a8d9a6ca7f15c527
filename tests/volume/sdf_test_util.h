// Helpers of the distance-field tests: seed sets, the exact CPU Euclidean distance transform they
// are checked against, and seed textures on the GPU.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "volume/distance_field.h"

namespace gis::test {

// A cubic grid of n^3 cells, x fastest: 1 marks a seed (surface) cell.
struct SeedGrid {
    int n = 0;
    std::vector<uint8_t> seed;
    std::vector<glm::vec3> normal;   // per cell, only read for seeds (zero = none)
    size_t index(int x, int y, int z) const { return (size_t(z) * n + y) * n + x; }
};

// Random seed sets: `count` uniformly placed cells; clusters of `perCluster` cells scattered with a
// Gaussian of sigma cells around random centres. Fixed seeds, so the sets are the same every run.
SeedGrid uniformSeeds(int n, int count, uint32_t rng);
SeedGrid clusteredSeeds(int n, int clusters, int perCluster, float sigma, uint32_t rng);

// Exact Euclidean distance (in cells) from every cell centre to the nearest seed centre:
// Felzenszwalb & Huttenlocher's separable transform (lower envelope of parabolas per axis).
// Cells with no seed at all get +infinity.
std::vector<double> exactDistance(const SeedGrid& g);
// The same by brute force over every seed (for checking the transform on small grids).
std::vector<double> bruteForceDistance(const SeedGrid& g);

// The seeds as the module takes them: RGBA8 3D textures of occupancy (alpha) and normals.
struct SeedTextures {
    gl::Texture occupancy, normals;
    SdfSeeds seeds(bool withNormals) const { return {occupancy.id(), withNormals ? normals.id() : 0u}; }
};
SeedTextures uploadSeeds(const SeedGrid& g, const gl::MemoryScope& scope);

}  // namespace gis::test
