// What a voxel's faces say about the light it shows (renderer/volume/voxelizer.h, voxel_radiance.h).
// A voxel with faces facing both ways along an axis (VOXEL_OPPOSITE_SHARE), or whose mean normal is
// shorter than VOXEL_TWO_SIDED, holds a wall thinner than itself. The voxelizer marks it a slab
// (shaders/volume/voxel_resolve.comp, slabMarks), and injection lights the slab's two faces apart
// (shaders/volume/inject.comp): level 0 holds their mean, the sides texture half their difference
// (rgb) and the slab's mark (a: its axis and where along it the slab lies, voxelSlabMark; 0 for no
// slab).
#define VOXEL_TWO_SIDED 0.3

// A slab's mark: its axis (0, 1, 2) and `offset`, where its faces lie along the axis from the
// voxel's centre (in voxels, within +-0.5), in one number: the axis + 1, plus the offset scaled by
// SLAB_MARK_PLACE (under a half, so that rounding gives the axis back).
const float SLAB_MARK_PLACE = 0.5;
float voxelSlabMark(int axis, float offset) { return float(axis + 1) + SLAB_MARK_PLACE * clamp(offset, -0.5, 0.5); }

// A junction's mark (a second thin wall across a slab, kept in the voxel normals' alpha, RGBA8):
// its axis + 0.5 plus the offset scaled by JUNCTION_MARK_PLACE (under one, so that the integer
// part gives the axis back), over the three axes, so that it lies in (0, 1) and 0 stays "none".
const float JUNCTION_MARK_PLACE = 0.9;
float voxelJunctionMark(int axis, float offset) {
    return (float(axis) + 0.5 + JUNCTION_MARK_PLACE * clamp(offset, -0.5, 0.5)) / 3.0;
}

// The junction's axis (0, 1, 2; -1 for none) and where its wall lies along it (voxels from the
// centre), from the normal texture's texel.
int voxelJunctionAxis(vec4 normalTexel) { return normalTexel.a > 0.5 / 255.0 ? min(int(normalTexel.a * 3.0), 2) : -1; }
float voxelJunctionOffset(vec4 normalTexel) {
    return (normalTexel.a * 3.0 - float(voxelJunctionAxis(normalTexel)) - 0.5) / JUNCTION_MARK_PLACE;
}

// Where in voxel v (voxel units) a face of its slab gathers from, on `side` (+1 or -1) of the
// junction's wall: `p` moved along the junction's axis near the voxel's boundary on that side
// (JUNCTION_SIDE of the way from the wall's middle), clear of a wall up to that thick. A point
// laterally at the voxel's centre may lie beyond the junction's wall: the ceiling of a room's corner
// lit by the sky outside it (builtin:building's closed room).
#define JUNCTION_SIDE 0.85
vec3 voxelJunctionSide(ivec3 v, vec4 normalTexel, vec3 p, float side) {
    int axis = voxelJunctionAxis(normalTexel);
    if (axis < 0) return p;
    float wall = float(v[axis]) + 0.5 + voxelJunctionOffset(normalTexel);
    float boundary = float(v[axis]) + (side > 0.0 ? 1.0 : 0.0);
    p[axis] = mix(wall, boundary, JUNCTION_SIDE);
    return p;
}

// The slab's axis (0, 1, 2), or -1 for a voxel that is no slab.
int voxelSlabAxis(vec4 sides) { return int(sides.a + 0.5) - 1; }

// The point a viewer's side of the slab in voxel v is judged from (voxel units): the voxel's
// centre moved along the slab's axis to where its faces lie. Judged from the centre, a ray that
// left a wall lying in the room-side part of its voxel started beyond the centre, on the far side,
// and saw the wall's sunlit outside (builtin:building's closed room).
vec3 voxelSlabCentre(ivec3 v, vec4 sides) {
    vec3 centre = vec3(v) + 0.5;
    int axis = voxelSlabAxis(sides);
    if (axis >= 0) centre[axis] += (sides.a - float(axis + 1)) / SLAB_MARK_PLACE;
    return centre;
}

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
