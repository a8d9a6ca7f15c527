// HDDAGI's debug views. hddagi.occupancy: a slice of one cascade's occupancy at one level (voxel
// bits, blocks with any bit, region bits), letterboxed into the frame; white where occupied, grey
// grid lines at block edges. hddagi.steps: each pixel's camera ray walked through the cascades by
// HDDA (volume/hdda.glsl), its steps as a heat map.
#include "volume/hdda.glsl"
#include "debug_slice.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = IH_DEBUG_TARGET) uniform writeonly image2D i_target;
layout(location = UH_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UH_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UH_CASCADES) uniform vec4 u_cascades[SDF_MAX_CASCADES];
layout(location = UH_CASCADE_COUNT) uniform int u_cascadeCount;
layout(location = UH_RESOLUTION) uniform int u_resolution;
layout(location = UH_VIEW) uniform int u_view;
HddagiSliceBlock u_slice;
layout(location = UH_STEPS_MAX) uniform int u_stepsMax;

// Black, blue, green, red, white as x goes 0..1.
vec3 heat(float x) {
    x = clamp(x, 0.0, 1.0) * 4.0;
    if (x < 1.0) return vec3(0.0, 0.0, x);
    if (x < 2.0) return vec3(0.0, x - 1.0, 2.0 - x);
    if (x < 3.0) return vec3(x - 2.0, 3.0 - x, 0.0);
    return vec3(1.0, x - 3.0, x - 3.0);
}

vec3 occupancySlice(ivec2 pixel, ivec2 size) {
    int n = u_resolution, axis = u_slice.axis, cascade = u_slice.cascade, level = u_slice.level;
    vec2 uv;
    vec3 frame;
    if (!slicePixel(pixel, size, axis, u_slice.position, uv, frame)) return frame;
    ivec3 v = clamp(ivec3(slicePoint(axis, u_slice.position, uv) * float(n)), ivec3(0), ivec3(n - 1));
    bool occupied = level == 2 ? occRegionPresent(cascade, v, n)
                  : level == 1 ? occRegionPresent(cascade, v, n) && occBlockMask(cascade, v, n) != uvec2(0u)
                               : occVoxel(cascade, v, n);
    vec2 inCell = fract(uv * float(n) / float(OCC_BLOCK));
    bool edge = any(lessThan(inCell, vec2(0.5 * float(OCC_BLOCK) / float(min(size.x, size.y)))));
    return occupied ? vec3(1.0) : (edge ? vec3(0.15) : vec3(0.0));
}

vec3 traversalSteps(ivec2 pixel, ivec2 size) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 far = u_invViewProj * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - u_cameraPos);
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_resolution);
    float reach = 4.0 * u_cascades[u_cascadeCount - 1].w + length(u_cameraPos - u_cascades[u_cascadeCount - 1].xyz);
    HddaHit h = hddaTraceCascades(cs, u_cameraPos, dir, 0.0, reach, 4096);
    return heat(float(h.steps) / float(u_stepsMax));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_target);
    if (any(greaterThanEqual(pixel, size))) return;
    vec3 c = u_view == 0 ? occupancySlice(pixel, size) : traversalSteps(pixel, size);
    imageStore(i_target, pixel, vec4(c, 1.0));
}
