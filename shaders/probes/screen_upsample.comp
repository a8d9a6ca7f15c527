// The screen gather's joint bilateral upsampling (gather scale 2 or 4): each full-resolution pixel
// blends the 4 gathered pixels around it by bilinear weight x how well their surface agrees with
// its own (distance from its tangent plane, relative to its distance from the eye, and normal
// agreement), so light does not cross a depth or normal edge. A pixel that no gathered neighbour
// agrees with (a silhouette, a thin object) gathers its own probes: edges cost a full gather and
// never leak. The probes' light is smooth, so away from edges the blend is what a full gather gives.
#include "probes/screen_gather.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TP_GATHERED) uniform sampler2D s_gathered;
layout(rgba16f, binding = IP_OUTPUT) uniform writeonly image2D i_diffuse;
layout(location = UP_GATHER_SCALE) uniform int u_scale;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(i_diffuse)))) return;
    GatherSurface s = gatherSurface(pixel);
    if (!s.valid) {
        imageStore(i_diffuse, pixel, vec4(0.0));
        return;
    }
    ivec2 coarse = textureSize(s_gathered, 0);
    // Gathered pixel q stands for full pixel q * scale: position p within the coarse grid.
    vec2 p = vec2(pixel) / float(u_scale);
    ivec2 q0 = ivec2(floor(p));
    vec2 f = p - vec2(q0);
    float planeScale = 0.01 * max(distance(s.position, u_cameraPos), 1e-30);
    vec4 sum = vec4(0.0);  // a: the share probes gave (screen_gather.glsl)
    float total = 0.0, best = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = min(q0 + ivec2(k & 1, k >> 1), coarse - 1);
        GatherSurface t = gatherSurface(q * u_scale);
        if (!t.valid) continue;
        vec2 b = mix(1.0 - f, f, vec2(k & 1, k >> 1));
        float plane = abs(dot(t.position - s.position, s.normal)) / planeScale;
        float agree = pow(saturate(dot(t.normal, s.normal)), 8.0);
        float alike = agree * (plane < 1.0 ? 1.0 - plane : 0.0);
        float w = (b.x * b.y + 1e-3) * alike;
        sum += w * texelFetch(s_gathered, q, 0);
        total += w;
        best = max(best, alike);
    }
    vec4 e = best >= 0.5 ? sum / total : gatherAt(s);
    imageStore(i_diffuse, pixel, vec4(finiteOrZero(e.rgb), e.a));
}
