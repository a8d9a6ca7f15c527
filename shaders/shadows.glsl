// Shadow-map visibility of a punctual light (shaders/lights.glsl) at a surface point, shared by the
// lighting pass and voxel light injection. The including shader declares, before this include,
// `sampler2DArrayShadow s_shadowMaps`, `sampler2DArrayShadow s_shadowCubes` (the shadow pass's
// "shadow.maps" and "shadow.cubes", the latter the cube faces as 2D layers, 6 per point light) and
// `int u_shadowsEnabled`.

// Receiver-side bias: move the lookup along the normal by a few shadow-map texels, more at grazing
// light, so a lit plane never shadows itself (acne) and contact shadows stay (little peter-panning).
const float SHADOW_NORMAL_OFFSET_TEXELS = 1.5;
// 3x3 taps, each a hardware 2x2 comparison (bilinear PCF): a soft edge about 4 texels wide. An
// includer whose lookups are averaged over many rays anyway may take one tap (SHADOW_PCF_RADIUS 0).
#ifndef SHADOW_PCF_RADIUS
#define SHADOW_PCF_RADIUS 1
#endif
const int PCF_RADIUS = SHADOW_PCF_RADIUS;
// The kinds of light the including shader meets: point (cube maps) and directional or spot (2D
// maps), both unless it says. The lighting pass compiles the mix the scene has, since on llvmpipe
// even a branch no pixel takes costs a masked pass through its loop (~12% of that pass).
#ifndef SHADOW_CUBES
#define SHADOW_CUBES 1
#endif
#ifndef SHADOW_MAPS
#define SHADOW_MAPS 1
#endif

// Where direction d meets the cube map: (s, t, face) by the GL's face selection (the major axis, then
// the face's own s and t axes; OpenGL 4.5 core, table 8.19), for the faces as 2D layers. A tap
// near an edge reads its own face's texels only (clamped), where the cube map filtered across the
// seam: a difference within a texel of the edges, inside the PCF taps.
vec3 cubeFaceCoordinates(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return vec3(0.5 * vec2(d.x > 0.0 ? -d.z : d.z, -d.y) / a.x + 0.5, d.x > 0.0 ? 0.0 : 1.0);
    if (a.y >= a.z) return vec3(0.5 * vec2(d.x, d.y > 0.0 ? d.z : -d.z) / a.y + 0.5, d.y > 0.0 ? 2.0 : 3.0);
    return vec3(0.5 * vec2(d.z > 0.0 ? d.x : -d.x, -d.y) / a.z + 0.5, d.z > 0.0 ? 4.0 : 5.0);
}

float shadowVisibility(GpuLight light, vec3 P, vec3 N, float NoL) {
    int layer = int(light.cone.z);
    if (u_shadowsEnabled == 0 || layer < 0) return 1.0;
    int type = int(light.positionType.w);
    float distance = type == LIGHT_DIRECTIONAL ? 0.0 : length(light.positionType.xyz - P);
    float texel = light.shadowParams.x + light.shadowParams.y * distance;
    vec3 Po = P + N * texel * SHADOW_NORMAL_OFFSET_TEXELS * (1.0 - 0.5 * NoL);
    // PCF taps lie in the receiver's tangent plane, one shadow texel apart: taps spread across
    // the light's view instead would sink into a tilted receiver and shadow it (acne at grazing).
    vec3 T = normalize(abs(N.y) < 0.99 ? cross(N, vec3(0.0, 1.0, 0.0)) : cross(N, vec3(1.0, 0.0, 0.0)));
    vec3 B = cross(N, T);

    // One loop per kind of map, each with a trip count the compiler cannot fold (u_shadowsEnabled
    // is 1 here). Unrolled under a per-tap branch on the light's type, llvmpipe evaluated both
    // kinds' lookups for every tap (it runs both sides of a branch it cannot prove uniform); this
    // way the other kind's loop ends after one masked pass: same image, the lighting pass ~20%
    // faster on cornell_point and the atrium (interleaved runs, docs/godot.md).
    int radius = PCF_RADIUS * u_shadowsEnabled;
    float sum = 0.0;
#if SHADOW_CUBES
    if (type == LIGHT_POINT) {
        // Compare with the depth the cube face's perspective projection stores: its view depth is
        // the distance along the dominant axis.
        float n = light.shadowParams.z, f = light.shadowParams.w;
        for (int i = -radius; i <= radius; ++i)
            for (int j = -radius; j <= radius; ++j) {
                vec3 d = Po + (T * float(i) + B * float(j)) * texel - light.positionType.xyz;
                vec3 ad = abs(d);
                float z = max(max(max(ad.x, ad.y), ad.z), n);
                float depth = ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * z)) * 0.5 + 0.5;
                vec3 face = cubeFaceCoordinates(d);
                sum += texture(s_shadowCubes, vec4(face.xy, float(layer * 6) + face.z, depth));
            }
    }
#endif
#if SHADOW_MAPS
    if (type != LIGHT_POINT) {
        for (int i = -radius; i <= radius; ++i)
            for (int j = -radius; j <= radius; ++j) {
                vec4 clip = light.shadowMatrix * vec4(Po + (T * float(i) + B * float(j)) * texel, 1.0);
                vec3 p = clip.xyz / max(clip.w, 1e-20) * 0.5 + 0.5;
                // Outside the map (or behind a spot light) nothing was rendered: lit.
                bool outside = clip.w <= 0.0 || any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(1.0)));
                sum += outside ? 1.0 : texture(s_shadowMaps, vec4(p.xy, float(layer), p.z));
            }
    }
#endif
    float taps = float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
    return sum / taps;
}
