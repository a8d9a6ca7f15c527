// The screen gather per traced pixel (screen_gather.glsl): at gather scale 1 every pixel, else the
// top-left pixel of each scale x scale block, which screen_upsample.comp then spreads.
#include "probes/screen_gather.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = IP_OUTPUT) uniform writeonly image2D i_diffuse;
layout(location = UP_GATHER_SCALE) uniform int u_scale;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(i_diffuse)))) return;
    GatherSurface s = gatherSurface(pixel * u_scale);
    imageStore(i_diffuse, pixel, s.valid ? gatherAt(s) : vec4(0.0));
}
