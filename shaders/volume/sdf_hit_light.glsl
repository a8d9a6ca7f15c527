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
// made its field. The trilinear mix is done by hand so that each of its voxels that is a slab (a
// wall thinner than a cell) shows the face on the side the ray came from before they are mixed: a
// mix of the filtered means let the slab next to the one hit (the sunlit roof above a closed
// room's wall) add half its lit top. "The side the ray came from" is judged from where it started,
// not from the field's gradient, which at a wall thinner than a cell may point the other way.
vec3 sdfHitLight(sampler3D radiance, sampler3D sides, SdfCascades cs, SdfHit h, vec3 dir) {
    SdfVolume vol = sdfCascadeVolume(cs, h.cascade);
    float cell = sdfCellSize(vol);
    vec3 front = faceforward(h.normal, dir, h.normal);
    vec3 rayOrigin = h.position - dir * h.t;
    vec3 p = (h.position + front * 0.5 * cell - vol.origin) / cell - 0.5;
    ivec3 base = ivec3(floor(p));
    vec3 f = p - vec3(base);
    vec4 r = vec4(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
        ivec3 v = clamp(base + o, ivec3(0), ivec3(cs.resolution - 1));
        vec3 w3 = mix(1.0 - f, f, vec3(o));
        ivec3 texel = v + ivec3(0, 0, h.cascade * cs.resolution);
        vec4 slab = texelFetch(sides, texel, 0);
        vec3 towardOrigin = rayOrigin - (vol.origin + voxelSlabCentre(v, slab) * cell);
        r += w3.x * w3.y * w3.z * voxelLightSeen(texelFetch(radiance, texel, 0), slab, towardOrigin);
    }
    return r.a > 1e-3 ? r.rgb / r.a : vec3(0.0);
}
