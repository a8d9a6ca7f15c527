// Voxelization, step 1: project each triangle along its dominant axis onto a resolution^2 viewport,
// so every voxel column the triangle crosses becomes (at least) one fragment. In geometry mode the
// triangle is dilated by half a pixel diagonal per edge (Hasselgren et al., GPU Gems 2 ch. 42): the
// edges move outward and the new corners are the offset edges' intersections. The fragment shader
// clips the over-estimate of sharp corners with the triangle's bounding box. The undilated projected
// triangle goes to every fragment, which weighs emission by the part of its pixel the triangle covers.

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in VertexData {
    vec3 worldPos;
    vec3 normal;
    vec4 tangent;
    vec2 uv;
    vec4 color;
} v_in[];

out VoxelData {
    vec3 normal;
    vec2 uv;
    vec4 color;
} g_out;
flat out int g_axis;        // dominant axis: 0 x, 1 y, 2 z (the projection's depth)
flat out vec4 g_bounds;     // the triangle's projected box: min xy, max xy (pixels)
flat out vec3 g_plane;      // depth = x * g_plane.x + y * g_plane.y + g_plane.z (voxels)
flat out vec2 g_depthRange; // the triangle's depth extent (voxels)
flat out vec2 g_triangle[3]; // the undilated projected triangle (pixels)

layout(location = UV_WORLD_TO_VOXEL) uniform mat4 u_worldToVoxel;
layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_CONSERVATIVE) uniform int u_conservative;

// Voxel coordinates rearranged so the dominant axis becomes the third (depth) component.
vec3 swizzleToAxis(vec3 v, int axis) { return axis == 0 ? v.yzx : axis == 1 ? v.zxy : v; }

void main() {
    vec3 p[3];
    for (int i = 0; i < 3; ++i) p[i] = (u_worldToVoxel * vec4(v_in[i].worldPos, 1.0)).xyz;
    vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    vec3 an = abs(n);
    if (max(max(an.x, an.y), an.z) <= 0.0) return;  // degenerate: no area, no plane
    int axis = an.x >= an.y && an.x >= an.z ? 0 : an.y >= an.z ? 1 : 2;
    vec3 s[3];
    for (int i = 0; i < 3; ++i) s[i] = swizzleToAxis(p[i], axis);
    vec3 ns = swizzleToAxis(n, axis);
    int order[3] = int[3](0, 1, 2);
    if (ns.z < 0.0) order = int[3](0, 2, 1);  // counter-clockwise in the projection

    vec3 plane = vec3(-ns.x / ns.z, -ns.y / ns.z, dot(ns, s[0]) / ns.z);
    vec4 bounds = vec4(min(min(s[0].xy, s[1].xy), s[2].xy), max(max(s[0].xy, s[1].xy), s[2].xy));
    vec2 depthRange = vec2(min(min(s[0].z, s[1].z), s[2].z), max(max(s[0].z, s[1].z), s[2].z));

    vec2 q[3];
    for (int i = 0; i < 3; ++i) q[i] = s[order[i]].xy;
    vec2 outQ[3] = q;
    if (u_conservative == 1) {
        // Edge lines a x + b y + c = 0, positive inside; pushed out by the pixel's half diagonal
        // measured along the edge normal (|a| + |b|) / 2.
        vec3 e[3];
        for (int i = 0; i < 3; ++i) {
            e[i] = cross(vec3(q[i], 1.0), vec3(q[(i + 1) % 3], 1.0));
            e[i].z += 0.5 * (abs(e[i].x) + abs(e[i].y));
        }
        for (int i = 0; i < 3; ++i) {
            vec3 v = cross(e[(i + 2) % 3], e[i]);  // corner i: where its two edges meet
            // Nearly parallel offset edges (a needle) meet very far away: keep the corner finite by
            // pulling it back along its own direction (a million pixels: the angle barely
            // changes); the bounding-box clip in the fragment shader removes the excess.
            float w = abs(v.z) > 1e-20 ? v.z : (v.z < 0.0 ? -1e-20 : 1e-20);
            vec2 d = v.xy / w - q[i];
            float len = length(d);
            outQ[i] = q[i] + (len > 1e6 ? d * (1e6 / len) : d);
        }
    }
    for (int i = 0; i < 3; ++i) {
        int k = order[i];
        g_out.normal = v_in[k].normal;
        g_out.uv = v_in[k].uv;
        g_out.color = v_in[k].color;
        g_axis = axis;  // flat outputs too: every output is undefined after EmitVertex
        g_bounds = bounds;
        g_plane = plane;
        g_depthRange = depthRange;
        g_triangle = q;
        gl_Position = vec4(outQ[i] / float(u_resolution) * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
