// Deferred lighting: every punctual light with its shadow map, emission, and the indirect light a
// GI method gives through the lighting contract (README "The lighting contract"), or else the
// constant ambient term that is the `--gi none` baseline. Output is linear radiance: the sum of the
// terms, or with one TERM_* defined that term alone (the lighting pass's debug views; the radiance
// terms add up to the sum).
#include "common.glsl"
#include "brdf.glsl"
#include "gbuffer_layout.glsl"
#include "lights.glsl"
#include "environment.glsl"
#include "environment_brdf.glsl"

layout(binding = T_LIGHTING_DEPTH) uniform sampler2D s_depth;
layout(binding = T_LIGHTING_BASE_COLOR) uniform sampler2D s_gbufBaseColor;
layout(binding = T_LIGHTING_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = T_LIGHTING_MATERIAL) uniform sampler2D s_gbufMaterial;
layout(binding = T_LIGHTING_EMISSIVE) uniform sampler2D s_gbufEmissive;
layout(binding = T_LIGHTING_SHADOW_MAPS) uniform sampler2DArrayShadow s_shadowMaps;
layout(binding = T_LIGHTING_SHADOW_CUBES) uniform sampler2DArrayShadow s_shadowCubes;  // cube faces, 6 layers per cube
layout(binding = T_LIGHTING_AO) uniform sampler2D s_ao;   // r = occlusion of the ambient term ("ao"), or a 1x1 one
layout(binding = T_LIGHTING_INDIRECT_DIFFUSE) uniform sampler2D s_indirectDiffuse;   // "indirect.diffuse" (or the 1x1 one)
layout(binding = T_LIGHTING_INDIRECT_SPECULAR) uniform sampler2D s_indirectSpecular;  // "indirect.specular" (or the 1x1 one)
layout(binding = T_LIGHTING_EMITTERS_DIRECT) uniform sampler2D s_emitterDirect;    // "emitters.direct" (or the 1x1 one)

layout(location = U_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = U_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = U_LIGHT_COUNT) uniform int u_lightCount;
layout(location = U_AMBIENT) uniform vec3 u_ambient;
layout(location = U_BRDF_MODELS) uniform ivec2 u_brdfModels;  // diffuse, specular: --diffuse, --specular
layout(location = U_SHADOWS_ENABLED) uniform int u_shadowsEnabled;
layout(location = U_MAX_RADIANCE) uniform float u_maxRadiance;  // 65504 for an RGBA16F target: no Inf
// The contract's terms the method gives (indirect.diffuse, indirect.specular, ao), compiled in: a
// branch on a uniform would still cost every pixel a masked pass on llvmpipe.
#ifndef INDIRECT_DIFFUSE
#define INDIRECT_DIFFUSE 0
#endif
#ifndef INDIRECT_SPECULAR
#define INDIRECT_SPECULAR 0
#endif
#ifndef AO_INPUT
#define AO_INPUT 0
#endif
#ifndef EMITTER_DIRECT
#define EMITTER_DIRECT 0
#endif
// One of TERM_DIRECT, TERM_INDIRECT_DIFFUSE, TERM_INDIRECT_SPECULAR, TERM_EMISSION, TERM_AO may be
// defined (LightingPass's term views): the output is that term instead of the lit sum.

in vec2 v_uv;
layout(location = 0) out vec4 o_radiance;

// The pixels the camera sees: a directional light's map around the camera where it reaches.
#define SHADOW_CAMERA_MAP 1
#include "shadows.glsl"

// Adds the direct light to `radiance`: every punctual light with its shadow, then the emissive
// triangles as lights. (The lit sum starts it at the emission, the order it always had.)
vec3 addDirectLight(vec3 radiance, SurfaceBrdf surface, vec3 P, vec3 N, vec3 V, ivec2 models, ivec2 pixel) {
    for (int i = 0; i < u_lightCount; ++i) {
        GpuLight light = u_lights[i];
        int type = int(light.positionType.w);
        vec3 L;
        vec3 irradiance = light.radiance.rgb;  // at normal incidence
        if (type == LIGHT_DIRECTIONAL) {
            L = -light.directionRange.xyz;
        } else {
            vec3 toLight = light.positionType.xyz - P;
            // The floor is relative to the coordinates' magnitude (float resolves ~1e-7 of them):
            // an absolute 1e-12 clamped every distance of a scene modelled at 1e-6 units.
            float d2 = max(dot(toLight, toLight), max(1e-14 * dot(P, P), 1e-37));
            float d = sqrt(d2);
            L = toLight / d;
            irradiance *= rangeWindow(d, light.directionRange.w) / d2;  // inverse square law
            if (type == LIGHT_SPOT)
                irradiance *= spotCone(dot(-L, light.directionRange.xyz), light.cone.x, light.cone.y);
        }
        if (all(equal(irradiance, vec3(0.0)))) continue;
        // f * cos(theta_l); wrap and toon diffuse also reach a little past N.L = 0.
        vec3 response = evaluateBrdfCosine(surface, N, V, L, models.x, models.y);
        if (all(equal(response, vec3(0.0)))) continue;
        radiance += response * irradiance * shadowVisibility(light, P, N, dot(N, L));
    }
#if EMITTER_DIRECT
    radiance += texelFetch(s_emitterDirect, pixel, 0).rgb;  // emissive triangles as lights (ReSTIR)
#endif
    return radiance;
}

// The baseline's unshadowed environment: a map's irradiance and prefiltered radiance, or the
// constant ambient (which --background sets). None when the environment is a light of the direct
// pass, which lights the surface there with its shadows.
float baselineEnvironment() { return environmentIsDirectLight() ? 0.0 : 1.0; }

// Indirect light before occlusion, by lobe. Without a method's terms each is the constant ambient
// times the lobe's colour (diffuse colour, F0): the constant-ambient baseline; under an
// environment map, the map's irradiance from its SH9 projection (Ramamoorthi and Hanrahan 2001)
// and its prefiltered radiance around the mirror direction times the lobe's albedo (the split
// sum, Karis 2013), so metals reflect it. With a method's terms (the lighting contract):
//   diffuse:  diffuseColor * indirect.diffuse (E / pi: a Lambert lobe integrated over the
//             incoming radiance, as evaluateBrdfCosine's diffuse term under uniform light);
//   specular: specularAlbedoSplitSum(F0, F90, roughness, N.V) * indirect.specular (the split-sum
//             approximation: the lobe's radiance times the lobe's directional albedo).
void indirectLight(SurfaceBrdf surface, vec3 N, vec3 V, int specularModel, out vec3 diffuse, out vec3 specular) {
#if INDIRECT_DIFFUSE
    diffuse = texture(s_indirectDiffuse, v_uv).rgb * surface.diffuseColor;
#else
    diffuse = baselineEnvironment() * (environmentIsMap() ? environmentIrradiance(N) * INV_PI : u_ambient) * surface.diffuseColor;
#endif
#if INDIRECT_SPECULAR
    float NoV = max(dot(N, V), MIN_N_DOT_V);
    specular = texture(s_indirectSpecular, v_uv).rgb * specularAlbedoSplitSum(surface, NoV, specularModel);
#else
    // A constant ambient is a uniform map: its prefiltered radiance is itself at every roughness.
    float NoV = max(dot(N, V), MIN_N_DOT_V);
    vec3 incoming = environmentIsMap() ? environmentSpecular(reflect(-V, N), surface.roughness) : u_ambient;
    incoming *= baselineEnvironment();
    specular = incoming * environmentSpecularAlbedo(surface, NoV, specularModel);
#endif
}

vec4 radianceOut(vec3 value) { return vec4(min(finiteOrZero(value), vec3(u_maxRadiance)), 1.0); }

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (depth >= 1.0) {  // the background: emitted radiance, open
#if defined(TERM_AO)
        o_radiance = vec4(1.0);
#elif defined(TERM_DIRECT) || defined(TERM_INDIRECT_DIFFUSE) || defined(TERM_INDIRECT_SPECULAR)
        o_radiance = vec4(0.0, 0.0, 0.0, 1.0);
#else
        // Along the pixel's ray: unprojecting two depths serves perspective and orthographic alike.
        vec4 near = u_invViewProj * vec4(v_uv * 2.0 - 1.0, -1.0, 1.0);
        vec4 far = u_invViewProj * vec4(v_uv * 2.0 - 1.0, 0.0, 1.0);
        o_radiance = radianceOut(environmentBackground(far.xyz / far.w - near.xyz / near.w));
#endif
        return;
    }
    // Methods may work at a lower resolution: bilinear upsampling of their (already filtered) terms.
#if AO_INPUT
    float ao = texture(s_ao, v_uv).r;
#else
    const float ao = 1.0;
#endif
    vec4 world = u_invViewProj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 P = world.xyz / world.w;
    vec4 normalAndModels = texelFetch(s_gbufNormal, pixel, 0);
    vec3 N = normalize(normalAndModels.xyz);
    ivec2 models = decodeBrdfOverride(normalAndModels.w, u_brdfModels);  // a material may override them
    vec3 baseColor = texelFetch(s_gbufBaseColor, pixel, 0).rgb;
    vec4 material = texelFetch(s_gbufMaterial, pixel, 0);  // metallic, roughness, occlusion, specular
    vec3 emissive = texelFetch(s_gbufEmissive, pixel, 0).rgb;
    vec3 V = normalize(u_cameraPos - P);
    SurfaceBrdf surface = makeSurfaceBrdf(baseColor, material.x, material.y, material.w);
    // AO (material occlusion x the method's "ao") multiplies only the indirect terms, never direct light.
    float occlusion = material.z * ao;
    vec3 diffuse, specular;  // (a term view that does not use them compiles their reads away)
    indirectLight(surface, N, V, models.y, diffuse, specular);

#if defined(TERM_DIRECT)
    o_radiance = radianceOut(addDirectLight(vec3(0.0), surface, P, N, V, models, pixel));
#elif defined(TERM_INDIRECT_DIFFUSE)
    o_radiance = radianceOut(diffuse * occlusion);
#elif defined(TERM_INDIRECT_SPECULAR)
    o_radiance = radianceOut(specular * occlusion);
#elif defined(TERM_EMISSION)
    o_radiance = radianceOut(emissive);
#elif defined(TERM_AO)
    o_radiance = vec4(vec3(occlusion), 1.0);
#else
    vec3 radiance = addDirectLight(emissive, surface, P, N, V, models, pixel);
    o_radiance = radianceOut(radiance + (diffuse + specular) * occlusion);
#endif
}
