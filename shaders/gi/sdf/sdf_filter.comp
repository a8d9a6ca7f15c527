// SDF GI's edge-aware spatial filter, per full-resolution pixel: a Gaussian over the traced
// pixels around it (joint bilateral upsampling when tracing at half resolution), each weighted by
// how well its surface agrees with this one - distance from this pixel's tangent plane and normal
// similarity - so light does not bleed across edges. Writes the lighting contract's terms:
// indirect.diffuse, indirect.specular (the mirror ray blended towards the diffuse as roughness
// rises) and ao. With SDFGI's probes the diffuse term filtered is the probes' gathered at the
// traced pixels (sdf_trace.comp), so joint bilateral upsampling spreads it too.
#include "common.glsl"
#include "gi/sdf/sdf_gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 2) uniform sampler2D s_diffuse;      // temporally accumulated, traced resolution
layout(binding = 3) uniform sampler2D s_reflection;   // rgb, a = weight against diffuse
layout(binding = 4) uniform sampler2D s_occlusion;
layout(rgba16f, binding = 0) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = 1) uniform writeonly image2D i_specular;
layout(r16f, binding = 2) uniform writeonly image2D i_ao;

layout(location = UG_FILTER) uniform int u_radius;
layout(location = UG_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UG_INTENSITY) uniform float u_intensity;
void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(i_diffuse)))) return;
    Surface s = surfaceAt(pixel);
    if (!s.valid) {
        imageStore(i_diffuse, pixel, vec4(0.0));
        imageStore(i_specular, pixel, vec4(0.0));
        imageStore(i_ao, pixel, vec4(1.0));
        return;
    }
    ivec2 tracedSize = textureSize(s_diffuse, 0);
    ivec2 centre = min(pixel / u_scale, tracedSize - 1);
    // Plane distances are compared to 1% of the distance from the camera: the tolerance follows
    // the depth resolution, so the filter behaves the same at any scene scale.
    float planeScale = 0.01 * max(distance(s.position, u_cameraPos), 1e-30);
    float sigma = max(float(u_radius), 0.5) * 0.6;
    vec3 diffuse = vec3(0.0), reflection = vec3(0.0);
    float total = 0.0, reflectionTotal = 0.0, reflectionWeight = 0.0, ao = 0.0;
    int r = max(u_radius, u_scale > 1 ? 1 : 0);
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            ivec2 q = centre + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, tracedSize))) continue;
            Surface t = tracedSurface(q);
            if (!t.valid) continue;
            float plane = abs(dot(t.position - s.position, s.normal)) / planeScale;
            float w = exp(-float(x * x + y * y) / (2.0 * sigma * sigma)) * exp(-plane) *
                      pow(saturate(dot(t.normal, s.normal)), 16.0);
            if (w < 1e-6) continue;
            diffuse += w * texelFetch(s_diffuse, q, 0).rgb;
            ao += w * texelFetch(s_occlusion, q, 0).r;
            total += w;
            // The mirror ray is sharp: only the nearest ring smooths it.
            if (abs(x) <= 1 && abs(y) <= 1) {
                vec4 m = texelFetch(s_reflection, q, 0);
                reflection += w * m.a * m.rgb;   // pixels without a mirror ray have a = 0
                reflectionWeight += w * m.a;
                reflectionTotal += w;
            }
        }
    if (total <= 0.0) {  // nothing alike nearby (a one-pixel sliver): take the nearest traced pixel
        diffuse = texelFetch(s_diffuse, centre, 0).rgb;
        ao = texelFetch(s_occlusion, centre, 0).r;
        total = 1.0;
    }
    diffuse /= total;
    vec3 specular = diffuse;
    if (reflectionWeight > 0.0) {
        float a = saturate(reflectionWeight / reflectionTotal);
        specular = mix(diffuse, reflection / reflectionWeight, a);
    }
    imageStore(i_diffuse, pixel, vec4(finiteOrZero(diffuse * u_intensity), 1.0));
    imageStore(i_specular, pixel, vec4(finiteOrZero(specular * u_intensity), 1.0));
    imageStore(i_ao, pixel, vec4(saturate(ao / total)));
}
