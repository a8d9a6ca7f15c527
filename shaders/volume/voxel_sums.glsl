// Per-voxel fixed-point sums that voxelization accumulates with atomicAdd and the resolve pass
// turns into averages. Integer sums are order-independent: the same scene gives bit-identical
// voxels every time (no flicker) and no concurrent write is ever lost, which a read-modify-write
// moving average on RGBA8 (compare-and-swap loops) cannot promise without spinning.
// The sums' channels (VOXEL_CHANNELS, renderer/volume/voxelizer.h): count, albedo rgb, emission rgb
// x coverage, normal xyz, emissive coverage, |normal| xyz. The places' (VOXEL_PLACE_CHANNELS): per
// axis, |normal| along it x where along it in the voxel the sample lies.
#define VOXEL_FIXED_ONE 4096.0 // one unit of a [0, 1] quantity; 2^32 / 4096 = 1M fragments per voxel
layout(std430, binding = VOXEL_SUMS_BINDING) buffer VoxelSums { uint u_voxelSums[]; };
layout(std430, binding = VOXEL_PLACES_BINDING) buffer VoxelPlaces { uint u_voxelPlaces[]; };

uint voxelIndex(ivec3 voxel, int resolution) { return uint(voxel.z * resolution + voxel.y) * uint(resolution) + uint(voxel.x); }
uint voxelSumIndex(ivec3 voxel, int resolution, int channel) {
    return voxelIndex(voxel, resolution) * uint(VOXEL_CHANNELS) + uint(channel);
}
uint voxelPlaceIndex(ivec3 voxel, int resolution, int axis) {
    return voxelIndex(voxel, resolution) * uint(VOXEL_PLACE_CHANNELS) + uint(axis);
}
