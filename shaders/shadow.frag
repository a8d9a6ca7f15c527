// Shadow maps record depth only; this stage exists for alphaMode MASK cut-outs.
#include "material.glsl"

in VertexData {
    vec3 worldPos;
    vec3 normal;
    vec4 tangent;
    vec2 uv;
    vec4 color;
} v_in;

void main() {
    if (materialCutout(materialBaseColor(v_in.uv, v_in.color).a)) discard;
}
