// Per-voxel fixed-point sums that voxelization accumulates with atomicAdd and the resolve pass
// turns into averages. Integer sums are order-independent: the same scene gives bit-identical
// voxels every time (no flicker) and no concurrent write is ever lost, which a read-modify-write
// moving average on RGBA8 (compare-and-swap loops) cannot promise without spinning.
#define VOXEL_CHANNELS 14      // count, albedo rgb, emission rgb x coverage, normal xyz, emissive coverage, |normal| xyz
#define VOXEL_FIXED_ONE 4096.0 // one unit of a [0, 1] quantity; 2^32 / 4096 = 1M fragments per voxel
layout(std430, binding = 0) buffer VoxelSums { uint u_voxelSums[]; };

uint voxelSumIndex(ivec3 voxel, int resolution, int channel) {
    return (uint(voxel.z * resolution + voxel.y) * uint(resolution) + uint(voxel.x)) * uint(VOXEL_CHANNELS) + uint(channel);
}
