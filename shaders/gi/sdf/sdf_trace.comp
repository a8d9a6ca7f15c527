// SDF GI, per traced pixel: u_rays cosine-distributed rays sphere-traced through the distance field
// (volume/sdf_march.glsl); a hit takes the radiance the voxelizer injected there (direct light and
// emission, Lambertian, premultiplied by occupancy), a miss the environment. Their mean is this
// frame's estimate of the cosine-weighted mean incoming radiance (E / pi: the lighting contract's
// indirect.diffuse) before temporal accumulation and filtering. Also: one mirror ray where the
// surface is smooth, the near-field soft occlusion, and the debug data (steps, first hit normal).
// With cascades (renderer/volume/volume_cascades.h) the field and the radiance hold one layer per
// cascade; a ray starts in the finest cascade around its pixel's surface and hands over outwards.
#include "common.glsl"
#include "random.glsl"
#include "sampling.glsl"
#include "environment.glsl"
#include "gi/sdf/sdf_gbuffer.glsl"
#include "volume/sdf_march.glsl"
#include "volume/sdf_hit_light.glsl"
#define PROBE_SEGMENT_TEST 1
#include "probes/probe_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TG_MATERIAL) uniform sampler2D s_gbufMaterial;  // metallic, roughness, occlusion, specular
layout(binding = VOLUME_DISTANCE_UNIT) uniform sampler3D s_distance;
layout(binding = VOLUME_COARSE_UNIT) uniform sampler3D s_coarse;
layout(binding = VOLUME_RADIANCE_UNIT) uniform sampler3D s_radiance;      // rgb = radiance x occupancy, a = occupancy; a layer per cascade
layout(binding = VOLUME_RADIANCE_UNIT + 7) uniform sampler3D s_sides;     // the slab voxels' sides (volume/voxel_faces.glsl), as many layers
layout(rgba16f, binding = IG_TRACE_DIFFUSE) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = IG_TRACE_REFLECTION) uniform writeonly image2D i_reflection;  // rgb, a = its weight against diffuse
layout(r16f, binding = IG_TRACE_AO) uniform writeonly image2D i_ao;
layout(rgba16f, binding = IG_TRACE_INFO) uniform writeonly image2D i_info;        // mean steps, first hit normal

layout(location = UG_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UG_RESOLUTION) uniform int u_resolution;
layout(location = UG_CASCADES) uniform vec4 u_cascades[SDF_MAX_CASCADES];   // origin xyz, edge; finest first
layout(location = UG_CASCADE_COUNT) uniform int u_cascadeCount;
SdfMarchBlock u_march;
layout(location = UG_RAYS) uniform int u_rays;
layout(location = UG_FRAME) uniform uint u_frame;
SdfTraceBlock u_trace;
layout(location = UG_AO) uniform float u_aoStrength;


SdfCascades cascades() { return SdfCascades(u_cascades, u_cascadeCount, u_resolution); }

// The probe gather's visibility through this field (probes/probe_common.glsl), from where the
// diffuse rays start off the surface.
bool probeSeesPoint(vec3 probe, vec3 P, vec3 away, vec3 V) {
    return sdfSurfaceSeesPoint(s_distance, s_coarse, cascades(), P, away, probe, u_march.offset);
}

SdfMarchParams marchParams() {
    // The coarsest cascade is the scene's cube: no ray inside it goes further than its diagonal.
    SdfMarchParams p = sdfDefaultParams(u_cascades[u_cascadeCount - 1].w * 1.7320508);
    p.hitThreshold = u_march.hitThreshold;
    p.relaxation = u_march.relaxation;
    p.maxSteps = u_march.maxSteps;
    return p;
}

// What a ray along `dir` brings back: the voxel radiance around its hit, or the environment.
vec3 rayRadiance(SdfHit h, vec3 dir) {
    return h.hit ? sdfHitLight(s_radiance, s_sides, cascades(), h, dir) : environmentMiss(dir);
}

// Occlusion closer than the rays' start offset, which the rays step over: the field a little way
// out along the normal against the same field at the surface (so a plane, whatever its offset from
// the level set, reads as open), Quilez-style, weighted towards the nearest samples.
float nearFieldOcclusion(SdfVolume vol, int layer, vec3 P, vec3 N, float reach) {
    if (u_aoStrength <= 0.0) return 1.0;
    float d0 = sdfSample(s_distance, vol, layer, P);
    float occlusion = 0.0, weight = 1.0, total = 0.0;
    for (int k = 1; k <= 3; ++k) {
        float s = reach * float(k) / 3.0;
        float d = sdfSample(s_distance, vol, layer, P + N * s) - d0;
        occlusion += weight * saturate((s - d) / s);
        total += weight;
        weight *= 0.5;
    }
    return saturate(1.0 - u_aoStrength * occlusion / total);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(i_diffuse)))) return;
    Surface s = tracedSurface(pixel);
    if (!s.valid) {
        imageStore(i_diffuse, pixel, vec4(0.0));
        imageStore(i_reflection, pixel, vec4(0.0));
        imageStore(i_ao, pixel, vec4(1.0));
        imageStore(i_info, pixel, vec4(0.0));
        return;
    }
    // Offsets in cells of the finest cascade that holds the surface: a surface far from the camera
    // lies in a coarser cascade, whose level set is further from the true surface.
    SdfCascades cs = cascades();
    int home = sdfCascadeAt(cs, s.position);
    SdfVolume vol = sdfCascadeVolume(cs, home);
    float cell = sdfCellSize(vol);
    vec3 origin = s.position + s.normal * (u_march.offset * cell);
    SdfMarchParams params = marchParams();
    Rng rng = makeRng(uvec2(pixel), u_frame, 0x5df1u);

    // SDFGI: the diffuse term from the probes around the surface (shaders/probes/probe_common.glsl).
    // Where the path test finds none of them in sight, the pixel's own rays.
    vec4 gathered = vec4(0.0);
    if (u_trace.probeGather != 0) gathered = sampleProbesSeenFrom(s.position, s.normal, u_cameraPos, u_trace.gatherBias, u_trace.probeVisibility);
    int rays = gathered.a > 0.0 ? 0 : u_rays;
    vec3 sum = vec3(0.0);
    float steps = 0.0;
    vec3 firstNormal = vec3(0.0);
    for (int i = 0; i < rays; ++i) {
        vec3 dir = cosineDirection(s.normal, nextFloat2(rng));
        SdfHit h = sdfMarchCascades(s_distance, s_coarse, cs, origin, dir, params);
        sum += rayRadiance(h, dir);
        steps += float(h.steps);
        if (i == 0 && h.hit) firstNormal = h.normal * 0.5 + 0.5;  // black: a miss
    }

    vec4 reflection = vec4(0.0);
    float roughness = texelFetch(s_gbufMaterial, pixel * u_scale, 0).y;
    if (u_trace.specular != 0 && roughness < u_trace.specularRoughness) {
        vec3 R = reflect(normalize(s.position - u_cameraPos), s.normal);
        SdfHit h = sdfMarchCascades(s_distance, s_coarse, cs, origin, R, params);
        // Blend towards the diffuse term as the lobe widens: a mirror ray is right only at 0.
        reflection = vec4(rayRadiance(h, R), 1.0 - roughness / max(u_trace.specularRoughness, 1e-6));
    }

    vec3 diffuse = rays > 0 ? sum / float(rays) : gathered.rgb;
    imageStore(i_diffuse, pixel, vec4(finiteOrZero(diffuse), 1.0));
    imageStore(i_reflection, pixel, vec4(finiteOrZero(reflection.rgb), reflection.a));
    imageStore(i_ao, pixel, vec4(nearFieldOcclusion(vol, home, s.position, s.normal, max(u_march.offset, 0.5) * cell)));
    imageStore(i_info, pixel, vec4(steps / float(max(rays, 1)), firstNormal));
}
