// The lightmap bake: one path per texel per dispatch, the path tracer's own (path_tracer.glsl),
// leaving the texel's point in a cosine-weighted direction. Their mean is the texel's irradiance
// over pi, what the lighting contract's indirect.diffuse holds: u_term (set to the indirect term)
// keeps what the first hit emits and the lights' direct light on the texel out, which the
// lighting pass adds itself. The running mean's alpha is the luminance's second moment, from
// which the denoiser knows each texel's noise.
#include "path_tracer.glsl"
#include "gi/lightmap/lightmap_texels.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IL_POSITION, rgba32f) readonly uniform image2DArray u_position;
layout(binding = IL_NORMAL, rgba32f) readonly uniform image2DArray u_normal;
layout(binding = IL_MEAN, rgba32f) uniform image2DArray u_mean;
layout(location = U_SAMPLE_INDEX) uniform uint u_sampleIndex;
layout(location = U_SEED) uniform uint u_seed;

void main() {
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(u_mean);
    if (any(greaterThanEqual(texel, size))) return;
    vec4 position = imageLoad(u_position, texel);
    // A gutter texel (no point of a surface), or one inside geometry (classify.comp): no light.
    if (position.w == 0.0 || (texelFlags(position.w) & TEXEL_INSIDE) != 0) return;
    vec3 n = imageLoad(u_normal, texel).xyz;
    Rng rng = makeRng(uvec2(texel.xy) + uvec2(0u, uint(texel.z * size.y)), u_sampleIndex, u_seed);
    vec3 dir = cosineDirection(n, nextFloat2(rng));
    vec3 radiance = finiteOrZero(min(tracePath(offsetRayOrigin(position.xyz, n), dir, rng, 1), vec3(MAX_RADIANCE)));
    float lum = luminance(radiance);
    vec4 mean = u_sampleIndex == 0u ? vec4(0.0) : imageLoad(u_mean, texel);
    float count = float(u_sampleIndex + 1u);
    mean += (vec4(radiance, lum * lum) - mean) / count;
    imageStore(u_mean, texel, min(mean, vec4(MAX_RADIANCE)));
    publishRayCounts();
}
