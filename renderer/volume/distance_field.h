// A signed distance field built on the GPU by 3D jump flooding (shaders/volume/), from a 3D texture
// that marks surface cells. Shared by the SDF GI method (renderer/gi/sdf/) and probe GI, which
// sphere-trace it with shaders/volume/sdf_march.glsl.
//
// Steps: seed (every surface cell is its own nearest seed), jfa (passes with jumps N/2 ... 1 over
// the 26 neighbours plus the cell itself, ping-ponging two R32UI images; the variants add a
// step-1 pass before, or steps 2 and 1 after, because plain JFA can lose the nearest seed),
// resolve (distance to the nearest seed's centre in world units, signed by the orientation of that
// seed's averaged normal - see shaders/volume/sdf_resolve.comp - into an R32F texture with linear
// filtering) and a coarse level (a lower bound per 4^3 block) for far marching.
//
// Takes seeds, not the voxelizer, so it can be tested and reused on any seed set. The field is
// view-independent: build() again only when the geometry changes.
//
// Layers: one field can hold several volumes of the same resolution (the cascades of
// volume/volume_cascades.h), stacked along z in one texture - layer k's cells are z in
// [k*n, (k+1)*n) - so a marcher switches cascade by changing a coordinate, not a sampler (indexing
// an array of samplers per ray is not allowed in GLSL). Each layer is built on its own.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/shader.h"

namespace gis {

class StepTimers;

enum class JfaVariant { Plain, OnePlusJfa, JfaPlusTwo };
JfaVariant parseJfaVariant(const std::string& s);  // plain, 1+jfa, jfa+2; throws gis::Error
const char* jfaVariantName(JfaVariant v);
// The jumps of each flood pass, in order (N rounded up to a power of two; plain: N/2 ... 1).
std::vector<int> jfaSteps(int resolution, JfaVariant v);

// Where the field lies: a cube of resolution^3 cells from `origin` with edge `size` (world units).
struct SdfVolume {
    glm::vec3 origin{0.0f};
    float size = 1.0f;
    int resolution = 1;
    float cellSize() const { return size / float(resolution); }
    // The value of every cell when there is no seed at all: the cube's diagonal, so a marcher
    // leaves the volume in one step and reports a miss.
    float farValue() const { return size * 1.7320508f; }
};

// The seed input: 3D textures of the field's resolution. `occupancy`: a cell is a surface cell
// when its alpha is above 0.5 (the voxelizer's albedo texture). `normals` (optional, RGBA8, mean
// normal * 0.5 + 0.5, as the voxelizer stores it): gives the field its sign; 0 = unsigned.
struct SdfSeeds {
    GLuint occupancy = 0;
    GLuint normals = 0;
};

constexpr int kSdfCoarseFactor = 4;       // fine cells per coarse texel along an edge
constexpr int kSdfMaxResolution = 1024;   // the seed packing has 10 bits per axis

// GPU bytes the field holds (distance + coarse), and the peak while building (plus the two
// transient nearest-seed images).
int64_t distanceFieldBytes(int resolution, int layers = 1);
int64_t distanceFieldBuildBytes(int resolution, int layers = 1);

class DistanceField {
public:
    // Allocates the distance and coarse textures for `layers` volumes (charged to scope.owner), each
    // at `volume` until setVolume(). Throws gis::Error for a resolution outside
    // [1, kSdfMaxResolution] or layers outside [1, 64].
    DistanceField(const SdfVolume& volume, const gl::MemoryScope& scope, int layers = 1);
    // Where layer `layer` lies from now on (same resolution; build() it again).
    void setVolume(int layer, const SdfVolume& volume);
    // Seed, flood, resolve, coarse into `layer`. Timed when timers are given, as steps
    // prefix + "seed", prefix + "jfa.K.STEP" (pass K, 1-based, of jump STEP) and prefix + "resolve".
    // The nearest-seed images exist only during the call.
    void build(const SdfSeeds& seeds, JfaVariant variant, StepTimers* timers = nullptr, int layer = 0,
               const std::string& prefix = "");
    // A field computed elsewhere (tests, analytic shapes): distances at cell centres, x fastest.
    void upload(const std::vector<float>& distances, int layer = 0);
    std::vector<float> readBack(int layer = 0) const;  // one layer of the distance texture, x fastest
    // The field at `unit` and the coarse level at unit + 1 (what sdf_march.glsl reads).
    void bind(GLuint unit) const;
    const gl::Texture& distance() const { return distance_; }
    const gl::Texture& coarse() const { return coarse_; }
    const SdfVolume& volume(int layer = 0) const { return volumes_.at(size_t(layer)); }
    int layers() const { return int(volumes_.size()); }
    static std::vector<ProgramDesc> programs();

private:
    void buildCoarse(int layer);
    std::vector<SdfVolume> volumes_;
    gl::MemoryScope scope_;
    gl::Texture distance_, coarse_;
    gl::Object seedProgram_, stepProgram_, resolveProgram_, coarseProgram_;
};

}  // namespace gis
