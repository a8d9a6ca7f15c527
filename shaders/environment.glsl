// The radiance of rays that leave the scene (renderer/environment_gpu.h): a constant or an
// equirectangular map, bound once for every program by GpuEnvironment::bind(). The mapping is
// renderer/environment.h's, Blender's: +Y up, the top row the zenith, the centre column down +X
// (u = 0.5 + atan2(z, x) / 2pi), the map turned by u_env.rotation about +Y. Every reader goes
// through environmentUv or environmentDirectionAt, so the rotation turns them all alike.
// A constant environment returns its value exactly, with no texture read, so a constant is the
// same bits whichever function reads it.
#ifndef ENVIRONMENT_GLSL
#define ENVIRONMENT_GLSL
#include "common.glsl"

EnvironmentBlock u_env;  // renderer/environment_gpu.h
layout(binding = ENV_RADIANCE_UNIT) uniform sampler2D s_envRadiance;        // box-filtered mips
layout(binding = ENV_SPECULAR_UNIT) uniform sampler2D s_envSpecular;        // GGX-prefiltered levels
layout(binding = ENV_MARGINAL_UNIT) uniform sampler2D s_envMarginal;        // (height + 1) x 1
layout(binding = ENV_CONDITIONAL_UNIT) uniform sampler2D s_envConditional;  // (width + 1) x height

bool environmentIsMap() { return u_env.isMap != 0; }

// World direction d in the map's frame (environment.cpp's environmentToMap), and back.
vec3 environmentToMap(vec3 d) {
    float c = cos(u_env.rotation), s = sin(u_env.rotation);
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

vec3 environmentToWorld(vec3 m) {
    float c = cos(u_env.rotation), s = sin(u_env.rotation);
    return vec3(c * m.x + s * m.z, m.y, c * m.z - s * m.x);
}

vec2 environmentUv(vec3 d) {
    vec3 m = environmentToMap(normalize(d));
    float u = fract(atan(m.z, m.x) * (0.5 * INV_PI) + 0.5);  // fract: atan2 = pi lands on u = 0
    return vec2(u, acos(clamp(m.y, -1.0, 1.0)) * INV_PI);
}

// The world direction at column coordinate u and height cosTheta: environmentUv's inverse, and the
// importance sampler's (which draws cos(theta) uniformly inside a texel).
vec3 environmentDirectionAt(float u, float cosTheta) {
    float phi = (u - 0.5) * 2.0 * PI, s = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    return environmentToWorld(vec3(s * cos(phi), cosTheta, s * sin(phi)));
}

vec3 environmentDirection(vec2 uv) { return environmentDirectionAt(uv.x, cos(uv.y * PI)); }

// The level-0 texel direction d falls in.
ivec2 environmentTexel(vec3 d) {
    ivec2 size = ivec2(u_env.width, u_env.height);
    return clamp(ivec2(environmentUv(d) * vec2(size)), ivec2(0), size - 1);
}

// Radiance arriving along -d (d points away from the scene) as a light: the texel's value, constant
// over the texel as the importance sampler's density is (environmentPdf). Filtered between texels,
// a small sun would shine into neighbours the sampler never draws: a light drawn by that density
// (ReSTIR's candidates) would lose that part, up to half a one-texel sun's power, and a BSDF ray
// that found it would count it at full weight (the path tracer's fireflies).
vec3 environmentRadiance(vec3 d) {
    if (!environmentIsMap()) return u_env.constant.rgb;
    return texelFetch(s_envRadiance, environmentTexel(d), 0).rgb;
}

// What the camera sees of the environment: the map filtered between texels (a sky seen straight
// on is not a mosaic); the same total over the sphere as environmentRadiance.
vec3 environmentBackground(vec3 d) {
    if (!environmentIsMap()) return u_env.constant.rgb;
    return textureLod(s_envRadiance, environmentUv(d), 0.0).rgb;
}

// Mean radiance over a cone of solid angle `steradians` around d: the mip whose texels cover that
// much (each level weighs the finer texels by their solid angle, renderer/environment.h
// nextMipLevel; a mip texel is still a rectangle in the equirectangular domain, so near the poles
// it is narrower than the cone).
vec3 environmentCone(vec3 d, float steradians) {
    if (!environmentIsMap()) return u_env.constant.rgb;
    float lod = 0.5 * log2(max(steradians / u_env.texelSteradians, 1.0));
    return textureLod(s_envRadiance, environmentUv(d), lod).rgb;
}

// What a GI method's ray or cone that leaves the scene brings back: the environment, or black when
// the environment is a light of the direct pass (u_env.light, emitters.environment), which then
// gives the light it sends straight to a surface, with its shadows; the methods' volumes are lit
// by it through injection, so what they carry is its indirect light alone.
bool environmentIsDirectLight() { return u_env.light != 0; }
vec3 environmentMiss(vec3 d) { return environmentIsDirectLight() ? vec3(0.0) : environmentRadiance(d); }
vec3 environmentMissCone(vec3 d, float steradians) {
    return environmentIsDirectLight() ? vec3(0.0) : environmentCone(d, steradians);
}

// Solid angle of a cone of half-angle atan(tanHalf): 2 pi (1 - cos).
float coneSteradians(float tanHalf) { return 2.0 * PI * (1.0 - inversesqrt(1.0 + tanHalf * tanHalf)); }

// Irradiance E(n) from the SH9 projection, the cosine lobe's band weights pi, 2pi/3, pi/4
// (Ramamoorthi and Hanrahan 2001, eq. 8): environment.cpp's shIrradiance. A constant gives pi L.
vec3 environmentIrradiance(vec3 n) {
    if (!environmentIsMap()) return PI * u_env.constant.rgb;
    n = environmentToMap(normalize(n));  // the projection is the map's (environment.cpp's projectSh9)
    float b[9] = float[9](0.282095, 0.488603 * n.y, 0.488603 * n.z, 0.488603 * n.x, 1.092548 * n.x * n.y,
                          1.092548 * n.y * n.z, 0.315392 * (3.0 * n.z * n.z - 1.0), 1.092548 * n.x * n.z,
                          0.546274 * (n.x * n.x - n.y * n.y));
    float band[9] = float[9](PI, 2.0 * PI / 3.0, 2.0 * PI / 3.0, 2.0 * PI / 3.0, PI / 4.0, PI / 4.0, PI / 4.0,
                             PI / 4.0, PI / 4.0);
    vec3 e = vec3(0.0);
    for (int k = 0; k < 9; ++k) e += band[k] * b[k] * u_env.sh[k].rgb;
    return max(e, vec3(0.0));
}

// The split sum's first factor (Karis 2013): the radiance around the mirror direction R filtered
// by the GGX lobe of `roughness` (the prefiltered chain, one roughness per level).
vec3 environmentSpecular(vec3 R, float roughness) {
    if (!environmentIsMap()) return u_env.constant.rgb;
    float levels = float(textureQueryLevels(s_envSpecular));
    return textureLod(s_envSpecular, environmentUv(R), clamp(roughness, 0.0, 1.0) * (levels - 1.0)).rgb;
}

// Importance sampling by luminance x solid angle: environment.cpp's EnvironmentSampler on the
// GPU, read from its CDFs (PBRT 3rd ed. 13.6.7, 14.2.4). Uniform in solid angle inside a texel.

// The first i in [0, n) with cdf[i + 1] > target (std::upper_bound's, as environment.cpp).
int environmentInterval(sampler2D cdf, int row, int n, float target) {
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (texelFetch(cdf, ivec2(mid + 1, row), 0).r > target) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

float environmentRowSteradians(int y) {
    float h = float(u_env.height);
    return 2.0 * PI / float(u_env.width) * (cos(PI * float(y) / h) - cos(PI * float(y + 1) / h));
}

// Density per steradian of sampling texel (x, y): its weight over the total, spread evenly over it.
float environmentTexelPdf(int x, int y) {
    float w = texelFetch(s_envConditional, ivec2(x + 1, y), 0).r - texelFetch(s_envConditional, ivec2(x, y), 0).r;
    return w / (u_env.cdfTotal * environmentRowSteradians(y));
}

float environmentPdf(vec3 d) {
    ivec2 t = environmentTexel(d);
    return environmentTexelPdf(t.x, t.y);
}

// A direction drawn from the map's distribution and its pdf (per steradian). Maps only.
vec3 sampleEnvironment(vec2 u, out float pdf) {
    int w = u_env.width, h = u_env.height;
    float total = u_env.cdfTotal;
    int y = environmentInterval(s_envMarginal, 0, h, u.y * total);
    float rowStart = texelFetch(s_envMarginal, ivec2(y, 0), 0).r;
    float row = texelFetch(s_envMarginal, ivec2(y + 1, 0), 0).r - rowStart;
    int x = environmentInterval(s_envConditional, y, w, u.x * row);
    float c0 = texelFetch(s_envConditional, ivec2(x, y), 0).r, c1 = texelFetch(s_envConditional, ivec2(x + 1, y), 0).r;
    // Clear of the texel's edges, where rounding of the CDF would land in a neighbour of another pdf.
    const float EDGE = 1e-4;
    float fx = clamp(row > 0.0 ? (u.x * row - c0) / max(c1 - c0, 1e-30) : 0.5, EDGE, 1.0 - EDGE);
    float fy = clamp(row > 0.0 ? (u.y * total - rowStart) / row : 0.5, EDGE, 1.0 - EDGE);
    float z0 = cos(PI * float(y) / float(h)), z1 = cos(PI * float(y + 1) / float(h));
    pdf = environmentTexelPdf(x, y);
    return environmentDirectionAt((float(x) + fx) / float(w), mix(z0, z1, fy));
}

#endif
