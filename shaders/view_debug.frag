// Debug displays: one G-buffer channel, or a grey data value (AO), made visible as display values
// (already sRGB-encoded where they are colours; data such as AO stays linear).
#include "common.glsl"

// Locations are this program's own (renderer/debug_view.cpp uses the same numbers).
#define CHANNEL_DEPTH 0
#define CHANNEL_NORMAL 1
#define CHANNEL_BASE_COLOR 2
#define CHANNEL_MATERIAL 3
#define CHANNEL_EMISSIVE 4
#define CHANNEL_GREY 5

layout(binding = T_DISPLAY_SOURCE) uniform sampler2D s_source;
layout(binding = T_DISPLAY_DEPTH) uniform sampler2D s_depth;
layout(location = U_DISPLAY_CHANNEL) uniform int u_channel;
layout(location = U_DISPLAY_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = U_DISPLAY_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = U_DISPLAY_MAX_DISTANCE) uniform float u_maxDistance;
layout(location = U_DISPLAY_HAS_DEPTH) uniform int u_hasDepth;  // 0: no G-buffer, every pixel is shown

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = u_hasDepth != 0 ? texelFetch(s_depth, pixel, 0).r : 0.0;
    if (u_channel == CHANNEL_GREY) {  // data, possibly at a lower resolution: filtered, 0 off geometry
        o_color = vec4(vec3(depth >= 1.0 ? 0.0 : texture(s_source, v_uv).r), 1.0);
        return;
    }
    if (depth >= 1.0) {  // nothing drawn: a dark grey that no channel produces on geometry
        o_color = vec4(0.1, 0.1, 0.12, 1.0);
        return;
    }
    vec4 t = texelFetch(s_source, pixel, 0);
    vec3 c;
    if (u_channel == CHANNEL_DEPTH) {
        // Distance from the camera, near = white, u_maxDistance (the far side of the scene) = black.
        vec4 world = u_invViewProj * vec4(v_uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
        float d = length(world.xyz / world.w - u_cameraPos);
        c = vec3(1.0 - saturate(d / max(u_maxDistance, 1e-20)));
    } else if (u_channel == CHANNEL_NORMAL) {
        c = normalize(t.xyz) * 0.5 + 0.5;             // world space, the usual colour coding
    } else if (u_channel == CHANNEL_BASE_COLOR) {
        c = linearToSrgb(t.rgb);                      // the sRGB target reads back linear
    } else if (u_channel == CHANNEL_MATERIAL) {
        c = saturate(t.rgb);                          // metallic, roughness, occlusion as R, G, B
    } else {
        vec3 e = max(finiteOrZero(t.rgb), vec3(0.0));
        c = linearToSrgb(e / (1.0 + e));              // emitted radiance, Reinhard-compressed
    }
    o_color = vec4(c, 1.0);
}
