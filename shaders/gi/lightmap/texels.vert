// The lightmap's texels: each atlas triangle drawn at its lightmap UVs (one array layer at a time),
// carrying its world position and normal to the texels it covers (lightmap_bake.cpp).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec3 a_layerChartSided;  // atlas layer, chart, double-sided

out vec3 v_position;
out vec3 v_normal;
flat out float v_chart;

void main() {
    v_position = a_position;
    v_normal = a_normal;
    v_chart = a_layerChartSided.y;
    gl_Position = vec4(a_uv * 2.0 - 1.0, 0.0, 1.0);
}
