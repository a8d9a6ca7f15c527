// glTF metallic-roughness material inputs, sampled at a surface point.

layout(binding = T_MATERIAL_BASE_COLOR) uniform sampler2D s_baseColor;
layout(binding = T_MATERIAL_METALLIC_ROUGHNESS) uniform sampler2D s_metallicRoughness;   // G = roughness, B = metallic (glTF)
layout(binding = T_MATERIAL_NORMAL) uniform sampler2D s_normal;
layout(binding = T_MATERIAL_EMISSIVE) uniform sampler2D s_emissive;
layout(binding = T_MATERIAL_OCCLUSION) uniform sampler2D s_occlusion;           // R = occlusion (glTF)

layout(location = U_BASE_COLOR_FACTOR) uniform vec4 u_baseColorFactor;
layout(location = U_METALLIC) uniform float u_metallic;
layout(location = U_ROUGHNESS) uniform float u_roughness;
layout(location = U_SPECULAR_FACTOR) uniform float u_specularFactor;
layout(location = U_OCCLUSION_STRENGTH) uniform float u_occlusionStrength;
layout(location = U_EMISSIVE) uniform vec3 u_emissive;
layout(location = U_ALPHA_CUTOFF) uniform float u_alphaCutoff;       // < 0: opaque
layout(location = U_NORMAL_SCALE) uniform float u_normalScale;
layout(location = U_DOUBLE_SIDED) uniform bool u_doubleSided;
layout(location = U_BRDF_OVERRIDE) uniform ivec2 u_brdfOverride;      // diffuse, specular model; -1 = the render's setting

// The textures the material has, one bit each (GpuMaterial::textures); every one unless the including
// shader says. The G-buffer pass compiles each material's set: a missing texture is a 1x1 white one,
// and sampling it still cost every fragment a filtered lookup (the G-buffer pass ~40% faster on
// cornell_point, which has none).
#define MATERIAL_BASE_COLOR_TEXTURE 1
#define MATERIAL_METALLIC_ROUGHNESS_TEXTURE 2
#define MATERIAL_NORMAL_TEXTURE 4
#define MATERIAL_EMISSIVE_TEXTURE 8
#define MATERIAL_OCCLUSION_TEXTURE 16
#ifndef MATERIAL_TEXTURES
#define MATERIAL_TEXTURES 31
#endif
#define MATERIAL_HAS(bit) ((MATERIAL_TEXTURES & (bit)) != 0)

// A material texture at uv, or the white its absence stands for.
#define MATERIAL_SAMPLE(bit, s, uv) (MATERIAL_HAS(bit) ? texture(s, uv) : vec4(1.0))

vec4 materialBaseColor(vec2 uv, vec4 vertexColor) {
    return u_baseColorFactor * vertexColor * MATERIAL_SAMPLE(MATERIAL_BASE_COLOR_TEXTURE, s_baseColor, uv);
}

// alphaMode MASK: cut-outs in the G-buffer and in the shadow maps alike.
bool materialCutout(float alpha) {
    return u_alphaCutoff >= 0.0 && alpha < u_alphaCutoff;
}
