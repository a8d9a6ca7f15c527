// Debug views probes.spheres (u_mode 0): every probe as a small sphere showing its irradiance
// (E / pi) in the direction of the sphere's normal there, over the G-buffer's depth (nearer
// surfaces hide it); switched-off probes dark red, relocated ones with a blue rim. probes.state
// (u_mode 1): the same spheres flat-coloured by state: green active, blue relocated, red off.
#include "probes/probe_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TP_GATHER_DEPTH) uniform sampler2D s_depth;
layout(rgba16f, binding = IP_OUTPUT) uniform writeonly image2D i_target;
layout(location = UP_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UP_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UP_SPHERE_RADIUS) uniform float u_sphereRadius;
layout(location = UP_MODE) uniform int u_mode;

vec3 stateColour(float state) {
    return state > 1.5 ? vec3(1.0, 0.1, 0.1) : (state > 0.5 ? vec3(0.2, 0.4, 1.0) : vec3(0.1, 1.0, 0.2));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_target);
    if (any(greaterThanEqual(pixel, size))) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 far = u_invViewProj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - u_cameraPos);
    float depth = texelFetch(s_depth, pixel, 0).r;
    vec4 surface = u_invViewProj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
    float tMax = depth >= 1.0 ? 1e30 : length(surface.xyz / surface.w - u_cameraPos);
    float r = u_sphereRadius, best = tMax;
    vec3 colour = vec3(0.0);
    int n = min(probeCount(), 65536);
    for (int i = 0; i < n; ++i) {
        vec3 oc = u_cameraPos - probePosition(i);
        float b = dot(oc, dir), c = dot(oc, oc) - r * r, disc = b * b - c;
        if (disc < 0.0) continue;
        float t = -b - sqrt(disc);
        if (t <= 0.0 || t >= best) continue;
        best = t;
        vec3 normal = normalize(oc + dir * t);
        float state = probeState[2 * i].w;
        if (u_mode == 1) {
            colour = stateColour(state) * (0.4 + 0.6 * max(dot(normal, -dir), 0.0));
            continue;
        }
        colour = state > 1.5 ? vec3(0.3, 0.0, 0.0) : probeIrradianceOverPi(i, normal);
        if (state > 0.5 && state < 1.5 && dot(normal, -dir) < 0.4) colour = vec3(0.0, 0.2, 1.0);
    }
    imageStore(i_target, pixel, vec4(finiteOrZero(colour), 1.0));
}
