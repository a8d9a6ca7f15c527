// The lightmap at render time: the scene's surfaces drawn again at their lightmap UVs, each pixel
// the irradiance / pi its surface's texels baked (lightmap_pass.cpp).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec3 a_layerChartSided;  // atlas layer, chart, double-sided

layout(location = UL_VIEW_PROJ) uniform mat4 u_viewProj;

out vec3 v_uvLayer;
out vec3 v_world;
out vec3 v_normal;
flat out float v_doubleSided;

void main() {
    v_uvLayer = vec3(a_uv, a_layerChartSided.x);
    v_doubleSided = a_layerChartSided.z;
    v_world = a_position;
    v_normal = a_normal;
    gl_Position = u_viewProj * vec4(a_position, 1.0);
}
