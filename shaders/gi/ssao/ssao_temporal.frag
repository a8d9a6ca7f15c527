// Temporal accumulation of SSAO: each pixel is reprojected into the previous frame; where the
// previous frame saw the same surface (view depth within tolerance) the history is blended with
// the new value (a running mean over up to u_temporal.maxFrames frames), elsewhere (disocclusion,
// off-screen) the history is dropped. With the noise rotating every frame, the mean converges to
// the noise-free AO.
#include "common.glsl"

layout(binding = TA_TEMPORAL_AO) uniform sampler2D s_ao;          // current (blurred) AO, g = view depth
layout(binding = TA_TEMPORAL_HISTORY) uniform sampler2D s_history;     // r = accumulated AO, g = view depth, b = frames
layout(binding = TA_TEMPORAL_DEPTH) uniform sampler2D s_depth;

layout(location = U_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = U_PREV_VIEW_PROJ) uniform mat4 u_prevViewProj;
SsaoTemporalBlock u_temporal;

in vec2 v_uv;
layout(location = 0) out vec4 o_history;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 current = texelFetch(s_ao, p, 0).rg;
    float depth = texture(s_depth, v_uv).r;
    if (depth >= 1.0 || u_temporal.hasHistory == 0) { o_history = vec4(current, 1.0, 1.0); return; }
    vec4 world = u_invViewProj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    world /= world.w;
    vec4 prevClip = u_prevViewProj * world;
    vec2 prevUv = prevClip.xy / prevClip.w * 0.5 + 0.5;
    float frames = 1.0;
    float ao = current.r;
    if (prevClip.w > 0.0 && all(greaterThanEqual(prevUv, vec2(0.0))) && all(lessThanEqual(prevUv, vec2(1.0)))) {
        vec3 history = texelFetch(s_history, ivec2(prevUv * vec2(textureSize(s_history, 0))), 0).rgb;
        // The same surface: its view depth then equals the reprojected point's (w of the previous clip).
        if (abs(history.g) > 0.0 && abs(-history.g - prevClip.w) <= u_temporal.depthTolerance * prevClip.w) {
            frames = min(history.b + 1.0, u_temporal.maxFrames);
            ao = mix(history.r, current.r, 1.0 / frames);
        }
    }
    o_history = vec4(ao, current.g, frames, 1.0);
}
