// A cubic volume fitted to the scene's bounds: what the scene volume's voxels and distance field
// (and probe grids) are placed in. Robust for empty, flat, single-triangle and very small or large scenes.
#pragma once

#include <array>
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
    Aabb bounds;             // what it was fitted to (the scene's bounds with their air, sceneAirBounds)
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

// The faces of a box in the order -x, +x, -y, +y, -z, +z: face f is axis f / 2, side f % 2 (0 min).
using BoxFaces = std::array<bool, 6>;

// The faces of the scene's bounds behind which it is solid: seen from outside along the face's
// inward normal, the first surface a ray meets lies on the face (within kOutwardFaceDepth of the
// largest extent), faces the ray (or is double-sided) and has no surface behind it for
// kOutwardSkinDepth, over at least 1 / kOutwardFaceShare of the face. Behind such a face the
// outermost probes of a grid fitted to the bounds sit inside the object, and its surfaces are lit
// from outside, where there is nothing. A box's side is such a face. A room's walls face in; an
// opening (Cornell's open front) has nothing on its face; a building's outer wall is a skin with
// its rooms' air (and their probes) behind it; the rim of a ground slab is a sliver of its face.
constexpr float kOutwardFaceDepth = 1.0f / 32.0f;  // a voxel of the coarsest volume a method uses
// Half the probe cell of a spacing of 1/8, finer than every preset's: behind a thinner skin the
// outermost probes of every preset lie in the air it encloses.
constexpr float kOutwardSkinDepth = 1.0f / 16.0f;
constexpr int kOutwardFaceShare = 4;
BoxFaces outwardFaces(const Scene& scene);

// Air given to such a face, as a fraction of the scene's largest extent: light reaches the
// surfaces behind that face from outside the bounds, so the volumes and probe grids must hold what
// lies there. A quarter holds a probe layer half a cell outside the face for any probe spacing up
// to half the extent (every preset's), with room for its rays to start inside the volume.
constexpr float kAirFraction = 0.25f;

// The scene's bounds grown by kAirFraction of their largest extent on each outwardFaces face: what
// the scene volumes are fitted to. A room's or a building's bounds come back unchanged.
Aabb sceneAirBounds(const Scene& scene);

// "64^3 voxels of 3.4 cm (2.2 m cube)": a volume in world units, for stats().
inline std::string describeVolume(const VolumeFit& fit, const char* what) {
    char text[160];
    std::snprintf(text, sizeof text, "%d^3 %s of %.4g world units (a %.4g cube)", fit.resolution, what,
                  double(fit.voxelSize()), double(fit.size));
    return text;
}

}  // namespace gis
