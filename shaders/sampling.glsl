// Directions for Monte Carlo sampling, shared by the path tracer, ray-traced AO and SDF GI.
#include "common.glsl"

void orthonormalBasis(vec3 n, out vec3 t, out vec3 b) {
    // Duff et al. 2017, "Building an orthonormal basis, revisited".
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction around n (Malley's method: uniform on the disk, lifted).
vec3 cosineDirection(vec3 n, vec2 u) {
    vec3 t, b;
    orthonormalBasis(n, t, b);
    float r = sqrt(u.x), phi = 2.0 * PI * u.y;
    return t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(0.0, 1.0 - u.x));
}

// Uniform direction on the sphere (density 1 / 4 pi): z uniform in [-1, 1] (Archimedes).
vec3 uniformSphereDirection(vec2 u) {
    float z = 1.0 - 2.0 * u.x, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Hammersley point i of n: i / n and the radical inverse of i in base 2 (a low-discrepancy set for
// the prefiltering integrals, which must not flicker between runs).
vec2 hammersley(uint i, uint n) { return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10); }

// A GGX half vector around +Z (a2 = alpha^2) with density D(h) cos(theta_h) (Walter et al. 2007,
// eq. 35-36); z is cos(theta_h).
vec3 sampleGgxHalfVector(vec2 u, float a2) {
    float cosH = sqrt((1.0 - u.x) / (1.0 + (a2 - 1.0) * u.x)), sinH = sqrt(max(0.0, 1.0 - cosH * cosH));
    float phi = 2.0 * PI * u.y;
    return vec3(sinH * cos(phi), sinH * sin(phi), cosH);
}

// A value in [0, 1) per pixel whose neighbours differ as much as possible (interleaved gradient
// noise, Jimenez 2014, "Next generation post processing in Call of Duty: Advanced Warfare"): turning
// a few fixed directions by it makes their error a fine-grained noise instead of bands.
float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}
