// One level of the radiance mip chain from the level below (premultiplied radiance, occupancy).
// ISOTROPIC: the mean of the 2x2x2 children. Otherwise DIRECTION (0..5 = +X -X +Y -Y +Z -Z, the
// way a cone travels): along that axis the two children are composited front to back (what a cone
// sees passing through), and the four composited pairs are averaged, so a thin wall stays opaque
// for cones that cross it instead of averaging to half-transparent. The first directional level
// also weighs each surface voxel by how squarely its mean normal faces the axis (|n.axis|): a
// plane seen edge-on covers nothing, but its one-voxel-thick voxelization would cover 1/D of every
// coarse cell beside it, so a bright ceiling would glow into every cone running along it. A slab
// voxel (a wall thinner than a voxel, volume/voxel_faces.glsl) shows a cone crossing it along its
// axis the light of the face the cone meets, not the mean of both faces: a roof lit from above
// stays dark for the cones of the room below.
#include "volume/voxel_faces.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TV_MIP_SOURCE) uniform sampler3D s_source;  // the level below, read with texelFetch
layout(binding = TV_MIP_NORMAL) uniform sampler3D s_normal;  // the voxel grid's mean normals (level 0 only)
layout(binding = TV_MIP_SIDES) uniform sampler3D s_sides;   // inject.comp's i_sides (level 0 only)
layout(rgba16f, binding = IV_MIP_TARGET) uniform writeonly image3D i_target;
layout(location = UV_MIP_LEVEL) uniform int u_sourceLevel;
layout(location = UV_DIRECTION) uniform int u_direction;  // -1: isotropic
layout(location = UV_NORMAL_WEIGHT) uniform int u_weightByNormal;  // 0 none, 1 |n.axis|, 2 cull back faces

// A child voxel as seen by a cone travelling along `axis` (travel = +1 or -1): scaled by |n.axis|,
// how much of the voxel's surface a cone along that axis sees, or (u_weightByNormal 2, culling)
// by max(-travel n.axis, 0), nothing of a surface the cone meets from behind. A cone leaving a
// surface then never meets that surface's own voxels (they occluded the sky over an open floor and
// lit a ceiling with its own hot spot). (Culling the light alone and keeping the opacity was tried
// too: every cone then sees its own surface as black, half the light on every wall.)
vec4 child(ivec3 c, int axis, float travel) {
    vec4 v = texelFetch(s_source, c, u_sourceLevel);
    if (u_weightByNormal == 0) return v;
    // A slab is a plane facing +-its axis: along that axis a cone meets the face towards it, and
    // seen edge-on, as any plane, it covers nothing.
    vec4 sides = texelFetch(s_sides, c, 0);
    int slab = voxelSlabAxis(sides);
    if (slab >= 0) {
        vec3 dir = vec3(0.0);
        dir[axis] = travel;
        return slab == axis ? voxelLightSeen(v, sides, -dir) : vec4(0.0, 0.0, 0.0, v.a);
    }
    vec3 n = texelFetch(s_normal, c, 0).xyz * 2.0 - 1.0;
    float len = length(n);
    if (len <= VOXEL_TWO_SIDED) return v;  // opposite faces in one voxel: seen from every side
    float cosine = n[axis] / len;
    return v * (u_weightByNormal == 2 ? max(-travel * cosine, 0.0) : abs(cosine));
}

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, imageSize(i_target)))) return;
    ivec3 base = v * 2;
    vec4 sum = vec4(0.0);
    if (u_direction < 0) {
        for (int i = 0; i < 8; ++i) sum += texelFetch(s_source, base + ivec3(i & 1, (i >> 1) & 1, i >> 2), u_sourceLevel);
    } else {
        int axis = u_direction / 2;
        bool positive = (u_direction & 1) == 0;
        ivec3 along = ivec3(0);
        along[axis] = 1;
        ivec3 u = ivec3(0), w = ivec3(0);
        u[(axis + 1) % 3] = 1;
        w[(axis + 2) % 3] = 1;
        for (int i = 0; i < 4; ++i) {
            ivec3 lo = base + u * (i & 1) + w * (i >> 1);
            vec4 a = child(lo, axis, positive ? 1.0 : -1.0), b = child(lo + along, axis, positive ? 1.0 : -1.0);
            vec4 front = positive ? a : b, back = positive ? b : a;
            sum += front + (1.0 - front.a) * back;
        }
        sum *= 2.0;  // four pairs, each standing for two voxels' worth of the eight
    }
    imageStore(i_target, v, sum * 0.125);
}
