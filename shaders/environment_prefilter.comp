// One level of the environment's prefiltered specular chain (renderer/environment_gpu.cpp): each
// texel the radiance around its direction R weighted by a GGX lobe of the level's roughness, with
// N = V = R as the split sum assumes (Karis 2013, "Real Shading in Unreal Engine 4"). The lobe is
// importance-sampled and each sample reads the radiance's mip whose texels cover the solid angle
// the sample stands for, so few samples give a smooth result (Colbert and Krivanek 2007, "GPU-Based
// Importance Sampling", GPU Gems 3 ch. 20).
#include "common.glsl"
#include "sampling.glsl"
#include "environment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = I_ENVIRONMENT_PREFILTER_LEVEL, rgba32f) uniform writeonly image2D u_level;
layout(location = U_ENV_ROUGHNESS) uniform float u_roughness;

const uint SAMPLES = 256u;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_level);
    if (texel.x >= size.x || texel.y >= size.y) return;
    vec3 R = environmentDirection((vec2(texel) + 0.5) / vec2(size));
    // The project's GGX convention (brdf.glsl): alpha = roughness^2. Roughness 0 is a mirror.
    float alpha = max(u_roughness * u_roughness, 1e-4);
    if (u_roughness == 0.0) {
        imageStore(u_level, texel, vec4(environmentCone(R, 4.0 * PI / float(size.x * size.y)), 1.0));
        return;
    }
    vec3 t, b;
    orthonormalBasis(R, t, b);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < SAMPLES; ++i) {
        vec2 u = hammersley(i, SAMPLES);
        float a2 = alpha * alpha;
        vec3 h = sampleGgxHalfVector(u, a2);
        float cosH = h.z;
        vec3 H = t * h.x + b * h.y + R * cosH;
        vec3 L = reflect(-R, H);
        float NoL = dot(R, L);
        if (NoL <= 0.0) continue;
        float d = (cosH * cosH * (a2 - 1.0) + 1.0);
        float D = a2 / (PI * d * d);
        float pdf = D / 4.0;  // of L, with N = V: D cos(theta_h) / (4 V.H) and V.H = N.H
        sum += environmentCone(L, 1.0 / (float(SAMPLES) * pdf)) * NoL;
        weight += NoL;
    }
    imageStore(u_level, texel, vec4(sum / max(weight, 1e-8), 1.0));
}
