// The light a ray sphere-traced through the distance field's cascades (volume/sdf_march.glsl) sees
// where it hits: SDF GI's per-pixel rays and the probe rays of the fields traced through the field.
#include "volume/voxel_faces.glsl"

// Light along `dir` at hit `h`, from `radiance` (rgb x occupancy, a = occupancy; a layer per
// cascade) and the slab voxels' `sides` (as many layers). Looked up half a cell out of the surface,
// towards the ray: the level set runs through the centres of the outermost surface voxels, so the
// trilinear lookup there mixes them only with the empty voxels in front (divided out below), never
// with the voxels behind. Behind a wall thinner than two cells lies its other face, lit from
// outside: half a cell in, a ray from a closed room saw half of its sunlit outside (issue #39,
// builtin:building's closed room). The radiance is the cascade's the hit was found in, whose voxels
// made its field. A slab voxel there (a wall thinner than a cell; the voxel whose centre the hit
// lies on, a quarter cell in against rounding) shows the ray the face it meets. "Out" is the side
// the ray came from: at a wall thinner than a cell the field's gradient may point the other way.
vec3 sdfHitLight(sampler3D radiance, sampler3D sides, SdfCascades cs, SdfHit h, vec3 dir) {
    SdfVolume vol = sdfCascadeVolume(cs, h.cascade);
    float cell = sdfCellSize(vol);
    vec3 front = faceforward(h.normal, dir, h.normal);
    vec4 r = textureLod(radiance, sdfLayerCoord(vol, h.cascade, cs.count, h.position + front * 0.5 * cell), 0.0);
    vec3 inside = (h.position - front * 0.25 * cell - vol.origin) / cell;
    ivec3 v = clamp(ivec3(floor(inside)), ivec3(0), ivec3(cs.resolution - 1));
    vec3 towardOrigin = (h.position - dir * h.t) - (vol.origin + (vec3(v) + 0.5) * cell);
    r = voxelLightSeen(r, texelFetch(sides, v + ivec3(0, 0, h.cascade * cs.resolution), 0), towardOrigin);
    return r.a > 1e-3 ? r.rgb / r.a : vec3(0.0);
}
