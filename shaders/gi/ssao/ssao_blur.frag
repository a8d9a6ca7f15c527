// Bilateral blur of the SSAO term over the 4x4 noise tile: neighbours count only if they lie on
// the centre pixel's tangent plane (distance relative to the view depth) and their normal is
// similar, so the blur removes the rotation pattern without bleeding occlusion across depth edges
// (halos). A plane test rather than a depth difference: a floor seen at a grazing angle changes
// depth quickly from pixel to pixel yet is one surface.
#include "common.glsl"

layout(binding = TA_BLUR_AO) uniform sampler2D s_ao;          // r = AO, g = view depth
layout(binding = TA_BLUR_NORMAL) uniform sampler2D s_gbufNormal;

layout(location = U_INV_PROJ) uniform mat4 u_invProj;
layout(location = U_VIEW) uniform mat4 u_view;

// Neighbours farther than this fraction of the view depth from the centre's plane are another surface.
const float DEPTH_TOLERANCE = 0.02;
// cos of the largest normal difference still blurred across.
const float NORMAL_TOLERANCE = 0.9;

in vec2 v_uv;
layout(location = 0) out vec4 o_ao;

// View-space position of the pixel centre at uv whose view-space z is z.
vec3 viewPosition(vec2 uv, float z) {
    vec4 p = u_invProj * vec4(uv * 2.0 - 1.0, 0.0, 1.0);
    vec3 d = p.xyz / p.w;
    return d * (z / d.z);
}

void main() {
    ivec2 size = textureSize(s_ao, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 center = texelFetch(s_ao, p, 0).rg;
    if (center.g < -1e29) { o_ao = vec4(1.0, center.g, 0.0, 1.0); return; }
    vec3 n = texture(s_gbufNormal, (vec2(p) + 0.5) / vec2(size)).xyz;
    vec3 nView = mat3(u_view) * n;
    vec3 P = viewPosition((vec2(p) + 0.5) / vec2(size), center.g);
    float sum = 0.0, weight = 0.0;
    for (int j = -2; j <= 1; ++j)
        for (int i = -2; i <= 1; ++i) {
            ivec2 q = clamp(p + ivec2(i, j), ivec2(0), size - 1);
            vec2 s = texelFetch(s_ao, q, 0).rg;
            vec3 nq = texture(s_gbufNormal, (vec2(q) + 0.5) / vec2(size)).xyz;
            vec3 Q = viewPosition((vec2(q) + 0.5) / vec2(size), s.g);
            bool similar = s.g > -1e29 && abs(dot(nView, Q - P)) <= DEPTH_TOLERANCE * abs(center.g) &&
                           dot(n, nq) >= NORMAL_TOLERANCE;
            float w = similar ? 1.0 : 0.0;
            sum += s.r * w;
            weight += w;
        }
    o_ao = vec4(weight > 0.0 ? sum / weight : center.r, center.g, 0.0, 1.0);
}
