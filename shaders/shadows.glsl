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

// A directional light's map around the camera (the shadow pass's second layer for it, its box a
// part of the scene map's: light.viewCascade) serves the includer that defines SHADOW_CAMERA_MAP 1
// (the lighting pass: the pixels the camera sees); the others read the scene's map alone, which a
// camera move leaves as it is.
#ifndef SHADOW_CAMERA_MAP
#define SHADOW_CAMERA_MAP 0
#endif

// Where `p` falls in a 2D map: the scene's (camera false) or the camera's around it.
vec3 shadowMapCoordinates(GpuLight light, bool camera, vec3 p, out bool outside) {
    vec4 clip = light.shadowMatrix * vec4(p, 1.0);
    if (camera) clip.xy = clip.xy * light.viewCascade.xy + light.viewCascade.zw * clip.w;
    vec3 c = clip.xyz / max(clip.w, 1e-20) * 0.5 + 0.5;
    // Outside the map (or behind a spot light) nothing was rendered: lit.
    outside = clip.w <= 0.0 || any(lessThan(c, vec3(0.0))) || any(greaterThan(c, vec3(1.0)));
    return c;
}

// PCF taps lie in the receiver's tangent plane (T, B), one shadow texel apart, around P moved
// along the normal by the bias (returned): taps spread across the light's view instead would sink
// into a tilted receiver and shadow it (acne at grazing).
vec3 tapFrame(vec3 P, vec3 N, float texel, float NoL, out vec3 T, out vec3 B) {
    T = normalize(abs(N.y) < 0.99 ? cross(N, vec3(0.0, 1.0, 0.0)) : cross(N, vec3(1.0, 0.0, 0.0)));
    B = cross(N, T);
    return P + N * texel * SHADOW_NORMAL_OFFSET_TEXELS * (1.0 - 0.5 * NoL);
}

// The taps of a 2D map (directional or spot) at P, summed: `texel` its world size there, `layer`
// the map's.
float mapVisibility(GpuLight light, bool camera, int layer, float texel, vec3 P, vec3 N, float NoL, int radius) {
    vec3 T, B;
    vec3 Po = tapFrame(P, N, texel, NoL, T, B);
    float sum = 0.0;
    for (int i = -radius; i <= radius; ++i)
        for (int j = -radius; j <= radius; ++j) {
            bool outside;
            vec3 c = shadowMapCoordinates(light, camera, Po + (T * float(i) + B * float(j)) * texel, outside);
            sum += outside ? 1.0 : texture(s_shadowMaps, vec4(c.xy, float(layer), c.z));
        }
    return sum;
}

float shadowVisibility(GpuLight light, vec3 P, vec3 N, float NoL) {
    int layer = int(light.cone.z);
    if (u_shadowsEnabled == 0 || layer < 0) return 1.0;
    int type = int(light.positionType.w);
    float distance = type == LIGHT_DIRECTIONAL ? 0.0 : length(light.positionType.xyz - P);
    float texel = light.shadowParams.x + light.shadowParams.y * distance;

    // One loop per kind of map, each with a trip count the compiler cannot fold (u_shadowsEnabled
    // is 1 here). Unrolled under a per-tap branch on the light's type, llvmpipe evaluated both
    // kinds' lookups for every tap (it runs both sides of a branch it cannot prove uniform); this
    // way the other kind's loop ends after one masked pass: same image, the lighting pass ~20%
    // faster on cornell_point and the atrium (interleaved runs, docs/godot.md).
    int radius = PCF_RADIUS * u_shadowsEnabled;
    float taps = float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
    float sum = 0.0;
#if SHADOW_CUBES
    if (type == LIGHT_POINT) {
        vec3 T, B;
        vec3 Po = tapFrame(P, N, texel, NoL, T, B);
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
        // The share of the scene's map: 1 outside the camera's, falling to 0 across the camera
        // map's outer fifth, so the two maps' edges blend instead of meeting in a seam.
        float sceneShare = 1.0;
#if SHADOW_CAMERA_MAP
        if (type == LIGHT_DIRECTIONAL && light.viewCascade.x > 0.0) {
            bool outside;
            vec3 c = shadowMapCoordinates(light, true, P, outside);
            // Every tap of the camera's map inside it: the normal offset and the taps' reach.
            float reach = (float(PCF_RADIUS) + SHADOW_NORMAL_OFFSET_TEXELS + 1.0) / float(textureSize(s_shadowMaps, 0).x);
            float edge = max(abs(c.x - 0.5), abs(c.y - 0.5)) * 2.0, inner = 1.0 - 2.0 * reach;
            sceneShare = outside ? 1.0 : smoothstep(0.8 * inner, inner, edge);
            float cameraTexel = texel / max(light.viewCascade.x, light.viewCascade.y);
            if (sceneShare < 1.0)
                sum += (1.0 - sceneShare) * mapVisibility(light, true, layer + 1, cameraTexel, P, N, NoL, radius);
        }
#endif
        if (sceneShare > 0.0) sum += sceneShare * mapVisibility(light, false, layer, texel, P, N, NoL, radius);
    }
#endif
    return sum / taps;
}
