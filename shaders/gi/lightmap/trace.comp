// The lightmap bake: one path per texel per dispatch, the path tracer's own (path_tracer.glsl),
// leaving the texel's point in a cosine-weighted direction. Their mean is the texel's irradiance
// over pi, what the lighting contract's indirect.diffuse holds: u_term (set to the indirect term)
// keeps what the first hit emits and the lights' direct light on the texel out, which the
// lighting pass adds itself. With lightmap.mode=all (u_term: everything, u_bakeDirect 1) the frame
// draws no light: the lights are also sampled at the texel, as the path tracer samples them at a
// vertex (the punctual lights, which no ray can hit, only so), and what the cosine ray hits first is
// weighted against that (MIS): shadows of small emitters come out of the noise as they do there. The running mean's
// alpha is the luminance's second moment, from which the denoiser knows each texel's noise.
#include "path_tracer.glsl"
#include "gi/lightmap/lightmap_texels.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = IL_POSITION, rgba32f) readonly uniform image2DArray u_position;
layout(binding = IL_NORMAL, rgba32f) readonly uniform image2DArray u_normal;
layout(binding = IL_MEAN, rgba32f) uniform image2DArray u_mean;
layout(binding = IL_DIRECTION, rgba32f) uniform image2DArray u_direction;  // lightmap.directional only
layout(location = U_SAMPLE_INDEX) uniform uint u_sampleIndex;
layout(location = U_SEED) uniform uint u_seed;
layout(location = UL_BAKE_DIRECT) uniform int u_bakeDirect;
layout(location = UL_DIRECTIONAL) uniform int u_directional;

// The light sampled at the texel as the path tracer samples it at a vertex (every punctual light,
// one emitter by power, the map by luminance), MIS-weighted against the cosine ray, on a white
// Lambertian surface: E / pi. `punctualMoment`: the punctual lights' luminance times their
// directions (xyz) and alone (w), for the directional mean; the one emitter and the map sampled
// here count along the texel's normal, their directions not kept.
vec3 lightsAtTexel(vec3 position, vec3 n, inout Rng rng, out vec4 punctualMoment) {
    SurfacePoint s;
    s.position = position;
    s.geometricNormal = n;
    s.normal = n;
    s.brdf = makeSurfaceBrdf(vec3(1.0), 0.0, 1.0, 0.0);
    s.emission = vec3(0.0);
    s.emitterPdfPerArea = 0.0;
    s.hasSpecular = false;
    vec3 unusedShare;
    const ivec2 lambert = ivec2(DIFFUSE_LAMBERT, SPECULAR_NONE);
    punctualMoment = vec4(0.0);
    return punctualLight(s, n, lambert, punctualMoment) + emitterLight(s, n, 0.0, lambert, rng) +
           environmentLight(s, n, 0.0, lambert, rng, false, unusedShare);
}

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
    bool direct = u_bakeDirect != 0;
    vec3 path = finiteOrZero(min(tracePath(offsetRayOrigin(position.xyz, n), dir, rng, 1,
                                           direct ? max(dot(n, dir), 0.0) * INV_PI : 0.0), vec3(MAX_RADIANCE)));
    vec4 punctual = vec4(0.0);
    vec3 lights = direct ? finiteOrZero(min(lightsAtTexel(position.xyz, n, rng, punctual), vec3(MAX_RADIANCE))) : vec3(0.0);
    vec3 radiance = min(path + lights, vec3(MAX_RADIANCE));
    float lum = luminance(radiance);
    vec4 mean = u_sampleIndex == 0u ? vec4(0.0) : imageLoad(u_mean, texel);
    float count = float(u_sampleIndex + 1u);
    mean += (vec4(radiance, lum * lum) - mean) / count;
    imageStore(u_mean, texel, min(mean, vec4(MAX_RADIANCE)));
    if (u_directional != 0) {
        // The luminance-weighted mean direction of the light arriving (the cosine-weighted first
        // moment of the radiance over pi, from which apply.frag fits its first-order harmonics).
        vec3 moment = luminance(path) * dir;
        if (direct) moment += punctual.xyz + max(luminance(lights) - punctual.w, 0.0) * n;
        vec4 directionMean = u_sampleIndex == 0u ? vec4(0.0) : imageLoad(u_direction, texel);
        directionMean += (vec4(moment, 0.0) - directionMean) / count;
        imageStore(u_direction, texel, directionMean);
    }
    publishRayCounts();
}
