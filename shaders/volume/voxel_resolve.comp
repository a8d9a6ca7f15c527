// Voxelization, step 3: the fixed-point sums become averages in the voxel textures.
#include "volume/voxel_sums.glsl"
#include "volume/voxel_faces.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(rgba8, binding = IV_RESOLVE_ALBEDO) uniform writeonly image3D i_albedo;    // rgb albedo, a occupancy (0 or 1)
layout(rgba8, binding = IV_RESOLVE_NORMAL) uniform writeonly image3D i_normal;    // xyz mean normal * 0.5 + 0.5, a the junction mark (below)
layout(rgba16f, binding = IV_RESOLVE_EMISSION) uniform writeonly image3D i_emission; // rgb emitted radiance, a the slab mark (below)

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_EMISSION_SCALE) uniform float u_emissionScale;  // the scale voxelize.frag applied
layout(location = UV_KEEP_LO) uniform ivec3 u_keepLo;   // a scrolled grid's moved cells: left alone
layout(location = UV_KEEP_HI) uniform ivec3 u_keepHi;

float sumOf(ivec3 v, int channel) { return float(u_voxelSums[voxelSumIndex(v, u_resolution, channel)]); }
float placeOf(ivec3 v, int axis) { return float(u_voxelPlaces[voxelPlaceIndex(v, u_resolution, axis)]); }

// A slab: a voxel with opposite faces, whose two faces inject.comp lights apart. Along the axis
// where the lesser of the shares facing + and - is largest, when it is VOXEL_OPPOSITE_SHARE or more
// (a wall thinner than a voxel; a junction of such a wall and a roof, whose mean normal points up
// and whose light was the sunlit roof's); else, where the normals still cancel (mean shorter than
// VOXEL_TWO_SIDED), along the axis the faces face most. Returns the slab's mark (x; 0 for any
// other voxel) and its junction's (y; 0 for none), volume/voxel_faces.glsl: each an axis and where
// along it the faces lie, from their samples' places in the voxel weighted by how squarely each
// faces the axis. The junction is a second wall thinner than the voxel across the slab (opposite
// shares of VOXEL_OPPOSITE_SHARE or more along another axis too: a room's corner, or where its
// wall meets the floor).
vec2 slabMarks(ivec3 v, vec3 meanNormal, float count) {
    vec3 a = vec3(sumOf(v, 11), sumOf(v, 12), sumOf(v, 13)) / VOXEL_FIXED_ONE;  // sums of |n|
    vec3 n = vec3(sumOf(v, 7), sumOf(v, 8), sumOf(v, 9)) / VOXEL_FIXED_ONE * 2.0 - count;  // sums of n
    vec3 weighted = vec3(placeOf(v, 0), placeOf(v, 1), placeOf(v, 2)) / VOXEL_FIXED_ONE;  // |n| x the place
    vec3 place = mix(vec3(0.5), weighted / max(a, vec3(1e-6)), greaterThan(a, vec3(0.0))) - 0.5;
    vec3 opposite = min(a + n, a - n) * 0.5;  // the lesser of the + and - sums, per axis
    float most = max(opposite.x, max(opposite.y, opposite.z));
    int axis;
    if (most >= VOXEL_OPPOSITE_SHARE * count) {
        axis = opposite.x == most ? 0 : opposite.y == most ? 1 : 2;
    } else {
        if (length(meanNormal) > VOXEL_TWO_SIDED) return vec2(0.0);
        axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    }
    int u = (axis + 1) % 3, w = (axis + 2) % 3;
    int across = opposite[u] >= opposite[w] ? u : w;
    float junction = opposite[across] >= VOXEL_OPPOSITE_SHARE * count ? voxelJunctionMark(across, place[across]) : 0.0;
    return vec2(voxelSlabMark(axis, place[axis]), junction);
}

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(u_resolution)))) return;
    if (all(greaterThanEqual(v, u_keepLo)) && all(lessThan(v, u_keepHi))) return;
    float count = sumOf(v, 0);
    if (count == 0.0) {
        imageStore(i_albedo, v, vec4(0.0));
        imageStore(i_normal, v, vec4(0.5, 0.5, 0.5, 0.0));
        imageStore(i_emission, v, vec4(0.0));
        return;
    }
    float norm = 1.0 / (count * VOXEL_FIXED_ONE);
    vec3 albedo = vec3(sumOf(v, 1), sumOf(v, 2), sumOf(v, 3)) * norm;
    // Emission is averaged over the emissive samples only, weighted by the part of the voxel's
    // cross-section each covers: a lamp 1 mm under the ceiling shares its voxels with the ceiling,
    // and seen from below the voxel shows the lamp, not half of it. Where the emitters cover less
    // than one cross-section in all (a 4 cm lamp in 2 cm voxels: its edges), the voxel carries only
    // the power through the part they cover: the sum, not the mean.
    float emissive = max(sumOf(v, 10) / VOXEL_FIXED_ONE, 1.0);
    vec3 emission = vec3(sumOf(v, 4), sumOf(v, 5), sumOf(v, 6)) / (emissive * VOXEL_FIXED_ONE) / u_emissionScale;
    vec3 normal = vec3(sumOf(v, 7), sumOf(v, 8), sumOf(v, 9)) * norm * 2.0 - 1.0;
    vec2 marks = slabMarks(v, normal, count);
    imageStore(i_albedo, v, vec4(albedo, 1.0));
    imageStore(i_normal, v, vec4(normal * 0.5 + 0.5, marks.y));
    imageStore(i_emission, v, vec4(min(emission, vec3(MAX_HALF_FLOAT)), marks.x));
}
