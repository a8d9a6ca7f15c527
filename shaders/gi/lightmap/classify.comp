// What each texel's light may be mixed with, decided once per bake from the ray scene: a texel
// whose centre lies behind a surface (a floor under a wall standing on it: a ray along the surface
// meets the back of a face within a texel) is inside, and gets no light of its own; a neighbour in
// the atlas whose point cannot be reached in a straight line from this one (a wall thinner than a
// texel stands between them) is blocked. The flags go into the position's w (1 + flags, so w > 0
// still says the texel is on a chart). The bake skips inside texels, the denoiser and the dilation
// treat them as gutters, and the lookup (apply.frag) leaves them and blocked neighbours out of its
// bilinear weights: the light of one side of a wall never reaches the other (Godot #117468).
#include "gi/lightmap/lightmap_texels.glsl"
#include "ray_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IL_POSITION, rgba32f) uniform image2DArray u_position;
layout(binding = IL_NORMAL, rgba32f) readonly uniform image2DArray u_normal;
layout(location = UL_TEXEL_SIZE) uniform float u_texelSize;

// The rays run a twentieth of a texel above the surface, parallel to it: lifted by a share of the
// texel (not by offsetRayOrigin's few units in the last place, which the float rounding of two
// texels' positions outweighs) so they neither graze their own plane nor depend on the unit of length.
const float LIFT = 0.05;

bool insideGeometry(vec3 origin, vec3 n) {
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0.0, 1.0, 0.0)) : cross(n, vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(n, t);
    vec3 directions[4] = vec3[4](t, -t, b, -b);
    for (int i = 0; i < 4; ++i) {
        Hit hit;
        if (traceRay(origin, directions[i], u_texelSize, false, false, hit) && !hitGeometry(hit, directions[i]).frontFace)
            return true;
    }
    return false;
}

void main() {
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(u_position);
    if (any(greaterThanEqual(texel, size))) return;
    vec4 p = imageLoad(u_position, texel);
    if (p.w == 0.0) return;
    vec4 n = imageLoad(u_normal, texel);
    vec3 origin = p.xyz + n.xyz * (LIFT * u_texelSize);
    int flags = insideGeometry(origin, n.xyz) ? TEXEL_INSIDE : 0;
    for (int i = 0; i < 4; ++i) {
        ivec3 q = ivec3(texel.xy + TEXEL_NEIGHBOURS[i], texel.z);
        if (any(lessThan(q.xy, ivec2(0))) || any(greaterThanEqual(q.xy, size.xy))) continue;
        vec4 qp = imageLoad(u_position, q);
        if (qp.w == 0.0 || imageLoad(u_normal, q).w != n.w) continue;  // not this chart's: never a real tap
        vec3 d = qp.xyz + imageLoad(u_normal, q).xyz * (LIFT * u_texelSize) - origin;
        float distance = length(d);
        Hit hit;
        if (distance > 0.0 && traceRay(origin, d / distance, distance, true, false, hit)) flags |= 1 << i;
    }
    imageStore(u_position, texel, vec4(p.xyz, 1.0 + float(flags)));
}
