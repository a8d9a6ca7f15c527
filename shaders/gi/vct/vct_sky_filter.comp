// The sky rays' noise filtered out of VCT's traced diffuse term (vct.sky-rays): each traced texel
// becomes the mean of the 5x5 texels around it that lie on its surface (surfaceWeight). The rays
// of neighbouring pixels are turned apart by interleaved gradient noise, so the window holds many
// different directions of one surface's sky (interleaved sampling, Keller and Heidrich 2001); the
// voxels' part of the term is smooth and passes almost unchanged.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_gbufNormal;
layout(binding = 2) uniform sampler2D s_traced;
layout(rgba16f, binding = 0) uniform writeonly image2D i_filtered;

layout(location = UV_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UV_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UV_TRACE_JITTER) uniform ivec3 u_traceJitter;  // pixels per texel, this frame's pixel in the block
#include "gi/vct/vct_surface.glsl"

const int RADIUS = 2;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 texels = imageSize(i_filtered);
    if (any(greaterThanEqual(texel, texels))) return;
    vec4 own = texelFetch(s_traced, texel, 0);
    Surface s = surfaceAt(tracedPixel(texel));
    if (!s.valid) {
        imageStore(i_filtered, texel, own);
        return;
    }
    vec4 sum = vec4(own.rgb, 1.0);
    for (int dy = -RADIUS; dy <= RADIUS; ++dy)
        for (int dx = -RADIUS; dx <= RADIUS; ++dx) {
            ivec2 t = texel + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, texels))) continue;
            Surface o = surfaceAt(tracedPixel(t));
            if (!o.valid) continue;
            float w = surfaceWeight(s, o, u_cameraPos);
            sum += w * vec4(texelFetch(s_traced, t, 0).rgb, 1.0);
        }
    imageStore(i_filtered, texel, vec4(sum.rgb / sum.w, own.a));
}
