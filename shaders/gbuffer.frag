// G-buffer: base colour (sRGB target), world normal, material parameters, emitted radiance.
#include "common.glsl"
#include "material.glsl"
#include "gbuffer_layout.glsl"

in VertexData {
    vec3 worldPos;
    vec3 normal;
    vec4 tangent;
    vec2 uv;
    vec4 color;
} v_in;

layout(location = 0) out vec4 o_baseColor;   // rgb base colour, a unused
layout(location = 1) out vec4 o_normal;      // xyz world normal, w BRDF model override (gbuffer_layout.glsl)
layout(location = 2) out vec4 o_material;    // metallic, roughness, occlusion, specular factor
layout(location = 3) out vec4 o_emissive;    // rgb emitted radiance

// A normal that is never zero-length, even for degenerate input.
vec3 safeNormalize(vec3 v, vec3 fallback) {
    float len2 = dot(v, v);
    return len2 > 1e-20 ? v * inversesqrt(len2) : fallback;
}

void main() {
    vec4 base = materialBaseColor(v_in.uv, v_in.color);
    if (materialCutout(base.a)) discard;

    vec3 geometricNormal = safeNormalize(cross(dFdx(v_in.worldPos), dFdy(v_in.worldPos)), vec3(0.0, 1.0, 0.0));
    vec3 n = safeNormalize(v_in.normal, geometricNormal);
    if (u_doubleSided && !gl_FrontFacing) n = -n;  // double-sided: light the side we see
    if (MATERIAL_HAS(MATERIAL_NORMAL_TEXTURE)) {
        vec3 t = v_in.tangent.xyz - n * dot(n, v_in.tangent.xyz);
        t = safeNormalize(t, abs(n.y) < 0.99 ? normalize(cross(n, vec3(0, 1, 0))) : vec3(1, 0, 0));
        vec3 b = cross(n, t) * (v_in.tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = texture(s_normal, v_in.uv).xyz * 2.0 - 1.0;
        tn.xy *= u_normalScale;
        n = safeNormalize(mat3(t, b, n) * tn, n);
    }

    vec4 mr = MATERIAL_SAMPLE(MATERIAL_METALLIC_ROUGHNESS_TEXTURE, s_metallicRoughness, v_in.uv);
    float occlusion = MATERIAL_SAMPLE(MATERIAL_OCCLUSION_TEXTURE, s_occlusion, v_in.uv).r;
    occlusion = 1.0 + u_occlusionStrength * (occlusion - 1.0);
    o_baseColor = vec4(saturate(base.rgb), 1.0);
    o_normal = vec4(n, encodeBrdfOverride(u_brdfOverride));
    o_material = vec4(saturate(u_metallic * mr.b), saturate(u_roughness * mr.g),
                      saturate(occlusion), saturate(u_specularFactor));
    // Clamped to the largest half float: the target is RGBA16F.
    vec3 emissive = u_emissive * MATERIAL_SAMPLE(MATERIAL_EMISSIVE_TEXTURE, s_emissive, v_in.uv).rgb;
    o_emissive = vec4(min(finiteOrZero(max(emissive, vec3(0.0))), vec3(MAX_HALF_FLOAT)), 0.0);
}
