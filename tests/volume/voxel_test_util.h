// Helpers of the voxel tests: scenes of loose triangles, the voxel grid read back, and the exact
// triangle-box overlap test the GPU voxelizer is checked against.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "scene/scene.h"
#include "volume/voxelizer.h"

namespace gis::test {

struct Triangle {
    glm::vec3 a, b, c;
};

// A finalized scene holding `triangles` (one primitive, one Lambert material of `albedo` that emits
// radiance `emissive`).
Scene triangleScene(const std::vector<Triangle>& triangles, glm::vec3 albedo = glm::vec3(0.5f),
                    glm::vec3 emissive = glm::vec3(0.0f));

// Level 0 of an RGBA8 3D texture, x fastest.
std::vector<uint8_t> readVoxelsRgba8(const gl::Texture& texture);
std::vector<float> readVoxelsRgba16f(const gl::Texture& texture, int level = 0);

// Separating-axis test of a triangle against the box centre +- half (Akenine-Moller 2001): the
// three box axes, the triangle's normal and the nine edge x axis cross products.
bool triangleBoxOverlap(const Triangle& t, glm::dvec3 center, double half);

// Voxels of a resolution^3 grid with unit voxels at the origin that triangles overlap (exact test,
// box half size `half`; slightly under 0.5 leaves out voxels the triangle only grazes).
std::vector<uint8_t> exactVoxels(const std::vector<Triangle>& triangles, int resolution, double half);

}  // namespace gis::test
