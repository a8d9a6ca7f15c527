// The scene volume's occupancy hierarchy (HDDAGI's "no distance field"): per cascade, a 64-bit
// mask per block of kOccupancyBlock^3 voxels and a presence bit per region of kOccupancyRegion^3
// voxels, built on the GPU from the voxels' occupancy (albedo alpha). Rays walk it with the
// hierarchical DDA of shaders/volume/hdda.glsl (Museth 2014, "Hierarchical digital differential
// analyzer for efficient ray-marching in OpenVDB"; Amanatides & Woo 1987 at each level): an empty
// region or block is crossed in one step. Rebuilt per cascade whenever its voxels are.
//
// Layout (std430, every cascade after the other, finest first):
//   blocks:  uvec2 per block, x + B (y + B z) with B = resolution / kOccupancyBlock; bit
//            x + 4 (y + 4 z) of the block's voxels, bits 0-31 in .x, 32-63 in .y;
//   regions: one bit per region, x + R (y + R z) with R = resolution / kOccupancyRegion, 32 to a uint.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/shader.h"

namespace gis {

struct VoxelGrid;

constexpr int kOccupancyBlock = 4;    // voxels per block edge: 4^3 = 64 bits
constexpr int kOccupancyRegion = 8;   // voxels per region edge
// SSBO bindings of the two buffers in every program that includes hdda.glsl (shared defines).
constexpr int kOccupancyBlocksBinding = 6;
constexpr int kOccupancyRegionsBinding = 7;

int64_t occupancyBytes(int resolution, int cascades);

class OccupancyHierarchy {
public:
    // `resolution` must be a multiple of kOccupancyRegion (the volumes' powers of two are).
    OccupancyHierarchy(const gl::MemoryScope& scope, int resolution, int cascades);
    OccupancyHierarchy(const OccupancyHierarchy&) = delete;
    OccupancyHierarchy& operator=(const OccupancyHierarchy&) = delete;

    // Cascade `cascade`'s masks and region bits from `grid`'s occupancy.
    void build(const VoxelGrid& grid, int cascade);
    void bind() const;   // both buffers at their bindings

    int resolution() const { return resolution_; }
    int cascades() const { return cascades_; }
    // Read back (tests, debug): cascade c's block masks as 64-bit words, its region bits one per region.
    std::vector<uint64_t> readBlocks(int cascade) const;
    std::vector<bool> readRegions(int cascade) const;
    int blocksPerEdge() const { return resolution_ / kOccupancyBlock; }
    int regionsPerEdge() const { return resolution_ / kOccupancyRegion; }
    int regionWords() const;   // uints of region bits per cascade
    static std::vector<ProgramDesc> programs();

private:
    int resolution_, cascades_;
    gl::Buffer blocks_, regions_;
    gl::Object buildProgram_;
};

}  // namespace gis
