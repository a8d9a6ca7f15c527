// SDF GI's edge-aware spatial filter, per full-resolution pixel, over the traced pixels around it,
// each weighted by how well its surface agrees with this one - distance from this pixel's tangent
// plane and normal similarity - so light does not bleed across edges. Two footprints:
//   - sdf.filter-radius >= 1: a Gaussian over the (2r+1)^2 traced pixels around the pixel's own
//     (at a reduced trace scale also the upsampling), which smooths the per-pixel rays' noise;
//   - sdf.filter-radius 0: no blur, a joint bilateral upsample of the 2x2 traced pixels around the
//     pixel (bilinear weights by where they stand); with SDFGI's probes, whose light is smooth, that
//     is all the gathered diffuse needs. Light crosses an edge only at a pixel no traced neighbour
//     agrees with (a sliver thinner than a traced pixel), and then from at most one traced pixel
//     away. (Gathering such a pixel's own probes here was tried: the gather's code made every
//     pixel's filter about a third slower on llvmpipe, though few pixels ran it.)
// Writes the lighting contract's terms: indirect.diffuse, indirect.specular (the mirror ray
// blended towards the diffuse as roughness rises) and ao.
#include "common.glsl"
#include "gi/sdf/sdf_gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TG_FILTER_DIFFUSE) uniform sampler2D s_diffuse;      // traced resolution: probes' gather, or the rays' history
layout(binding = TG_FILTER_REFLECTION) uniform sampler2D s_reflection;   // rgb, a = weight against diffuse
layout(binding = TG_FILTER_OCCLUSION) uniform sampler2D s_occlusion;
layout(rgba16f, binding = IG_FILTER_DIFFUSE) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = IG_FILTER_SPECULAR) uniform writeonly image2D i_specular;
layout(r16f, binding = IG_FILTER_AO) uniform writeonly image2D i_ao;

layout(location = UG_FILTER) uniform int u_radius;
layout(location = UG_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UG_INTENSITY) uniform float u_intensity;

// The weighted sums over the taps.
struct Taps {
    vec3 diffuse, reflection;
    float ao, total, reflectionWeight, reflectionTotal;
};

// How alike traced surface t is to this pixel's s (1: the same plane and normal). Plane distances
// are compared to `planeScale` (1% of the distance from the camera): the tolerance follows the
// depth resolution, so the filter behaves the same at any scene scale.
float agreement(Surface s, Surface t, float planeScale) {
    if (!t.valid) return 0.0;
    float plane = abs(dot(t.position - s.position, s.normal)) / planeScale;
    return exp(-plane) * pow(saturate(dot(t.normal, s.normal)), 16.0);
}

void addTap(inout Taps t, ivec2 q, float w, bool reflection) {
    if (w < 1e-6) return;
    t.diffuse += w * texelFetch(s_diffuse, q, 0).rgb;
    t.ao += w * texelFetch(s_occlusion, q, 0).r;
    t.total += w;
    if (reflection) {
        vec4 m = texelFetch(s_reflection, q, 0);
        t.reflection += w * m.a * m.rgb;   // pixels without a mirror ray have a = 0
        t.reflectionWeight += w * m.a;
        t.reflectionTotal += w;
    }
}

// The Gaussian footprint: (2r+1)^2 traced pixels around the pixel's own; the mirror ray is sharp,
// so only the nearest ring smooths it.
Taps gaussianTaps(ivec2 pixel, Surface s, float planeScale, ivec2 tracedSize) {
    Taps t = Taps(vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0);
    ivec2 centre = min(pixel / u_scale, tracedSize - 1);
    float sigma = max(float(u_radius), 0.5) * 0.6;
    int r = max(u_radius, u_scale > 1 ? 1 : 0);
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            ivec2 q = centre + ivec2(x, y);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, tracedSize))) continue;
            float w = exp(-float(x * x + y * y) / (2.0 * sigma * sigma)) * agreement(s, tracedSurface(q), planeScale);
            addTap(t, q, w, abs(x) <= 1 && abs(y) <= 1);
        }
    return t;
}

// The upsampling footprint: the 2x2 traced pixels around the pixel, bilinear weights by the
// full-resolution pixels they stand for (tracedFullPixel).
Taps bilinearTaps(ivec2 pixel, Surface s, float planeScale, ivec2 tracedSize) {
    Taps t = Taps(vec3(0.0), vec3(0.0), 0.0, 0.0, 0.0, 0.0);
    ivec2 q0 = min(pixel / u_scale, tracedSize - 2);
    vec2 lo = vec2(tracedFullPixel(q0)), hi = vec2(tracedFullPixel(q0 + 1));
    vec2 f = clamp((vec2(pixel) - lo) / max(hi - lo, vec2(1.0)), 0.0, 1.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 corner = ivec2(k & 1, k >> 1);
        ivec2 q = min(q0 + corner, tracedSize - 1);
        vec2 b = mix(1.0 - f, f, vec2(corner));
        addTap(t, q, (b.x * b.y + 1e-3) * agreement(s, tracedSurface(q), planeScale), true);
    }
    return t;
}

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
    float planeScale = 0.01 * max(distance(s.position, u_cameraPos), 1e-30);
    Taps t = u_radius == 0 && u_scale > 1 ? bilinearTaps(pixel, s, planeScale, tracedSize) : gaussianTaps(pixel, s, planeScale, tracedSize);
    if (t.total <= 0.0) {  // nothing alike nearby (a one-pixel sliver): take the nearest traced pixel
        ivec2 centre = min(pixel / u_scale, tracedSize - 1);
        t.diffuse = texelFetch(s_diffuse, centre, 0).rgb;
        t.ao = texelFetch(s_occlusion, centre, 0).r;
        t.total = 1.0;
    }
    vec3 diffuse = t.diffuse / t.total;
    vec3 specular = diffuse;
    if (t.reflectionWeight > 0.0) {
        float a = saturate(t.reflectionWeight / t.reflectionTotal);
        specular = mix(diffuse, t.reflection / t.reflectionWeight, a);
    }
    imageStore(i_diffuse, pixel, vec4(finiteOrZero(diffuse * u_intensity), 1.0));
    imageStore(i_specular, pixel, vec4(finiteOrZero(specular * u_intensity), 1.0));
    imageStore(i_ao, pixel, vec4(saturate(t.ao / t.total)));
}
