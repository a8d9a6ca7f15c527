// Voxel cone tracing per pixel: the lighting contract's indirect.diffuse (cosine-weighted mean
// incoming radiance, E / pi), indirect.specular (radiance along one cone around the mirror
// direction whose aperture follows roughness) and ao (1 - the diffuse cones' mean opacity).
// At a trace scale above 1 each texel traces one full-resolution pixel of its block, the one this
// frame's jitter picks (vct_upsample.comp brings the texels to full resolution).
#include "common.glsl"
#define CONE_RAYS
#include "volume/cone_trace.glsl"
#include "ray_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TC_TRACE_DEPTH) uniform sampler2D s_depth;
layout(binding = TC_TRACE_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TC_TRACE_MATERIAL) uniform sampler2D s_gbufMaterial;
layout(rgba16f, binding = IC_TRACE_DIFFUSE) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = IC_TRACE_SPECULAR) uniform writeonly image2D i_specular;
layout(r16f, binding = IC_TRACE_AO) uniform writeonly image2D i_ao;

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
#include "gi/vct/vct_surface.glsl"

// Sky rays (vct.sky-rays, issue #39): rays from the pixel's surface through the scene's triangles
// in place of each cone's march (volume/cone_rays.glsl): the environment only along rays that leave
// the scene, and the light of the surfaces the others meet, not cones through voxels coarser than
// the walls, which let the sky and the sunlit ground beyond a room's walls in.
#include "volume/cone_rays.glsl"

// The normal of the surface's own plane at `pixel` (whose position is P), from the positions of
// its neighbours in the depth buffer, on each axis the side nearer in depth (not across an edge);
// towards the camera.
vec3 neighbourPosition(ivec2 q) {
    q = clamp(q, ivec2(0), textureSize(s_depth, 0) - 1);
    return positionFromDepth(q, texelFetch(s_depth, q, 0).r);
}

vec3 depthNormal(ivec2 pixel, vec3 P) {
    vec3 r = neighbourPosition(pixel + ivec2(1, 0)) - P, l = P - neighbourPosition(pixel - ivec2(1, 0));
    vec3 u = neighbourPosition(pixel + ivec2(0, 1)) - P, d = P - neighbourPosition(pixel - ivec2(0, 1));
    vec3 n = cross(dot(r, r) < dot(l, l) ? r : l, dot(u, u) < dot(d, d) ? u : d);
    if (!(dot(n, n) > 0.0)) return vec3(0.0);
    n = normalize(n);
    return dot(n, u_cameraPos - P) < 0.0 ? -n : n;
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
    vec3 P = positionFromDepth(pixel, depth);
    vec3 N = normalize(texelFetch(s_gbufNormal, pixel, 0).xyz);
    vec4 material = texelFetch(s_gbufMaterial, pixel, 0);
    // The surface's plane only matters to the rays (marching cones lift off the shading normal).
    vec3 plane = u_cones.skyRays > 0 ? depthNormal(pixel, P) : vec3(0.0);
    g_coneRays = ConeRaySource(gbufferRayOrigin(P, N, u_cameraPos), interleavedGradientNoise(vec2(pixel)), u_cones.skyRays,
                               false, plane);
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
        // The specular cone marches: one ray's visibility over a rough lobe was noise no filter
        // takes out (renderer/gi/vct/README.md, *Sky rays*).
        float tanHalf = specularConeTan(material.y);
        // A mirror shows the far wall as it shows the near one: the specular cone goes at least the
        // volume's edge whatever vct.max-distance cuts the diffuse cones to (realtime's half-length
        // cones left builtin:mirror's spheres with 0.44 of Cycles' light).
        ConeTracer mirror = t;
        mirror.maxDistance = max(t.maxDistance, float(u_resolution));
        bool escaped;
        vec4 c = traceCone(mirror, origin, R, tanHalf, 1.0, N, escaped);
        specular = coneRadiance(c, R, tanHalf, escaped);
    }
    imageStore(i_diffuse, texel, vec4(finiteOrZero(diffuse.rgb * u_intensity), 1.0));
    imageStore(i_specular, texel, vec4(finiteOrZero(specular * u_intensity), 1.0));
    imageStore(i_ao, texel, vec4(saturate(1.0 - diffuse.a), 0.0, 0.0, 0.0));
}
