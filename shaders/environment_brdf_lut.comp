// The environment's split-sum table (environment_brdf.glsl): per (N.V, roughness), the directional
// albedo of brdf.glsl's GGX lobe with F0 = 1, F90 = 0 (A) and F0 = 0, F90 = 1 (B), since Schlick's
// Fresnel is linear in them. GGX half vectors importance-sampled with N fixed (Walter et al. 2007),
// a fixed Hammersley set so the table is the same every run.
#include "common.glsl"
#include "environment_brdf.glsl"
#include "sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = I_ENVIRONMENT_BRDF_TABLE, rg32f) uniform writeonly image2D u_table;

const uint SAMPLES = 1024u;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_table);
    if (texel.x >= size.x || texel.y >= size.y) return;
    vec2 p = environmentBrdfParameters((vec2(texel) + 0.5) / vec2(size));
    float NoV = p.x, roughness = p.y, alpha = roughness * roughness, a2 = alpha * alpha;
    vec3 N = vec3(0.0, 0.0, 1.0), V = vec3(sqrt(max(0.0, 1.0 - NoV * NoV)), 0.0, NoV);
    SurfaceBrdf f0Lobe, f90Lobe;
    f0Lobe.diffuseColor = f90Lobe.diffuseColor = vec3(0.0);
    f0Lobe.roughness = f90Lobe.roughness = roughness;
    f0Lobe.f0 = vec3(1.0), f0Lobe.f90 = 0.0;
    f90Lobe.f0 = vec3(0.0), f90Lobe.f90 = 1.0;
    vec2 sum = vec2(0.0);
    for (uint i = 0u; i < SAMPLES; ++i) {
        vec2 u = hammersley(i, SAMPLES);
        vec3 H = sampleGgxHalfVector(u, a2);
        float cosH = H.z;
        vec3 L = reflect(-V, H);
        float VoH = dot(V, H);
        if (L.z <= 0.0 || VoH <= 0.0) continue;
        float d = cosH * cosH * (a2 - 1.0) + 1.0;
        float pdf = a2 / (PI * d * d) * cosH / (4.0 * VoH);  // of L: D(h) cos(theta_h) / (4 V.H)
        sum.x += evaluateBrdfCosine(f0Lobe, N, V, L, DIFFUSE_LAMBERT, SPECULAR_GGX).r / pdf;
        sum.y += evaluateBrdfCosine(f90Lobe, N, V, L, DIFFUSE_LAMBERT, SPECULAR_GGX).r / pdf;
    }
    imageStore(u_table, texel, vec4(sum / float(SAMPLES), 0.0, 0.0));
}
