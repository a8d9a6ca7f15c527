// The occupancy hierarchy's storage (renderer/volume/occupancy.h has the layout): a 64-bit mask per
// block of OCC_BLOCK^3 voxels and a bit per region of OCC_REGION^3 voxels, every cascade after the
// other. Lookups take voxel coordinates of one cascade, inside it.
layout(std430, binding = OCC_BLOCKS_BINDING) buffer OccupancyBlocks { uvec2 occBlocks[]; };
layout(std430, binding = OCC_REGIONS_BINDING) buffer OccupancyRegions { uint occRegions[]; };

int occBlockIndex(int cascade, ivec3 block, int resolution) {
    int b = resolution / OCC_BLOCK;
    return cascade * b * b * b + block.x + b * (block.y + b * block.z);
}
uint occRegionIndex(ivec3 region, int resolution) {
    int r = resolution / OCC_REGION;
    return uint(region.x + r * (region.y + r * region.z));
}
int occRegionBase(int cascade, int resolution) {
    int r = resolution / OCC_REGION;
    return cascade * ((r * r * r + 31) / 32);
}

bool occRegionPresent(int cascade, ivec3 voxel, int resolution) {
    uint r = occRegionIndex(voxel / OCC_REGION, resolution);
    return (occRegions[occRegionBase(cascade, resolution) + int(r >> 5)] & (1u << (r & 31u))) != 0u;
}
uvec2 occBlockMask(int cascade, ivec3 voxel, int resolution) {
    return occBlocks[occBlockIndex(cascade, voxel / OCC_BLOCK, resolution)];
}
bool occMaskHas(uvec2 mask, ivec3 voxel) {
    ivec3 l = voxel & (OCC_BLOCK - 1);
    int bit = l.x + OCC_BLOCK * (l.y + OCC_BLOCK * l.z);
    return (mask[bit >> 5] & (1u << uint(bit & 31))) != 0u;
}
bool occVoxel(int cascade, ivec3 voxel, int resolution) {
    return occRegionPresent(cascade, voxel, resolution) && occMaskHas(occBlockMask(cascade, voxel, resolution), voxel);
}
