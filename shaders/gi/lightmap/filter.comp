// The bake's mean made a lightmap (lightmap_bake.cpp's resolve): copied in, denoised by a-trous
// steps (Dammertz et al., "Edge-Avoiding A-Trous Wavelet Transform for fast Global Illumination
// Filtering", HPG 2010) that stay inside each region (a chart, split where a wall parts its texels:
// lightmap_bake.cpp) and stop at the plane and normal of the
// texel's surface and at a luminance difference of a few of its standard errors (the texels' own
// noise, as SVGF weighs by variance: Schied et al. 2017), then dilated into the gutters. Directional
// lightmaps run it a second time on the light's mean direction (over its luminance), without the
// luminance edges.
#include "common.glsl"
#include "gi/lightmap/lightmap_texels.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IL_POSITION, rgba32f) readonly uniform image2DArray u_position;
layout(binding = IL_NORMAL, rgba32f) readonly uniform image2DArray u_normal;
layout(binding = IL_MEAN, rgba32f) readonly uniform image2DArray u_mean;
layout(binding = IL_SOURCE, rgba16f) readonly uniform image2DArray u_source;
layout(binding = IL_TARGET, rgba16f) writeonly uniform image2DArray u_target;
layout(binding = IL_DIRECTION, rgba32f) readonly uniform image2DArray u_direction;  // directional only
layout(location = UL_MODE) uniform int u_mode;
layout(location = UL_STEP) uniform int u_step;
layout(location = UL_SAMPLES) uniform int u_samples;
layout(location = UL_TEXEL_SIZE) uniform float u_texelSize;
layout(location = UL_DIRECTIONAL) uniform int u_directional;  // 1: filtering the direction (no luminance edges)

const int MODE_COPY = 0, MODE_DENOISE = 1, MODE_DILATE = 2, MODE_COPY_DIRECTION = 3;
// Standard errors of the difference between two texels' means at which the weight is 1/e.
const float LUMINANCE_SIGMA = 4.0;
const float NORMAL_POWER = 64.0;

// The standard error of a texel's mean luminance, from its second moment.
float standardError(ivec3 t) {
    vec4 m = imageLoad(u_mean, t);
    float variance = max(m.a - luminance(m.rgb) * luminance(m.rgb), 0.0);
    return sqrt(variance / max(float(u_samples), 1.0));
}

vec4 denoised(ivec3 c, ivec3 size) {
    vec4 centre = imageLoad(u_source, c);
    vec4 pc = imageLoad(u_position, c);
    vec4 nc = imageLoad(u_normal, c);
    if (centre.a < 1.0) return centre;  // not a texel of its own light
    float lc = luminance(centre.rgb), ec = standardError(c);
    const float kernel[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int y = -2; y <= 2; ++y)
        for (int x = -2; x <= 2; ++x) {
            ivec3 t = ivec3(c.xy + ivec2(x, y) * u_step, c.z);
            if (any(lessThan(t.xy, ivec2(0))) || any(greaterThanEqual(t.xy, size.xy))) continue;
            vec4 nt = imageLoad(u_normal, t);
            vec4 pt = imageLoad(u_position, t);
            vec4 st = imageLoad(u_source, t);
            if (st.a < 1.0 || nt.w != nc.w) continue;  // a gutter, inside geometry, or another region
            vec3 s = st.rgb;
            float plane = abs(dot(nc.xyz, pt.xyz - pc.xyz)) / (u_texelSize * float(u_step));
            float edge = u_directional != 0 ? 0.0 : abs(luminance(s) - lc) / (LUMINANCE_SIGMA * sqrt(ec * ec + standardError(t) * standardError(t)) + 1e-6 * (lc + 1e-30));
            float w = kernel[abs(x)] * kernel[abs(y)] * pow(max(dot(nc.xyz, nt.xyz), 0.0), NORMAL_POWER) * exp(-plane - edge);
            sum += s * w;
            weights += w;
        }
    return weights > 0.0 ? vec4(sum / weights, 1.0) : centre;
}

// A texel without light of its own (a gutter, inside geometry) takes the mean of its neighbours that
// hold light; alpha 1 marks a texel's own light, 0.5 a dilated one (apply.frag prefers the first).
vec4 dilated(ivec3 c, ivec3 size) {
    vec4 centre = imageLoad(u_source, c);
    if (centre.a > 0.0) return centre;
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 t = c.xy + ivec2(x, y);
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size.xy))) continue;
            vec4 s = imageLoad(u_source, ivec3(t, c.z));
            if (s.a > 0.0) sum += s.rgb, count += 1.0;
        }
    return count > 0.0 ? vec4(sum / count, 0.5) : centre;
}

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(u_target);
    if (any(greaterThanEqual(c, size))) return;
    vec4 result;
    float w = imageLoad(u_position, c).w;
    bool own = w > 0.0 && (texelFlags(w) & TEXEL_INSIDE) == 0;
    if (u_mode == MODE_COPY) result = own ? vec4(imageLoad(u_mean, c).rgb, 1.0) : vec4(0.0);
    else if (u_mode == MODE_COPY_DIRECTION) {  // the mean direction, weighted by the light's luminance
        float level = luminance(imageLoad(u_mean, c).rgb);
        vec3 d = level > 0.0 ? imageLoad(u_direction, c).xyz / level : vec3(0.0);
        result = own ? vec4(d / max(1.0, length(d)), 1.0) : vec4(0.0);
    }
    else if (u_mode == MODE_DENOISE) result = denoised(c, size);
    else result = dilated(c, size);
    imageStore(u_target, c, result);
}
