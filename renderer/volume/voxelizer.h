// The voxelizer: the scene rasterized into a cubic grid of averaged albedo, normal, emission and
// occupancy (shaders/volume/). Triangles are projected along their dominant axis in a geometry
// shader and rasterized conservatively, by GL_NV_conservative_raster (hardware) or by dilating the
// triangle in the geometry shader (geometry); `off` is plain rasterization, which misses thin and
// small triangles. The scene volume's (renderer/volume/scene_volume.h) first step.
#pragma once

#include <string>

#include "gl/gl.h"
#include "gl/shader.h"
#include "gpu_scene.h"
#include "volume/volume_fit.h"

namespace gis {

// The fixed-point sums voxelization keeps per voxel (shaders/volume/voxel_sums.glsl names them;
// GLSL's VOXEL_CHANNELS) and, in a buffer of their own, where in the voxel its surface samples lie
// (VOXEL_PLACE_CHANNELS): two buffers, each within a driver's limit on one storage block (llvmpipe's
// 128 MiB holds 128^3 voxels of either, not of both together).
constexpr int kVoxelSumChannels = 14;
constexpr int kVoxelPlaceChannels = 3;
constexpr int kVoxelSumsBinding = 0;
constexpr int kVoxelPlacesBinding = 1;

enum class ConservativeMode { Hardware, Geometry, Off };
const char* conservativeModeName(ConservativeMode m);

// GPU bytes the voxel textures of one grid take (albedo, normal, emission, and the transient
// fixed-point sums during voxelization).
int64_t voxelGridBytes(int resolution);
// Throws gis::Error with the estimate when `bytes` exceed what we allow a voxel method to hold
// (kVoxelBudgetBytes) or the resolution exceeds the driver's 3D texture size, before anything is
// allocated.
void checkVoxelBudget(int resolution, int64_t bytes, const std::string& what);
constexpr int64_t kVoxelBudgetBytes = int64_t(8) << 30;

struct VoxelGrid {
    VolumeFit fit;
    gl::Texture albedo;    // RGBA8: linear albedo, a = occupancy (1 where any surface touched)
    gl::Texture normal;    // RGBA8: mean normal * 0.5 + 0.5 (shorter than 1 where normals disagree); a: a slab's junction (0 none)
    gl::Texture emission;  // RGBA16F: emitted radiance; a: a slab voxel's mark, its axis and place (0 none; voxel_resolve.comp)
};

class Voxelizer {
public:
    // Allocates the grid (charged to scope.owner) after checking its size. `hardware` without
    // GL_NV_conservative_raster falls back to `geometry`, with one warning on stderr naming
    // `modeKey` (the parameter that asked for it; none when empty: the best available was asked).
    Voxelizer(const VolumeFit& fit, ConservativeMode mode, const gl::MemoryScope& scope,
              const std::string& modeKey = "");
    // Places the grid over another cube of the same resolution (a cascade that follows the camera):
    // textures and programs are kept; the next voxelize() fills it. Throws gis::Error for another
    // resolution.
    void moveTo(const VolumeFit& fit);
    // Clears the grid and voxelizes every draw of the scene.
    void voxelize(const GpuScene& scene);
    // Places the grid over `fit`, the current cube moved by `shift` of its cells (a cascade that
    // scrolls with the camera): the cells both cubes hold are moved on the GPU, and only the cells
    // that entered are voxelized, which gives the same voxels as moveTo() + voxelize(). A shift of
    // a whole edge or more voxelizes everything. Returns the cells voxelized.
    int64_t scroll(const VolumeFit& fit, const glm::ivec3& shift, const GpuScene& scene);
    const VoxelGrid& grid() const { return grid_; }
    ConservativeMode mode() const { return mode_; }
    static std::vector<ProgramDesc> programs();
    static bool hardwareConservativeAvailable();

private:
    // Voxelizes the scene but leaves the cells in [keepLo, keepHi) as they are.
    void voxelizeAround(const GpuScene& scene, const glm::ivec3& keepLo, const glm::ivec3& keepHi);
    VoxelGrid grid_;
    gl::MemoryScope scope_;
    ConservativeMode mode_;
    gl::Object voxelizeProgram_, resolveProgram_, fbo_;
};

}  // namespace gis
