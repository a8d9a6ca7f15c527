// What the SDF GI shaders read of the G-buffer at a traced pixel: at a reduced trace scale, traced
// pixel q stands for full-resolution pixel q * u_scale (its block's top-left one), so the trace,
// the temporal pass and the filter all agree on which surface a traced pixel is.
#include "gbuffer_layout.glsl"

layout(binding = TG_DEPTH) uniform sampler2D s_depth;
layout(binding = TG_NORMAL) uniform sampler2D s_gbufNormal;

layout(location = UG_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UG_SCALE) uniform int u_scale;

struct Surface {
    bool valid;     // false: background
    vec3 position;  // world
    vec3 normal;
};

Surface surfaceAt(ivec2 fullPixel) {
    fullPixel = clamp(fullPixel, ivec2(0), textureSize(s_depth, 0) - 1);
    Surface s;
    s.valid = gbufferPosition(s_depth, u_invViewProj, fullPixel, s.position);
    vec3 n = texelFetch(s_gbufNormal, fullPixel, 0).xyz;
    s.normal = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    return s;
}

// The full-resolution pixel traced pixel q stands for: q * u_scale, the last traced row and column
// the frame's last pixel.
ivec2 tracedFullPixel(ivec2 tracedPixel) { return min(tracedPixel * u_scale, textureSize(s_depth, 0) - 1); }
Surface tracedSurface(ivec2 tracedPixel) { return surfaceAt(tracedFullPixel(tracedPixel)); }
