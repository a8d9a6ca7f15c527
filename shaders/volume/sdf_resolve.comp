// From the nearest-seed field to a signed distance in world units at each cell's centre.
//
// Magnitude: the distance to the nearest seed cell's centre. The zero level set is therefore the
// surface of the seed cells' centres, which lies within half a cell of the true surface.
//
// Sign (how "inside" is decided): from the orientation of the nearest surface. The voxelizer
// stores each surface cell's averaged normal; a cell whose offset from its nearest seed points
// against that normal is behind the surface, i.e. inside (negative). Where the averaged normal is
// short (a thin wall voxelized from both sides, a sharp edge whose normals cancel), the seed has no
// trustworthy orientation and the cell is taken as outside. Consequences: a closed mesh is negative
// inside and positive outside; a room modelled with inward normals is positive in the room, where
// the camera is; an open mesh (a single quad, the open front of the Cornell box) is negative in the
// region behind its front faces, bounded by where another surface becomes the nearest. The
// marcher steps by |distance|, so it traces such regions correctly as unsigned distance.
// Without normals (u_hasNormals = 0) the field is unsigned.
#include "volume/jfa_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = IF_RESOLVE_SEEDS, r32ui) uniform readonly uimage3D i_seeds;
layout(binding = IF_RESOLVE_DISTANCE, r32f) uniform writeonly image3D i_distance;
layout(binding = TF_RESOLVE_NORMALS) uniform sampler3D s_normals;   // RGBA8: mean normal * 0.5 + 0.5
layout(location = US_CELL_SIZE) uniform float u_cellSize;
layout(location = US_FAR) uniform float u_far;
layout(location = US_HAS_NORMALS) uniform int u_hasNormals;
layout(location = US_LAYER) uniform int u_layer;   // cells z in [layer * n, (layer + 1) * n) of the target

// Averaged normals shorter than this do not decide a sign (three faces of a corner average to
// 0.58, two of an edge to 0.71; both sides of a thin wall to about 0).
const float MIN_NORMAL_LENGTH = 0.25;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (!jfaInside(c)) return;
    uint s = imageLoad(i_seeds, c).x;
    float d = u_far;
    if (s != JFA_NONE) {
        vec3 offset = vec3(c - jfaUnpack(s));
        d = length(offset) * u_cellSize;
        if (u_hasNormals != 0 && d > 0.0) {
            vec3 n = texelFetch(s_normals, jfaUnpack(s), 0).xyz * 2.0 - 1.0;
            if (length(n) > MIN_NORMAL_LENGTH && dot(offset, n) < 0.0) d = -d;
        }
    }
    imageStore(i_distance, c + ivec3(0, 0, u_layer * u_resolution), vec4(d));
}
