// Voxel cone tracing per pixel: the lighting contract's indirect.diffuse (cosine-weighted mean
// incoming radiance, E / pi), indirect.specular (radiance along one cone around the mirror
// direction whose aperture follows roughness) and ao (1 - the diffuse cones' mean opacity).
// At a trace scale above 1 each texel traces one full-resolution pixel of its block, the one this
// frame's jitter picks (vct_upsample.comp brings the texels to full resolution).
#include "common.glsl"
#define CONE_SKY_VISIBILITY
#include "volume/cone_trace.glsl"
#include "ray_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_gbufNormal;
layout(binding = 2) uniform sampler2D s_gbufMaterial;
layout(rgba16f, binding = 0) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = 1) uniform writeonly image2D i_specular;
layout(r16f, binding = 2) uniform writeonly image2D i_ao;

layout(location = UV_WORLD_TO_VOXEL) uniform mat4 u_worldToVoxel;
layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UV_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UV_CONE_SET) uniform int u_coneSet;
ConeTraceBlock u_cones;
layout(location = UV_ANISOTROPIC) uniform int u_anisotropic;
layout(location = UV_INTENSITY) uniform float u_intensity;
layout(location = UV_TRACE_JITTER) uniform ivec3 u_traceJitter;  // pixels per texel, this frame's pixel in the block
layout(location = UV_SPECULAR_ROUGHNESS) uniform float u_specularRoughness;

// Sky rays (vct.sky-rays, issue #39): the environment reaches a surface only along rays that
// leave the scene, traced through its triangles from the surface point, not along cones through
// voxels coarser than the walls (a 20 cm wall in 68 cm voxels lets most of a cone through). Each
// cone's rays cover its cap in equal areas, the set turned per pixel (noise rather than bands
// where a window's edge crosses them).
struct SkyRays {
    vec3 origin;      // world, off the surface
    float rotation;   // the pixel's turn of every cone's rays, in [0, 1)
};
SkyRays g_sky;

// The fraction of the cone's rays that leave the scene (-1 without sky rays: the voxels decide).
float coneSkyVisibility(vec3 dir, float tanHalf) {
    int count = u_cones.skyRays;
    if (count == 0) return -1.0;
    mat3 frame = tangentFrame(dir);
    float cosCap = inversesqrt(1.0 + tanHalf * tanHalf);
    float leaving = 0.0;
    for (int i = 0; i < count; ++i) {
        float cosTheta = 1.0 - (float(i) + 0.5) / float(count) * (1.0 - cosCap);
        float phi = 6.2831853 * fract(float(i) * 0.618034 + g_sky.rotation);
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        vec3 d = frame * vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
        Hit h;
        if (!traceRay(g_sky.origin, d, 1e30, true, h)) leaving += 1.0;
    }
    return leaving / float(count);
}

// tan(half aperture) of the specular cone: the GGX lobe widens with alpha = roughness^2; a floor
// keeps mirrors from stepping a fraction of a voxel at a time.
float specularConeTan(float roughness) { return clamp(roughness * roughness, 0.03, 1.0); }

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(i_diffuse)))) return;
    ivec2 size = textureSize(s_depth, 0);
    ivec2 pixel = min(texel * u_traceJitter.x + u_traceJitter.yz, size - 1);
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (depth >= 1.0) {  // background: nothing to light
        imageStore(i_diffuse, texel, vec4(0.0));
        imageStore(i_specular, texel, vec4(0.0));
        imageStore(i_ao, texel, vec4(1.0));
        return;
    }
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 P = world.xyz / world.w;
    vec3 N = normalize(texelFetch(s_gbufNormal, pixel, 0).xyz);
    vec4 material = texelFetch(s_gbufMaterial, pixel, 0);
    g_sky = SkyRays(gbufferRayOrigin(P, N, u_cameraPos), interleavedGradientNoise(vec2(pixel)));
    ConeTracer t = makeConeTracer(u_resolution, u_cones.stepFactor, u_cones.maxDistance, u_anisotropic);
    vec3 origin = (u_worldToVoxel * vec4(P, 1.0)).xyz + N * u_cones.offset;

    vec4 diffuse = traceDiffuse(t, origin, N, u_coneSet, 1.0, 0.0);
    vec3 specular = vec3(0.0);
    if (u_cones.specular != 0 && material.y > u_specularRoughness) {
        // So rough a lobe takes in most of the hemisphere: it sees about what the diffuse cones
        // see (the lighting pass weighs indirect.specular by the split-sum albedo either way).
        specular = diffuse.rgb;
    } else if (u_cones.specular != 0) {
        vec3 V = normalize(u_cameraPos - P);
        vec3 R = reflect(-V, N);
        float tanHalf = specularConeTan(material.y);
        bool escaped;
        vec4 c = traceCone(t, origin, R, tanHalf, 1.0, N, escaped);
        specular = coneRadiance(c, R, tanHalf, escaped);
    }
    imageStore(i_diffuse, texel, vec4(finiteOrZero(diffuse.rgb * u_intensity), 1.0));
    imageStore(i_specular, texel, vec4(finiteOrZero(specular * u_intensity), 1.0));
    imageStore(i_ao, texel, vec4(saturate(1.0 - diffuse.a), 0.0, 0.0, 0.0));
}
