// SDF GI temporal accumulation, per traced pixel: this frame's diffuse estimate blended into the
// history found by reprojecting the pixel's world position into the previous frame. The history
// is trusted only where the previous frame saw the same surface there: its stored distance from
// the previous camera must match this point's within 2% (else disocclusion: start again). The
// blend is a running mean: while the camera moves, of at most 1 / (1 - u_temporal.maxWeight) frames (an
// exponential average beyond, so lighting seen from a new angle catches up); while it stands still,
// of up to MAX_STATIC_FRAMES, so a static view keeps converging instead of flickering at the
// exponential average's noise floor.
#include "common.glsl"
#include "gi/sdf/sdf_gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TG_TEMPORAL_CURRENT) uniform sampler2D s_current;        // this frame's traced diffuse
layout(binding = TG_TEMPORAL_HISTORY) uniform sampler2D s_history;        // rgb, a = frames accumulated
layout(binding = TG_TEMPORAL_HISTORY_DISTANCE) uniform sampler2D s_historyDistance; // distance from the previous camera, -1 = none
layout(rgba16f, binding = IG_TEMPORAL_HISTORY) uniform writeonly image2D i_history;
layout(r32f, binding = IG_TEMPORAL_HISTORY_DISTANCE) uniform writeonly image2D i_historyDistance;

layout(location = UG_PREV_VIEW_PROJ) uniform mat4 u_prevViewProj;
SdfTemporalBlock u_temporal;

const float MAX_STATIC_FRAMES = 256.0;
layout(location = UG_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UG_PREV_CAMERA_POS) uniform vec3 u_prevCameraPos;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_history);
    if (any(greaterThanEqual(pixel, size))) return;
    Surface s = tracedSurface(pixel);
    vec3 current = texelFetch(s_current, pixel, 0).rgb;
    if (!s.valid) {
        imageStore(i_history, pixel, vec4(0.0));
        imageStore(i_historyDistance, pixel, vec4(-1.0));
        return;
    }
    vec4 result = vec4(current, 1.0);
    if (u_temporal.hasHistory != 0 && u_temporal.maxWeight > 0.0) {
        vec4 clip = u_prevViewProj * vec4(s.position, 1.0);
        if (clip.w > 0.0) {
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            // The traced pixel whose block holds the reprojected point.
            ivec2 full = ivec2(floor(uv * vec2(textureSize(s_depth, 0))));
            ivec2 previous = full / u_scale;
            if (all(greaterThanEqual(full, ivec2(0))) && all(lessThan(previous, size))) {
                float expected = distance(s.position, u_prevCameraPos);
                float stored = texelFetch(s_historyDistance, previous, 0).r;
                if (stored > 0.0 && abs(stored - expected) < 0.02 * expected) {
                    vec4 history = texelFetch(s_history, previous, 0);
                    float cap = u_temporal.cameraMoved != 0 ? 1.0 / (1.0 - u_temporal.maxWeight) : MAX_STATIC_FRAMES;
                    float frames = min(history.a + 1.0, cap);
                    result = vec4(mix(history.rgb, current, 1.0 / frames), frames);
                }
            }
        }
    }
    imageStore(i_history, pixel, vec4(finiteOrZero(result.rgb), result.a));
    imageStore(i_historyDistance, pixel, vec4(distance(s.position, u_cameraPos)));
}
