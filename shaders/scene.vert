// Scene geometry for the G-buffer and the shadow maps: object -> world -> clip.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec4 a_color;

layout(location = U_MODEL) uniform mat4 u_model;
layout(location = U_NORMAL_MATRIX) uniform mat3 u_normalMatrix;
layout(location = U_VIEW_PROJ) uniform mat4 u_viewProj;

out VertexData {
    vec3 worldPos;
    vec3 normal;
    vec4 tangent;
    vec2 uv;
    vec4 color;
} v_out;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_out.worldPos = world.xyz;
    v_out.normal = u_normalMatrix * a_normal;
    v_out.tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w);
    v_out.uv = a_uv;
    v_out.color = a_color;
    gl_Position = u_viewProj * world;
}
