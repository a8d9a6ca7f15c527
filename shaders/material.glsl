// glTF metallic-roughness material inputs, sampled at a surface point.
#include "uniforms.glsl"

layout(binding = 0) uniform sampler2D s_baseColor;
layout(binding = 1) uniform sampler2D s_metallicRoughness;   // G = roughness, B = metallic (glTF)
layout(binding = 2) uniform sampler2D s_normal;
layout(binding = 3) uniform sampler2D s_emissive;
layout(binding = 4) uniform sampler2D s_occlusion;           // R = occlusion (glTF)

layout(location = U_BASE_COLOR_FACTOR) uniform vec4 u_baseColorFactor;
layout(location = U_MATERIAL_PARAMS) uniform vec4 u_materialParams;  // metallic, roughness, specular, occlusion strength
layout(location = U_EMISSIVE) uniform vec3 u_emissive;
layout(location = U_ALPHA_PARAMS) uniform vec4 u_alphaParams;        // cutoff (<0 opaque), normal scale, has normal map, double sided
layout(location = U_BRDF_OVERRIDE) uniform ivec2 u_brdfOverride;      // diffuse, specular model; -1 = the render's setting

vec4 materialBaseColor(vec2 uv, vec4 vertexColor) {
    return u_baseColorFactor * vertexColor * texture(s_baseColor, uv);
}

// alphaMode MASK: cut-outs in the G-buffer and in the shadow maps alike.
bool materialCutout(float alpha) {
    return u_alphaParams.x >= 0.0 && alpha < u_alphaParams.x;
}
