// Surfaces that face air no light reaches: the outsides of a closed, lit room. They are dark in
// every bounce, and a coarse cone texel that holds a wall holds its outside too, which the
// directional mips show in front for cones travelling outwards: the cones of a room's own walls
// and floor saw them as black (renderer/gi/vct/README.md, "Unlit outsides"). Three steps over the
// voxel grid, run after injection:
//   SEED:  the air in front of every lit voxel (direct light or emission) is reached, and with a
//          lit environment the air on the volume's boundary;
//   SWEEP: reached air floods along lines of one axis through air (the host alternates the axes
//          until a round adds nothing);
//   CULL:  a surface voxel whose front is air that was not reached leaves the light's level 0
//          (radiance and occupancy 0); the wall keeps its inside's voxels.
#include "common.glsl"
#include "volume/voxel_faces.glsl"

#if SWEEP
layout(local_size_x = 8, local_size_y = 8) in;
#else
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#endif
layout(binding = 0) uniform sampler3D s_albedo;    // a = occupancy
layout(binding = 1) uniform sampler3D s_normal;
layout(binding = 2) uniform sampler3D s_radiance;  // the injected light (SEED)
layout(r8ui, binding = 0) uniform uimage3D i_reach;
layout(rgba16f, binding = 1) uniform writeonly image3D i_radiance;  // CULL's target
layout(std430, binding = 0) buffer Changed { uint u_changed; };

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_EXTERIOR_STEP) uniform ivec2 u_step;  // SEED/CULL: (0 seed | 2 cull, environment lit); SWEEP: (axis, 0)

bool inside(ivec3 v) { return all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, ivec3(u_resolution))); }
bool isAir(ivec3 v) { return texelFetch(s_albedo, v, 0).a == 0.0; }

// The voxel a surface voxel faces (its mean normal rounded to a neighbour), or v itself for a
// voxel holding opposite faces (a one-voxel slab: lit from both sides, never culled).
ivec3 frontOf(ivec3 v) {
    vec3 n = texelFetch(s_normal, v, 0).xyz * 2.0 - 1.0;
    float len = length(n);
    return len > VOXEL_TWO_SIDED ? v + ivec3(round(n / len)) : v;
}

#if SWEEP
void main() {
    ivec2 line = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(line, ivec2(u_resolution)))) return;
    int axis = u_step.x;
    ivec3 along = ivec3(0), u = ivec3(0), w = ivec3(0);
    along[axis] = 1;
    u[(axis + 1) % 3] = 1;
    w[(axis + 2) % 3] = 1;
    ivec3 base = u * line.x + w * line.y;
    uint added = 0u;
    for (int pass = 0; pass < 2; ++pass) {
        bool carry = false;
        for (int i = 0; i < u_resolution; ++i) {
            ivec3 p = base + along * (pass == 0 ? i : u_resolution - 1 - i);
            if (!isAir(p)) {
                carry = false;
            } else if (imageLoad(i_reach, p).r != 0u) {
                carry = true;
            } else if (carry) {
                imageStore(i_reach, p, uvec4(1u));
                ++added;
            }
        }
    }
    if (added > 0u) atomicAdd(u_changed, added);
}
#else
void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!inside(v)) return;
    bool seed = u_step.x == 0;
    if (isAir(v)) {
        bool boundary = any(equal(v, ivec3(0))) || any(equal(v, ivec3(u_resolution - 1)));
        if (seed && u_step.y != 0 && boundary) imageStore(i_reach, v, uvec4(1u));
        return;
    }
    ivec3 f = frontOf(v);
    if (f == v || !inside(f) || !isAir(f)) return;
    if (seed) {
        vec3 light = texelFetch(s_radiance, v, 0).rgb;
        if (max(light.r, max(light.g, light.b)) > 0.0) imageStore(i_reach, f, uvec4(1u));
    } else if (imageLoad(i_reach, f).r == 0u) {
        imageStore(i_radiance, v, vec4(0.0));
    }
}
#endif
