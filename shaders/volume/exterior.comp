// Surfaces that face air no light reaches: the outsides of a closed, lit room. They are dark in
// every bounce, and a coarse cone texel that holds a wall holds its outside too, which the
// directional mips show in front for cones travelling outwards: the cones of a room's own walls
// and floor saw them as black (renderer/gi/vct/README.md, "Unlit outsides"). Three steps over the
// voxel grid, run after injection, each air voxel holding two bits:
//   SEED:  REACHED for the air in front of a lit voxel (direct light or emission), and with a lit
//          environment for the air on the volume's boundary; OPEN for the air on the boundary;
//   SWEEP: each bit floods along lines of one axis through air (the host alternates the axes
//          until a round adds nothing);
//   CULL:  a surface voxel whose front is air that is OPEN but not REACHED (the space around a
//          closed, lit room) leaves the light's level 0 (radiance and occupancy 0); the wall
//          keeps its inside's voxels. Unreached air that is not OPEN is a closed room of its own
//          (a room with no opening in a sunlit building): its surfaces stay, or its cones would
//          see through its walls to the sunlit outsides behind them.
#include "common.glsl"
#include "volume/voxel_faces.glsl"

#if SWEEP
layout(local_size_x = 8, local_size_y = 8) in;
#else
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#endif
layout(binding = TV_EXTERIOR_ALBEDO) uniform sampler3D s_albedo;    // a = occupancy
layout(binding = TV_EXTERIOR_NORMAL) uniform sampler3D s_normal;
layout(binding = TV_EXTERIOR_RADIANCE) uniform sampler3D s_radiance;  // the injected light (SEED)
layout(r8ui, binding = IV_EXTERIOR_REACH) uniform uimage3D i_reach;
layout(rgba16f, binding = IV_EXTERIOR_RADIANCE) uniform writeonly image3D i_radiance;  // CULL's target
layout(std430, binding = SV_EXTERIOR_CHANGED) buffer Changed { uint u_changed; };

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_EXTERIOR_STEP) uniform ivec2 u_step;  // SEED/CULL: (0 seed | 2 cull, environment lit); SWEEP: (axis, 0)

const uint REACHED = 1u, OPEN = 2u;

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
        uint carry = 0u;
        for (int i = 0; i < u_resolution; ++i) {
            ivec3 p = base + along * (pass == 0 ? i : u_resolution - 1 - i);
            if (!isAir(p)) {
                carry = 0u;
                continue;
            }
            uint have = imageLoad(i_reach, p).r;
            if ((carry & ~have) != 0u) {
                imageStore(i_reach, p, uvec4(have | carry));
                ++added;
            }
            carry |= have;
        }
    }
    if (added > 0u) atomicAdd(u_changed, added);
}
#else
void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!inside(v)) return;
    if (u_step.x == 0) {
        // Each air voxel writes its own bits, gathered from the neighbours that face it (a
        // rounded normal may point to an edge or corner neighbour; two neighbours writing one
        // voxel's different bits would race).
        if (!isAir(v)) return;
        bool boundary = any(equal(v, ivec3(0))) || any(equal(v, ivec3(u_resolution - 1)));
        uint bits = boundary ? (u_step.y != 0 ? OPEN | REACHED : OPEN) : 0u;
        for (int i = 0; i < 27; ++i) {
            ivec3 s = v + ivec3(i % 3, (i / 3) % 3, i / 9) - 1;
            if (s == v || !inside(s) || isAir(s) || frontOf(s) != v) continue;
            vec3 light = texelFetch(s_radiance, s, 0).rgb;
            if (max(light.r, max(light.g, light.b)) > 0.0) bits |= REACHED;
        }
        if (bits != 0u) imageStore(i_reach, v, uvec4(bits));
        return;
    }
    if (isAir(v)) return;
    ivec3 f = frontOf(v);
    if (f == v || !inside(f) || !isAir(f)) return;
    if (imageLoad(i_reach, f).r == OPEN) imageStore(i_radiance, v, vec4(0.0));
}
#endif
