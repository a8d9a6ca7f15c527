// Ray-traced ambient occlusion, the ground truth for SSAO: from the surface each pixel sees,
// cosine-distributed rays around the shading normal; AO = the fraction that travels u_aoRadius
// without hitting anything, i.e. (1/pi) * integral of V(w) cos(theta) over the hemisphere, the
// same quantity as Cycles' AO pass (1 = open, background = 0). One sample per pixel per dispatch.
#include "common.glsl"
#include "random.glsl"
#include "ray_scene.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = I_ACCUMULATION_SUM, rgba32f) uniform image2D u_accumulation;
layout(binding = I_ACCUMULATION_MEAN, rgba32f) uniform writeonly image2D u_output;

layout(location = U_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = U_SAMPLE_INDEX) uniform uint u_sampleIndex;
layout(location = U_SEED) uniform uint u_seed;
layout(location = U_AO_RADIUS) uniform float u_aoRadius;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_output);
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    Rng rng = makeRng(uvec2(pixel), u_sampleIndex, u_seed);
    vec2 ndc = (vec2(pixel) + nextFloat2(rng)) / vec2(size) * 2.0 - 1.0;  // box-filtered pixel
    vec4 near = u_invViewProj * vec4(ndc, -1.0, 1.0);
    vec4 far = u_invViewProj * vec4(ndc, 0.0, 1.0);
    vec3 origin = near.xyz / near.w;
    vec3 dir = normalize(far.xyz / far.w - origin);

    float visibility = 0.0;
    Hit hit;
    if (traceRay(origin, dir, 1e30, false, true, hit)) {  // culls as the G-buffer does
        RayHitGeometry g = hitGeometry(hit, dir);
        vec3 w = cosineDirection(g.normal, nextFloat2(rng));
        // A direction below the geometric surface (possible with interpolated or mapped normals)
        // goes into the surface itself: occluded.
        if (dot(w, g.geometricNormal) > 0.0) {
            Hit occluder;
            visibility = traceRay(offsetRayOrigin(g.position, g.geometricNormal), w, u_aoRadius, true, occluder) ? 0.0 : 1.0;
        }
    }
    vec4 sum = u_sampleIndex == 0u ? vec4(0.0) : imageLoad(u_accumulation, pixel);
    sum += vec4(vec3(visibility), 1.0);
    imageStore(u_accumulation, pixel, sum);
    imageStore(u_output, pixel, vec4(sum.rgb / sum.w, 1.0));
}
