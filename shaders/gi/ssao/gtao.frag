// Ground-truth-based ambient occlusion (GTAO, Jimenez, Wu, Pesce and Jarabo 2016, "Practical
// Realtime Strategies for Accurate Indirect Occlusion"). The hemisphere around the view vector V is
// cut into u_slices planes through V at uniform angles about it (rotated per pixel by the noise
// tile). In each slice a march of `steps` depth-buffer texels per side finds the highest horizon
// within the AO radius; the cosine-weighted visibility between the two horizons is then integrated
// analytically against the normal projected into the slice (the paper's inner integral, eq. 10):
//   a(h) = (cos n + 2 h sin n - cos(2h - n)) / 4 per side,  slice visibility = |N_proj| (a(h0) + a(h1)),
// and the mean over slices is the cosine-weighted visibility the ray-traced reference estimates
// (the |N_proj| weight and the uniform slice angles make the outer integral cosine-correct),
// divided by what the same slices give unoccluded, so that an open plane is exactly 1. Samples
// farther than the radius from the shading point do not raise the horizon (the reference's rays
// end there: no halo around distant occluders); off-screen samples end the march on that side
// (nothing known: counted as open, as the hemisphere kernel leaves such directions out).
#include "gi/ssao/ssao_common.glsl"

layout(location = U_AO_KERNEL_SIZE) uniform int u_slices;   // this kernel's size: slices per pixel

in vec2 v_uv;
layout(location = 0) out vec4 o_ao;   // r = AO, g = view-space depth (for the bilateral blur)

// Normals this close to perpendicular to a slice add next to nothing there, and sliding samples
// back onto such a slice (below) would divide by almost 0: the slice is left out of both sums.
const float MIN_PROJECTED_NORMAL = 0.05;
// A sample's weight fades from 1 at the radius to 0 at this many radii: a few steps per side rarely
// land on the highest point within the radius, so a hard cut leaves the horizon low (Cornell box,
// 3 x 4 at 64x64: RMSE against ray-traced AO 0.129 with a hard cut, 0.109 with this fade).
const float FALLOFF_END = 1.5;

// A 4x4 ordered-dither (Bayer) matrix: per-pixel offsets of the march's first step that the blur
// over the same 4x4 tile averages out (with the slice rotation, 16 different slice/step patterns).
const float BAYER4[16] = float[](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);

// The highest horizon (as its cosine against V) on one side of a slice, starting from the
// tangent plane's, `lowCos`. Samples are whole texels along `dirPx` so each is a surface the
// depth buffer really holds (no interpolated depth across silhouettes).
float horizonCos(ivec2 pixel, vec2 dirPx, float radiusPx, int steps, float jitter, vec3 P, vec3 origin, vec3 V,
                 vec3 side, vec3 axis, vec3 slide, float radius, float lowCos) {
    ivec2 size = textureSize(s_depth, 0);
    float best = lowCos;
    for (int s = 0; s < steps; ++s) {
        // Linear spacing out to the radius (quadratic, denser near the centre, found the far
        // horizons too rarely: RMSE 0.138 against 0.129), at least one texel further per step.
        float t = (float(s) + jitter) / float(steps);
        float distPx = max(radiusPx * t, float(s + 1));
        ivec2 q = pixel + ivec2(round(dirPx * distPx));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) break;
        float depth = texelFetch(s_depth, q, 0).r;
        if (depth >= 1.0) continue;   // background: nothing there
        vec3 S = viewPosition((vec2(q) + 0.5) / vec2(size), depth);
        float weight = saturate((FALLOFF_END - distance(S, P) / radius) / (FALLOFF_END - 1.0));
        if (weight <= 0.0) continue;   // beyond the reference's rays
        // A whole-texel sample lies up to half a texel off the slice plane; slid back onto it
        // along the shading point's tangent plane, a sample on that plane stays on it (else the
        // offset shows as height: an open plane seen at a grazing angle was 7% occluded). Its
        // angle from V then comes from its two in-slice coordinates: a cosine alone cannot tell
        // an angle past pi (the far side of a plane seen at a grazing angle, whose tangent there
        // is almost -V) from one above the horizon.
        vec3 toS = S - origin;
        toS -= slide * dot(toS, axis);
        float x = dot(toS, V), y = dot(toS, side);
        if (y <= 0.0) continue;   // at or past -V: below any horizon on this side
        best = max(best, mix(lowCos, x * inversesqrt(x * x + y * y), weight));
    }
    return best;
}

// (cos n + 2 h sin n - cos(2h - n)) / 4: the cosine-weighted visibility from V to the horizon h
// in a slice whose projected normal makes the angle n with V (Jimenez et al. 2016, eq. 10).
float innerIntegral(float h, float n, float cosN, float sinN) { return 0.25 * (cosN + 2.0 * h * sinN - cos(2.0 * h - n)); }

void main() {
    ivec2 size = textureSize(s_depth, 0);
    // The depth texel this output pixel stands for (at half resolution, one of the four it covers):
    // every position below is an exact depth-buffer sample, so a plane is exactly a plane.
    ivec2 pixel = clamp(ivec2(v_uv * vec2(size)), ivec2(0), size - 1);
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (depth >= 1.0) {
        o_ao = vec4(1.0, -1e30, 0.0, 1.0);
        return;
    }
    vec3 P = viewPosition((vec2(pixel) + 0.5) / vec2(size), depth);
    vec3 N = normalize(mat3(u_view) * texelFetch(s_gbufNormal, pixel, 0).xyz);
    bool orthographic = u_proj[3][3] == 1.0;
    vec3 V = orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-P);

    float radius = max(u_aoRadius, 1e-30);
    // Horizons are measured from one bias above the surface, so depth round-off cannot lift a
    // sample of the same surface above its tangent plane (self-occlusion streaks).
    vec3 origin = P + N * (u_ao.bias * radius);
    // The radius in pixels at P's depth (clip w is -z in perspective, 1 in orthographic).
    float w = (u_proj * vec4(P, 1.0)).w;
    float radiusPx = radius * u_proj[1][1] * 0.5 * float(size.y) / max(w, 1e-30);
    int steps = max(u_ao.steps, 1);
    int slices = max(u_slices, 1);
    vec2 rotation = noiseRotation();
    float sliceOffset = atan(rotation.y, rotation.x) / (2.0 * PI) + 0.5;   // [0, 1]
    ivec2 cell = noiseCell();
    float jitter = (BAYER4[cell.y * 4 + cell.x] + 0.5) / 16.0;

    // A basis around V: slice planes at uniform angles about V make the outer integral exact
    // (screen directions at uniform angles would not, off the image centre: 4% error at 27 degrees).
    vec3 T1 = normalize(vec3(V.z, 0.0, -V.x));   // V is never +-y inside a frustum
    vec3 T2 = cross(V, T1);
    vec2 pixelScale = vec2(u_proj[0][0], u_proj[1][1]) * 0.5 * vec2(size);

    float visibility = 0.0, open = 0.0;
    for (int i = 0; i < slices; ++i) {
        float phi = (float(i) + sliceOffset) * PI / float(slices);
        vec3 orthoDir = cos(phi) * T1 + sin(phi) * T2;   // the slice's direction perpendicular to V
        vec3 axis = cross(orthoDir, V);
        // Where the slice runs on screen: the image of P + t orthoDir (d/dt of x/-z in perspective).
        vec2 dirPx = normalize((orthographic ? orthoDir.xy : orthoDir.xy * -P.z + P.xy * orthoDir.z) * pixelScale);
        vec3 projN = N - axis * dot(N, axis);
        float projLen = length(projN);
        if (projLen < MIN_PROJECTED_NORMAL) continue;
        float cosN = clamp(dot(projN, V) / projLen, -1.0, 1.0);
        float n = (dot(orthoDir, projN) < 0.0 ? -1.0 : 1.0) * acos(cosN);
        float sinN = sin(n);
        // The direction within N's tangent plane that moves a point across the slice by one unit.
        vec3 slide = (axis - N * dot(N, axis)) / (projLen * projLen);
        // Horizons start at the tangent plane (n +- pi/2): below it the cosine is 0 anyway.
        float cos1 = horizonCos(pixel, dirPx, radiusPx, steps, jitter, P, origin, V, orthoDir, axis, slide, radius, cos(n + 0.5 * PI));
        float cos0 = horizonCos(pixel, -dirPx, radiusPx, steps, jitter, P, origin, V, -orthoDir, axis, slide, radius, cos(n - 0.5 * PI));
        float h0 = n + max(-acos(clamp(cos0, -1.0, 1.0)) - n, -0.5 * PI);
        float h1 = n + min(acos(clamp(cos1, -1.0, 1.0)) - n, 0.5 * PI);
        visibility += projLen * (innerIntegral(h0, n, cosN, sinN) + innerIntegral(h1, n, cosN, sinN));
        // The same slice unoccluded (horizons at n -+ pi/2): cos n + n sin n.
        open += projLen * (cosN + n * sinN);
    }
    // The mean over slices of the open slices' value is 1 only as slices -> infinity: with a few,
    // at grazing angles it strays by 5%. Dividing by it (a ratio estimator) keeps an open
    // plane at exactly 1 with any slice count and converges to the same integral.
    float ao = open > 0.0 ? visibility / open : 1.0;
    o_ao = vec4(pow(saturate(ao), max(u_ao.power, 1e-3)), P.z, 0.0, 1.0);
}
