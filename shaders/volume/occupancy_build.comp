// The occupancy hierarchy of one cascade (renderer/volume/occupancy.h): one invocation per block
// of OCC_BLOCK^3 voxels reads their occupancy (albedo alpha) into its 64-bit mask and marks its
// region present when any is set.
#include "volume/occupancy.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TV_OCCUPANCY_ALBEDO) uniform sampler3D s_albedo;   // a = occupancy
layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_CASCADE) uniform int u_cascade;

void main() {
    ivec3 b = ivec3(gl_GlobalInvocationID);
    int blocks = u_resolution / OCC_BLOCK;
    if (any(greaterThanEqual(b, ivec3(blocks)))) return;
    uvec2 mask = uvec2(0u);
    for (int bit = 0; bit < 64; ++bit) {
        ivec3 l = ivec3(bit & 3, (bit >> 2) & 3, bit >> 4);
        if (texelFetch(s_albedo, b * OCC_BLOCK + l, 0).a > 0.5) mask[bit >> 5] |= 1u << uint(bit & 31);
    }
    occBlocks[occBlockIndex(u_cascade, b, u_resolution)] = mask;
    if (mask != uvec2(0u)) {
        uint r = occRegionIndex(b * OCC_BLOCK / OCC_REGION, u_resolution);
        atomicOr(occRegions[occRegionBase(u_cascade, u_resolution) + (r >> 5)], 1u << (r & 31u));
    }
}
