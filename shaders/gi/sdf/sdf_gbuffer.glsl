// What the SDF GI shaders read of the G-buffer at a traced pixel: with half-resolution tracing,
// traced pixel q stands for full-resolution pixel q * u_scale (its top-left one), so the trace,
// the temporal pass and the filter all agree on which surface a traced pixel is.
#include "gbuffer_layout.glsl"

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_gbufNormal;

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

Surface tracedSurface(ivec2 tracedPixel) { return surfaceAt(tracedPixel * u_scale); }
