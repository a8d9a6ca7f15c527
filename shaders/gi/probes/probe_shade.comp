// Probe GI per pixel: the lighting contract's indirect.diffuse (E / pi) from the 8 probes around
// the shading point, moved off the surface along the normal and towards the eye (DDGI's bias, in
// units of the smallest probe step) so that a probe's distance moments do not shadow the very
// surface they were measured on.
#include "probes/probe_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 4) uniform sampler2D s_depth;
layout(binding = 5) uniform sampler2D s_gbufNormal;
layout(rgba16f, binding = 0) uniform writeonly image2D i_diffuse;
layout(location = UP_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UP_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UP_SHADE_PARAMS) uniform vec4 u_shadeParams;  // bias, intensity, visibility on, -

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_diffuse);
    if (any(greaterThanEqual(pixel, size))) return;
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (depth >= 1.0) {
        imageStore(i_diffuse, pixel, vec4(0.0));
        return;
    }
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 P = world.xyz / world.w;
    vec3 N = normalize(texelFetch(s_gbufNormal, pixel, 0).xyz);
    vec3 toEye = u_cameraPos - P;
    vec3 V = length(toEye) > 0.0 ? normalize(toEye) : N;
    float bias = u_shadeParams.x * gridMinStep(gridAt(P));
    vec3 e = sampleProbes(P + (0.2 * N + 0.8 * V) * bias, N, u_shadeParams.z > 0.5);
    imageStore(i_diffuse, pixel, vec4(finiteOrZero(e * u_shadeParams.y), 1.0));
}
