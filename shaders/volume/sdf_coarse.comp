// The coarse level for far marching: one texel per COARSE_FACTOR^3 fine cells holding a lower
// bound of |distance| anywhere in its region. Every point of the region lies in some fine cell,
// within half a cell diagonal (sqrt(3)/2 cells) of that cell's centre, and distance is 1-Lipschitz,
// so min over the region's cells of |d| minus that half diagonal bounds it from below. A marcher
// may step by this value without a fine lookup while it is far from everything.

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TF_COARSE_DISTANCE) uniform sampler3D s_distance;
layout(binding = IF_COARSE_TARGET, r32f) uniform writeonly image3D i_coarse;
layout(location = US_RESOLUTION) uniform int u_resolution;
layout(location = US_CELL_SIZE) uniform float u_cellSize;
layout(location = US_COARSE_FACTOR) uniform int u_factor;
layout(location = US_LAYER) uniform int u_layer;   // which of the stacked volumes (renderer/volume/distance_field.h)

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    int size = imageSize(i_coarse).x;   // per layer: the layers stack along z
    if (any(greaterThanEqual(c, ivec3(size)))) return;
    float lowest = 3.4e38;
    for (int z = 0; z < u_factor; ++z)
        for (int y = 0; y < u_factor; ++y)
            for (int x = 0; x < u_factor; ++x) {
                ivec3 f = min(c * u_factor + ivec3(x, y, z), ivec3(u_resolution - 1));
                lowest = min(lowest, abs(texelFetch(s_distance, f + ivec3(0, 0, u_layer * u_resolution), 0).r));
            }
    imageStore(i_coarse, c + ivec3(0, 0, u_layer * size), vec4(max(lowest - 0.8660254 * u_cellSize, 0.0)));
}
