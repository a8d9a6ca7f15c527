// The sky rays' noise filtered out of VCT's full-resolution diffuse term (vct.sky-rays): each pixel
// becomes the mean of the 5x5 pixels around it that lie on its surface (surfaceWeight). The rays
// of neighbouring pixels are turned apart by interleaved gradient noise, so the window holds many
// different directions of one surface's sky (interleaved sampling, Keller and Heidrich 2001); the
// voxels' part of the term is smooth and passes almost unchanged.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TC_SKY_FILTER_DEPTH) uniform sampler2D s_depth;
layout(binding = TC_SKY_FILTER_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TC_SKY_FILTER_DIFFUSE) uniform sampler2D s_diffuse;
layout(rgba16f, binding = IC_SKY_FILTER_OUTPUT) uniform writeonly image2D i_filtered;

layout(location = UV_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UV_CAMERA_POS) uniform vec3 u_cameraPos;
#include "gi/vct/vct_surface.glsl"

const int RADIUS = 2;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_filtered);
    if (any(greaterThanEqual(pixel, size))) return;
    vec4 own = texelFetch(s_diffuse, pixel, 0);
    Surface s = surfaceAt(pixel);
    if (!s.valid) {
        imageStore(i_filtered, pixel, own);
        return;
    }
    vec4 sum = vec4(own.rgb, 1.0);
    for (int dy = -RADIUS; dy <= RADIUS; ++dy)
        for (int dx = -RADIUS; dx <= RADIUS; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            Surface o = surfaceAt(q);
            if (!o.valid) continue;
            sum += surfaceWeight(s, o, u_cameraPos) * vec4(texelFetch(s_diffuse, q, 0).rgb, 1.0);
        }
    imageStore(i_filtered, pixel, vec4(sum.rgb / sum.w, own.a));
}
