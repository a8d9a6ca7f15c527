// A texel's point of the surface: position (w = 1: the texel is on a chart) and normal (w = its
// chart + 1, so the denoiser never mixes charts).
#if EDGES  // drawn through texel_edges.geom
#define v_position g_position
#define v_normal g_normal
#define v_chart g_chart
#endif
in vec3 v_position;
in vec3 v_normal;
flat in float v_chart;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;

void main() {
    vec3 n = dot(v_normal, v_normal) > 0.0 ? normalize(v_normal) : vec3(0.0, 1.0, 0.0);
    o_position = vec4(v_position, 1.0);
    o_normal = vec4(n, v_chart + 1.0);
}
