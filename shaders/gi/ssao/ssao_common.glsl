// What both SSAO kernels (ssao.frag: the normal-oriented hemisphere; gtao.frag: horizons per
// slice) read and share: the G-buffer inputs, the per-pixel rotation from the 4x4 noise tile, and
// view-space reconstruction from window depth.
#include "common.glsl"

layout(binding = TA_DEPTH) uniform sampler2D s_depth;       // window depth; the pass binds a linear sampler
layout(binding = TA_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TA_NOISE) uniform sampler2D s_noise;       // 4x4 tile of random rotation vectors (xy)

layout(location = U_PROJ) uniform mat4 u_proj;
layout(location = U_INV_PROJ) uniform mat4 u_invProj;
layout(location = U_VIEW) uniform mat4 u_view;
layout(location = U_AO_RADIUS) uniform float u_aoRadius;
SsaoBlock u_ao;

vec3 viewPosition(vec2 uv, float depth) {
    vec4 p = u_invProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

// This pixel's cell of the noise tile. With temporal accumulation the tile shifts every frame
// (u_ao.noiseOffset = 0..15), so the running mean sees every rotation.
ivec2 noiseCell() {
    int shift = u_ao.noiseOffset;
    return (ivec2(gl_FragCoord.xy) + ivec2(shift & 3, (shift >> 2) & 3)) & 3;
}

// A unit vector of random direction in the xy plane: the cell's rotation.
vec2 noiseRotation() { return texelFetch(s_noise, noiseCell(), 0).xy; }
