// What the SDF GI shaders read of the G-buffer at a traced pixel: with half-resolution tracing,
// traced pixel q stands for full-resolution pixel q * u_scale (its top-left one), so the trace,
// the temporal pass and the filter all agree on which surface a traced pixel is.
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
    ivec2 size = textureSize(s_depth, 0);
    fullPixel = clamp(fullPixel, ivec2(0), size - 1);
    float depth = texelFetch(s_depth, fullPixel, 0).r;
    Surface s;
    s.valid = depth < 1.0;
    vec2 uv = (vec2(fullPixel) + 0.5) / vec2(size);
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    s.position = world.xyz / world.w;
    vec3 n = texelFetch(s_gbufNormal, fullPixel, 0).xyz;
    s.normal = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    return s;
}

Surface tracedSurface(ivec2 tracedPixel) { return surfaceAt(tracedPixel * u_scale); }
