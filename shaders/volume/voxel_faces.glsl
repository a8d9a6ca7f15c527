// What a voxel's faces say about the light it shows (renderer/volume/voxelizer.h, voxel_radiance.h).
// A voxel with faces facing both ways along an axis (VOXEL_OPPOSITE_SHARE), or whose mean normal is
// shorter than VOXEL_TWO_SIDED, holds a wall thinner than itself. The voxelizer marks it a slab
// (shaders/volume/voxel_resolve.comp, slabAxis), and injection lights the slab's two faces apart
// (shaders/volume/inject.comp): level 0 holds their mean, the sides texture half their difference
// (rgb) and the axis (a: 1, 2, 3; 0 for no slab).
#define VOXEL_TWO_SIDED 0.3

// The slab's axis (0, 1, 2), or -1 for a voxel that is no slab.
int voxelSlabAxis(vec4 sides) { return int(sides.a + 0.5) - 1; }

// A voxel holds opposite faces along an axis when at least this share of its surface faces each
// way along it: a wall thinner than the voxel, or where such a wall meets a roof or a floor (the
// sunlit roof, its underside and the wall under it in one voxel, whose mean normal points up).
#define VOXEL_OPPOSITE_SHARE 0.1

// What something seen from `towardViewer` (a vector from the voxel towards where the ray or cone
// comes from) sees of a voxel with level-0 light `light` (premultiplied by its occupancy a) and sides
// `sides`: a slab shows the face on the viewer's side of it alone, so a roof lit from above shows the
// room under it none of the sun (light stored per direction: Crassin et al. 2011's anisotropic
// voxels, the six directions Godot's SDFGI lights each cell from). A ray that starts in the room and
// meets the slab almost edge-on (along the wall, under the roof) is on the room's side: by where it
// comes from, not by the sign of its direction's tiny component along the axis. Other voxels, and
// a viewer level with the slab, see the mean.
vec4 voxelLightSeen(vec4 light, vec4 sides, vec3 towardViewer) {
    int axis = voxelSlabAxis(sides);
    if (axis < 0 || towardViewer[axis] == 0.0) return light;
    return vec4(max(light.rgb + sign(towardViewer[axis]) * sides.rgb * light.a, vec3(0.0)), light.a);
}
