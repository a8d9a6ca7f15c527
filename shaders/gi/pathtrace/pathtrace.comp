// Path-traced reference: one sample per pixel per dispatch, accumulated, of the paths in
// path_tracer.glsl.
#include "path_tracer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = I_ACCUMULATION_SUM, rgba32f) uniform image2D u_accumulation;
layout(binding = I_ACCUMULATION_MEAN, rgba32f) uniform writeonly image2D u_output;
layout(location = U_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = U_SAMPLE_INDEX) uniform uint u_sampleIndex;
layout(location = U_SEED) uniform uint u_seed;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_output);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Rng rng = makeRng(uvec2(pixel), u_sampleIndex, u_seed);
    // A uniformly jittered point in the pixel: the box filter Cycles' references use.
    vec2 ndc = (vec2(pixel) + nextFloat2(rng)) / vec2(size) * 2.0 - 1.0;
    // Unprojecting the near and far planes serves perspective and orthographic cameras alike.
    vec4 near = u_invViewProj * vec4(ndc, -1.0, 1.0);
    vec4 far = u_invViewProj * vec4(ndc, 0.0, 1.0);  // not the far plane: it may be at infinity
    vec3 origin = near.xyz / near.w;
    vec3 dir = normalize(far.xyz / far.w - origin);
    // A path whose radiance overflowed (emission or background near FLT_MAX) counts as the
    // largest float, not as black; NaN (min's result is undefined for it) still becomes 0.
    vec3 radiance = finiteOrZero(min(tracePath(origin, dir, rng, 0, 0.0), vec3(MAX_RADIANCE)));

    // The accumulation holds the running mean (rgb) and the sample count (w), not a sum: a sum
    // of samples near FLT_MAX overflows to Inf after two, while the mean of finite non-negative
    // samples lies between them. mean += (x - mean) / n stays in [min, max] of the samples.
    vec4 acc = u_sampleIndex == 0u ? vec4(0.0) : imageLoad(u_accumulation, pixel);
    acc.w += 1.0;
    acc.rgb = min(acc.rgb + (radiance - acc.rgb) / acc.w, vec3(MAX_RADIANCE));
    imageStore(u_accumulation, pixel, acc);
    imageStore(u_output, pixel, vec4(acc.rgb, 1.0));
    publishRayCounts();
}
