// Constants and small helpers shared by every shader.
const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;

// Rec. 709 / sRGB primaries' luminance weights.
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

float saturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 saturate(vec3 x) { return clamp(x, vec3(0.0), vec3(1.0)); }

// sRGB transfer function (IEC 61966-2-1), linear -> encoded.
vec3 linearToSrgb(vec3 c) {
    c = saturate(c);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// sRGB transfer function, encoded -> linear.
vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

#ifdef COUNT_NONFINITE
// Bound by the renderer at this pass's own counter (renderer/nonfinite_counter.h).
layout(std430, binding = NONFINITE_BINDING) coherent buffer NonFiniteCount { uint u_nonFiniteCount; };
#endif

// Replaces NaN and Inf with 0 so one bad sample cannot poison a blur, a mip chain or a mean; with
// GIS_CHECK_FINITE=1 it counts each replacement, so that tests see the bug it hides.
vec3 finiteOrZero(vec3 c) {
    bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
#ifdef COUNT_NONFINITE
    if (any(bad)) atomicAdd(u_nonFiniteCount, 1u);
#endif
    return mix(c, vec3(0.0), bad);
}
