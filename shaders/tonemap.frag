// Exposure, tone mapping and sRGB encoding: linear radiance -> display 8-bit.
#include "common.glsl"

layout(binding = T_TONEMAP_RADIANCE) uniform sampler2D s_radiance;
layout(location = U_EXPOSURE) uniform float u_exposureScale;   // 2^EV
layout(location = U_TONEMAPPER) uniform int u_tonemapper;      // 0 ACES fitted, 1 linear clamp

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

// ACES filmic curve as fitted by Stephen Hill (BakingLab, 2016): sRGB -> ACES AP1-ish input
// matrix, RRT+ODT rational fit, output matrix back to linear sRGB.
vec3 acesFitted(vec3 c) {
    const mat3 inputMat = mat3(0.59719, 0.07600, 0.02840,
                               0.35458, 0.90834, 0.13383,
                               0.04823, 0.01566, 0.83777);
    const mat3 outputMat = mat3(1.60475, -0.10208, -0.00327,
                                -0.53108, 1.10813, -0.07276,
                                -0.07367, -0.00605, 1.07602);
    c = inputMat * c;
    vec3 a = c * (c + 0.0245786) - 0.000090537;
    vec3 b = c * (0.983729 * c + 0.4329510) + 0.238081;
    return saturate(outputMat * (a / b));
}

void main() {
    vec3 c = finiteOrZero(texelFetch(s_radiance, ivec2(gl_FragCoord.xy), 0).rgb) * u_exposureScale;
    c = u_tonemapper == 0 ? acesFitted(max(c, vec3(0.0))) : saturate(c);
    o_color = vec4(linearToSrgb(c), 1.0);
}
