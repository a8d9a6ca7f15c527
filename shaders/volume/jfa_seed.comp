// Jump flood, pass 0: a surface cell is its own nearest seed, every other cell has none.
// A cell is a surface cell when the occupancy texture's alpha is above one half (the voxelizer's
// albedo texture carries occupancy there; tests give their own).
#include "volume/jfa_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TF_SEED_OCCUPANCY) uniform sampler3D s_occupancy;
layout(binding = IF_SEED_SEEDS, r32ui) uniform writeonly uimage3D i_seeds;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (!jfaInside(c)) return;
    bool surface = texelFetch(s_occupancy, c, 0).a > 0.5;
    imageStore(i_seeds, c, uvec4(surface ? jfaPack(c) : JFA_NONE));
}
