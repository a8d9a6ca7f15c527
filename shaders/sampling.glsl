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
