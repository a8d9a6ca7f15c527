// What a voxel's faces say about the light it shows (renderer/volume/voxelizer.h, voxel_radiance.h).
// A mean normal shorter than VOXEL_TWO_SIDED comes from faces that face opposite ways: a wall
// thinner than a voxel. The voxelizer marks such a voxel a slab along the axis its faces face most,
// and injection lights the slab's two faces apart (shaders/volume/inject.comp): level 0 holds their
// mean, the sides texture half their difference (rgb) and the axis (a: 1, 2, 3; 0 for no slab).
#define VOXEL_TWO_SIDED 0.3

// The slab's axis (0, 1, 2), or -1 for a voxel that is no slab.
int voxelSlabAxis(vec4 sides) { return int(sides.a + 0.5) - 1; }

// What something travelling along `dir` sees of a voxel with level-0 light `light` (premultiplied
// by its occupancy a) and sides `sides`: crossing a slab along its axis it meets one face, the
// one towards -dir, and sees that face's light alone, so a roof lit from above shows the room under
// it none of the sun (light stored per direction: Crassin et al. 2011's anisotropic voxels, the six
// directions Godot's SDFGI lights each cell from). Other voxels, and a slab met edge-on, show the mean.
vec4 voxelLightSeen(vec4 light, vec4 sides, vec3 dir) {
    int axis = voxelSlabAxis(sides);
    if (axis < 0 || dir[axis] == 0.0) return light;
    return vec4(max(light.rgb - sign(dir[axis]) * sides.rgb * light.a, vec3(0.0)), light.a);
}
