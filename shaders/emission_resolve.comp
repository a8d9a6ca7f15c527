// The G-buffer's antialiased emission (passes/gbuffer_pass.cpp): the mean of one multisampled
// draw's samples in each pixel, added as 1/count of the result; the draws are offset by less than
// a pixel, so together they are a box filter over the pixel with count x samples points.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = T_EMISSION_SAMPLES) uniform sampler2DMS s_samples;
layout(rgba16f, binding = I_EMISSION) uniform image2D i_emission;
layout(location = U_EMISSION_PASS) uniform ivec2 u_pass;  // this draw's index, the draws

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(i_emission)))) return;
    int samples = textureSamples(s_samples);
    vec4 sum = vec4(0.0);
    for (int s = 0; s < samples; ++s) sum += texelFetch(s_samples, p, s);
    vec4 before = u_pass.x == 0 ? vec4(0.0) : imageLoad(i_emission, p);
    imageStore(i_emission, p, before + sum / float(samples * u_pass.y));
}
