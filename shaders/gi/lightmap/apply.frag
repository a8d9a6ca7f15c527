// indirect.diffuse from the lightmap, on the surfaces the G-buffer sees: single-sided faces seen
// from behind are culled there, so they are left out here too. The lookup is bilinear over the
// texels with light of their own (filter.comp's alpha 1) that the nearest texel reaches
// (classify.comp's flags): a texel inside a wall or across it never lends its light. Where the
// nearest texel is itself inside a wall (a pixel beside the wall's foot), its flags cannot say
// which side the pixel is on: the taps are then those a ray from the pixel reaches. Where no tap
// is left (a chart's border), the dilated gutter's light is used. Two programs: RAY_FALLBACK 0
// shades every pixel without rays (llvmpipe pays for the ray code in every pixel, taken or not:
// 4 ms of 12 at 256x256 on cornell_point), RAY_FALLBACK 1, drawn after it, only those pixels. The
// alpha-masked surfaces get a third (CUTOUTS 1, every pixel of theirs): the G-buffer saw through
// their holes, so a fragment of theirs away from the G-buffer's point there is left out before it
// writes depth (no early tests: a discarded fragment would have hidden the surface behind it).
#include "gi/lightmap/lightmap_texels.glsl"
#if RAY_FALLBACK
#include "ray_scene.glsl"
#endif

// Against (a copy of) the G-buffer's depth before shading: the pixels behind cost nothing.
#if !CUTOUTS
layout(early_fragment_tests) in;
#else
layout(binding = TL_GBUFFER_DEPTH) uniform sampler2D s_gbufferDepth;
layout(location = UL_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
#endif

in vec3 v_uvLayer;
in vec3 v_world;
in vec3 v_normal;
flat in float v_doubleSided;

layout(binding = TL_LIGHTMAP) uniform sampler2DArray s_lightmap;
layout(binding = TL_TEXELS) uniform sampler2DArray s_texels;    // position, w = 1 + flags
layout(location = UL_MODE) uniform int u_mode;  // 0 the light, 1 lightmap.texels' checker, 2 lightmap.seams
layout(location = UL_STEP) uniform int u_side;  // the atlas array's side, texels
layout(location = UL_TEXEL_SIZE) uniform float u_texelSize;
layout(location = UL_DIRECTIONAL) uniform int u_directional;  // lightmap.directional
layout(binding = TL_DIRECTION) uniform sampler2DArray s_direction;  // the light's mean direction, |d| <= 1
layout(binding = TL_SHADING_NORMAL) uniform sampler2D s_shadingNormal;  // the G-buffer's (normal maps)
layout(location = 0) out vec4 o_indirect;

// As classify.comp's rays: a twentieth of a texel above the surface.
const float LIFT = 0.05;

bool reaches(vec3 from, vec3 to) {
#if RAY_FALLBACK
    vec3 d = to - from;
    float distance = length(d);
    Hit hit;
    return !(distance > 0.0) || !traceRay(from, d / distance, distance, true, false, hit);
#else
    return true;  // not asked: such pixels are the fallback program's
#endif
}

vec3 lightmapLight(vec2 uv, int layer, out vec3 direction) {
    vec2 st = uv * float(u_side) - 0.5;
    ivec2 corner = ivec2(floor(st));
    vec2 f = st - floor(st);
    ivec2 toNearest = ivec2(greaterThanEqual(f, vec2(0.5)));
    ivec2 nearest = corner + toNearest;
    int flags = texelFlags(texelFetch(s_texels, ivec3(clamp(nearest, ivec2(0), ivec2(u_side - 1)), layer), 0).w);
    bool nearestInside = (flags & TEXEL_INSIDE) != 0;
#if RAY_FALLBACK && !CUTOUTS
    if (!nearestInside) discard;  // shaded by the first program
#endif
    // The taps across a column (row) from the nearest lie one step along x (y) from it: whether
    // that step is blocked is one bit of its flags, the same for both taps.
    bvec2 acrossBlocked = bvec2((flags & neighbourBit(ivec2(1 - 2 * toNearest.x, 0))) != 0,
                                (flags & neighbourBit(ivec2(0, 1 - 2 * toNearest.y))) != 0);
#if !RAY_FALLBACK
    // Most pixels: every tap has light of its own and none is across a blocked step, so the
    // filtering unit's bilinear sample is the answer (alpha 1 only where all four taps' is).
    vec4 filtered = texture(s_lightmap, vec3(uv, float(layer)));
    if (filtered.a >= 0.9999 && !any(acrossBlocked)) {
        direction = u_directional != 0 ? texture(s_direction, vec3(uv, float(layer))).xyz : vec3(0.0);
        return filtered.rgb;
    }
#endif
    vec3 n = dot(v_normal, v_normal) > 0.0 ? normalize(v_normal) : vec3(0.0);
    vec3 pixel = v_world + n * (LIFT * u_texelSize);
    vec4 own = vec4(0.0), any = vec4(0.0);
    vec3 ownDirection = vec3(0.0), anyDirection = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 offset = ivec2(k & 1, k >> 1);
        ivec3 tap = ivec3(clamp(corner + offset, ivec2(0), ivec2(u_side - 1)), layer);
        vec4 light = texelFetch(s_lightmap, tap, 0);
        float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
        bvec2 across = notEqual(offset, toNearest);
        bool blocked = (across.x && acrossBlocked.x) || (across.y && acrossBlocked.y);
#if RAY_FALLBACK
        if (nearestInside) blocked = !reaches(pixel, texelFetch(s_texels, tap, 0).xyz + n * (LIFT * u_texelSize));
#endif
        vec3 d = u_directional != 0 ? texelFetch(s_direction, tap, 0).xyz : vec3(0.0);
        if (light.a == 1.0 && !blocked) own += vec4(light.rgb, 1.0) * w, ownDirection += d * w;
        if (light.a > 0.0) any += vec4(light.rgb, 1.0) * w, anyDirection += d * w;
    }
    direction = own.w > 0.0 ? ownDirection / own.w : any.w > 0.0 ? anyDirection / any.w : vec3(0.0);
    if (own.w > 0.0) return own.rgb / own.w;
    return any.w > 0.0 ? any.rgb / any.w : vec3(0.0);
}

// Directional lightmaps: the irradiance towards the shading normal `m` over that towards the
// surface's normal `n`, from a first-order spherical-harmonic fit of the radiance. The bake keeps
// the irradiance E (over pi) and the luminance-weighted mean direction d of the light arriving
// about n (both cosine-weighted moments: stable under cosine sampling). Radiance a + b.w over n's
// hemisphere (none below it) has exactly those two moments for a = 9 - 12 d.n,
// b = 4 (d - (d.n) n) + (18 d.n - 12) n (per unit of E); its projection on the sphere's first two
// bands convolved with the clamped cosine (Ramamoorthi and Hanrahan 2001: pi and 2 pi / 3) gives the
// irradiance towards any m. Exact at m = n; uniform light gives (1 + n.m) / 2 and light from along n
// the cosine to it, light from elsewhere what a first-order fit can hold (a light 60 degrees off n
// reads 1.41 for m tilted 30 degrees towards it, where the cosine gives 1.73).
float directionalFactor(vec3 d, vec3 n, vec3 m) {
    float dn = dot(d, n);
    float a = 9.0 - 12.0 * dn;
    vec3 b = 4.0 * (d - dn * n) + (18.0 * dn - 12.0) * n;
    float towardsM = 0.25 * (2.0 * a + dot(b, n)) + 0.5 * a * dot(n, m) + dot(b, m) / 3.0;
    float towardsN = 2.0 - 1.5 * dn;  // the same at m = n
    return towardsN > 1e-4 ? clamp(towardsM / towardsN, 0.0, 4.0) : 1.0;
}

// Whether the pixel's bilinear footprint reaches a texel on no chart (the gutter): a chart's edge,
// where two charts of one surface meet in the image and a seam would show.
bool atChartEdge(vec2 uv, int layer) {
    ivec2 corner = ivec2(floor(uv * float(u_side) - 0.5));
    for (int k = 0; k < 4; ++k) {
        ivec3 tap = ivec3(clamp(corner + ivec2(k & 1, k >> 1), ivec2(0), ivec2(u_side - 1)), layer);
        if (!texelOnChart(texelFetch(s_texels, tap, 0).w)) return true;
    }
    return false;
}

void main() {
    if (!gl_FrontFacing && v_doubleSided < 0.5) discard;
#if CUTOUTS
    // The G-buffer's point in this pixel: a fragment more than half a texel from it lies in a hole.
    vec2 ndc = gl_FragCoord.xy / vec2(textureSize(s_gbufferDepth, 0)) * 2.0 - 1.0;
    float depth = texelFetch(s_gbufferDepth, ivec2(gl_FragCoord.xy), 0).r * 2.0 - 1.0;
    vec4 seen = u_invViewProj * vec4(ndc, depth, 1.0);
    if (!(distance(seen.xyz / seen.w, v_world) <= 0.5 * u_texelSize)) discard;
#endif
    int layer = int(v_uvLayer.z + 0.5);
    vec3 direction;
    vec3 light = lightmapLight(v_uvLayer.xy, layer, direction);
    // (The back of a double-sided face keeps the plain light: the direction was baked about its front.)
    if (u_directional != 0 && u_mode == 0 && gl_FrontFacing) {
        vec3 m = texelFetch(s_shadingNormal, ivec2(gl_FragCoord.xy), 0).xyz;
        vec3 n = dot(v_normal, v_normal) > 0.0 ? normalize(v_normal) : m;
        if (dot(m, m) > 0.0) light *= directionalFactor(direction, n, normalize(m));
    }
    float peak = max(max(light.r, max(light.g, light.b)), 1e-30);
    if (u_mode == 1) {
        vec2 texel = floor(v_uvLayer.xy * float(u_side));
        float square = mod(texel.x + texel.y, 2.0) < 0.5 ? 0.25 : 0.75;
        light = square * (0.5 + 0.5 * light / peak);
    } else if (u_mode == 2) {  // the surfaces' light in grey, the charts' edges in magenta
        light = atChartEdge(v_uvLayer.xy, layer) ? vec3(1.0, 0.0, 1.0)
                                                  : vec3(0.25 + 0.5 * dot(light / peak, vec3(1.0 / 3.0)));
    }
    o_indirect = vec4(light, 1.0);
}
