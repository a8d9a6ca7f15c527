// Where the scene volume's cascades lie (renderer/volume/): for a scene too large for one volume,
// nested cubes around the camera, each twice the edge of the one inside it, all with the same
// number of cells. CPU-only placement, so tests can check it without a GPU.
//
// How many: from the scene's extent against the finest cascade's largest edge: a scene cube within
// it gets one volume; each doubling beyond it one more cascade, up to kMaxCascades. The coarsest is
// always the scene's cube, so the finest is that cube halved count - 1 times. The finest edge is
// the method's `cascade-extent` when the user gives one (world units, like Godot's SDFGI cell size),
// else (0, the default) a multiple of how far the render camera sees (nearViewDepth): a camera
// among walls far smaller than the scene gets cascades, one looking at a room or a model from
// outside gets one volume, and the choice is the same at every unit of length. (Measures of the
// scene alone, its mean free path among them, were tried and could not tell a courtyard from two
// small rooms: renderer/gi/sdf/README.md.)
//
// Where: the coarsest cascade is the scene's fitted cube and never moves. Cascade i < last is
// centred on the camera, on the grid of its own cells (aligned with the scene cube, so a finer
// cascade's cells nest in the coarser ones) and kept inside the scene cube. It moves only when the
// camera is more than snapCells() of its cells from where it was placed, so small camera moves
// rebuild nothing and a coarser cascade (cells twice as large) moves half as often.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render_settings.h"
#include "scene/scene.h"
#include "volume/distance_field.h"
#include "volume/volume_fit.h"

namespace gis {

struct Bvh;

constexpr int kMaxCascades = 4;          // GLSL's SDF_MAX_CASCADES (renderer/shader_constants.cpp)
// A cascade moves when the camera is more than resolution / kCascadeSnapDivisor of its cells away.
constexpr int kCascadeSnapDivisor = 8;

// 1 when the scene cube's edge is within `finestExtent`, else 1 + the halvings that bring it
// there, at most kMaxCascades. `requested` > 0 overrides it (the method's `cascades`). Throws
// gis::Error naming the parameter of the requesting `method` ("sdf": "sdf.cascades") for a request
// outside [0, kMaxCascades] or an extent that is not positive.
int chooseCascadeCount(const VolumeFit& sceneCube, float finestExtent, int requested, const std::string& method);

struct CascadeLayout {
    VolumeFit scene;   // the scene's fitted cube: the coarsest cascade
    int count = 1;

    int resolution() const { return scene.resolution; }
    float extent(int i) const { return scene.size / float(1 << (count - 1 - i)); }
    float cellSize(int i) const { return extent(i) / float(scene.resolution); }
    int snapCells() const { return std::max(1, scene.resolution / kCascadeSnapDivisor); }
    // The offset (in cascade i's cells, from the scene cube's corner) that centres cascade i on
    // `camera`, kept inside the scene cube.
    glm::ivec3 centredOffset(int i, const glm::vec3& camera) const;
    // Whether a cascade at `current` must move to `centred` (more than snapCells() on some axis).
    bool mustMove(const glm::ivec3& current, const glm::ivec3& centred) const;
    SdfVolume volume(int i, const glm::ivec3& offset) const;
};

// How near the camera stands to what it sees: the distance within which the nearest
// 1/kNearViewFraction of its view lies, over a grid of kViewDepthRays^2 rays across it (a ray that
// leaves the scene counts as infinitely far, so +inf when nearly all of them leave). Not the median:
// a camera in a courtyard sees mostly the far walls, but stands among the near ones. It scales with
// the scene and its camera, so a count chosen from it is the same at every unit of length.
constexpr int kViewDepthRays = 16;
constexpr int kNearViewFraction = 10;
float nearViewDepth(const Bvh& bvh, const CameraMatrices& camera);
// The finest cascade's largest edge as a multiple of that depth, for `cascade-extent` 0 (the
// default): the finest cascade reaches past the near surfaces on every side of the camera. Chosen
// so that the rooms keep one volume and the courtyard and the building their cascades at 32^3 and
// 64^3 (tests/volume/test_cascades.cpp prints each scene's margin).
constexpr float kFinestExtentPerViewDepth = 2.4f;
// The finest cascade's extent, world units: `cascadeExtent` when the user gave one (> 0), else from
// the view depth (+inf, so one volume, when the view sees nothing).
float finestCascadeExtent(float cascadeExtent, float viewDepth);

// The layout for a scene: its cube (fitted with `marginVoxels` of empty cells, shared with the
// voxels), and the count from its extent (or `requested`; errors name `method`'s parameters).
CascadeLayout layoutCascades(const Aabb& bounds, int resolution, float finestExtent, int requested,
                             const std::string& method, float marginVoxels = kVolumeMarginVoxels);

}  // namespace gis
