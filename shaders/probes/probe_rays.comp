// Debug view probes.rays: the rays of one probe (probes.debug-probe) from its last update, drawn
// as one-pixel lines from the probe to the hit (or out of the volume for a miss), coloured by the
// radiance the ray brought back, hidden behind nearer G-buffer surfaces. Lines are found per pixel
// by projecting each segment: NDC depth is linear in screen space, so the depth test interpolates
// it directly.
#include "probes/probe_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = SP_RAYS) readonly buffer Rays { vec4 rayResults[]; };
layout(binding = TP_GATHER_DEPTH) uniform sampler2D s_depth;
layout(rgba16f, binding = IP_OUTPUT) uniform writeonly image2D i_target;
layout(location = UP_VIEW_PROJ) uniform mat4 u_viewProj;
layout(location = UP_RAYS) uniform int u_rays;
layout(location = UP_BATCH_SLOT) uniform int u_slot;   // the probe's slot in the last batch, -1: none
layout(location = UP_ROTATION) uniform mat3 u_rotation;
layout(location = UP_MODE) uniform int u_probe;

// Pixel position and NDC depth of p; w <= 0 (behind the eye) in .w.
vec4 project(vec3 p, vec2 size) {
    vec4 c = u_viewProj * vec4(p, 1.0);
    if (c.w <= 1e-6) return vec4(0.0, 0.0, 0.0, -1.0);
    vec3 ndc = c.xyz / c.w;
    return vec4((ndc.xy * 0.5 + 0.5) * size, ndc.z, 1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_target);
    if (any(greaterThanEqual(pixel, size))) return;
    vec2 centre = vec2(pixel) + 0.5;
    float surface = texelFetch(s_depth, pixel, 0).r * 2.0 - 1.0;
    vec3 colour = vec3(0.0);
    float nearest = 2.0;
    if (u_slot >= 0) {
        vec3 o = probePosition(u_probe);
        vec4 a = project(o, vec2(size));
        for (int r = 0; r < u_rays && a.w > 0.0; ++r) {
            vec4 ray = rayResults[u_slot * u_rays + r];
            vec4 b = project(o + normalize(u_rotation * fibonacciDirection(r, u_rays)) * ray.w, vec2(size));
            if (b.w <= 0.0) continue;
            vec2 ab = b.xy - a.xy;
            float t = clamp(dot(centre - a.xy, ab) / max(dot(ab, ab), 1e-12), 0.0, 1.0);
            if (length(centre - (a.xy + t * ab)) > 0.75) continue;
            float z = mix(a.z, b.z, t);
            if (z > surface + 1e-4 || z >= nearest) continue;
            nearest = z;
            colour = ray.rgb;
        }
    }
    imageStore(i_target, pixel, vec4(finiteOrZero(colour), 1.0));
}
