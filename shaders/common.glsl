// Constants and small helpers shared by every shader.
const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;

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

// Replaces NaN and Inf with 0 so one bad sample cannot poison a blur, a mip chain or a mean.
vec3 finiteOrZero(vec3 c) {
    bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
    return mix(c, vec3(0.0), bad);
}
