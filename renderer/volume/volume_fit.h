// A cubic volume fitted to the scene's bounds: what the scene volume's voxels and distance field
// (and probe grids) are placed in. Robust for empty, flat, single-triangle and very small or large scenes.
#pragma once

#include <cstdio>
#include <string>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "scene/scene.h"

namespace gis {

struct VolumeFit {
    glm::vec3 origin{0.0f};  // world position of the cube's minimum corner
    float size = 1.0f;       // world edge length of the cube
    int resolution = 1;      // voxels per edge
    float voxelSize() const { return size / float(resolution); }
    // Voxel coordinates run over [0, resolution]^3; voxel (i, j, k) covers [i, i+1) x ...
    glm::vec3 worldToVoxel(const glm::vec3& p) const { return (p - origin) / voxelSize(); }
    glm::vec3 voxelToWorld(const glm::vec3& v) const { return origin + v * voxelSize(); }
    glm::mat4 worldToVoxelMatrix() const;
    glm::mat4 voxelToWorldMatrix() const;
};

// Empty voxels around the scene's bounds: a whole number and a half, so the bounds (a room's walls)
// lie mid-voxel instead of on a voxel boundary, where float rounding at another scene scale would
// flip them between one and two voxel layers (and change the light by a few percent).
constexpr float kVolumeMarginVoxels = 2.5f;

// The cube around `bounds`, centred on them, its edge the longest extent plus `marginVoxels` empty
// voxels on each side (so surfaces on the bounds never sit in the outermost voxel, where trilinear
// lookups and mips would clamp them). Empty bounds give a unit cube at the origin; a flat or
// point-like scene gets a cube sized from its largest extent or, if all are zero, from its distance
// to the origin. Throws gis::Error for a resolution outside [1, 4096] or non-finite bounds.
VolumeFit fitVolume(const Aabb& bounds, int resolution, float marginVoxels = kVolumeMarginVoxels);

// "64^3 voxels of 3.4 cm (2.2 m cube)": a volume in world units, for stats().
inline std::string describeVolume(const VolumeFit& fit, const char* what) {
    char text[160];
    std::snprintf(text, sizeof text, "%d^3 %s of %.4g world units (a %.4g cube)", fit.resolution, what,
                  double(fit.voxelSize()), double(fit.size));
    return text;
}

}  // namespace gis
