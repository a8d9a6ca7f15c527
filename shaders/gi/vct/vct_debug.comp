// VCT debug views. "vct.voxels": the grid ray-marched from the camera, showing the first voxel with
// occupancy >= 0.5 / 2^level at the chosen mip level (albedo and occupancy shaded by face). "vct.slice": one slice of the grid in the
// debug slices' frame (debug_slice.glsl). Channels: 0 albedo, 1 emission, 2 radiance, 3 occupancy. Albedo and emission exist at
// level 0 only; radiance and occupancy at every level of the radiance chain.
#include "common.glsl"
#include "debug_slice.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = VOLUME_ALBEDO_UNIT) uniform sampler3D s_albedo;
layout(binding = VOLUME_EMISSION_UNIT) uniform sampler3D s_emission;
layout(binding = VOLUME_RADIANCE_UNIT) uniform sampler3D s_radiance;
layout(rgba16f, binding = IC_DEBUG_VIEW) uniform writeonly image2D i_view;

layout(location = UV_WORLD_TO_VOXEL) uniform mat4 u_worldToVoxel;
layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
VctDebugBlock u_debug;

vec4 texelAt(ivec3 v, int channel, int level) {
    if (channel == 0) return level == 0 ? texelFetch(s_albedo, v, 0) : vec4(0.0);
    if (channel == 1) return level == 0 ? vec4(texelFetch(s_emission, v, 0).rgb, texelFetch(s_albedo, v, 0).a) : vec4(0.0);
    vec4 r = texelFetch(s_radiance, v, level);
    return channel == 2 ? vec4(r.a > 1e-6 ? r.rgb / r.a : vec3(0.0), r.a) : vec4(vec3(r.a), r.a);
}

// Albedo and occupancy are drawn lit by a light at the eye, so the voxels' shape reads: the face
// the ray entered voxel v through (of the axes along which it left the previous voxel, the one it
// crossed last; the ray's dominant axis where it started inside) at full value facing the eye,
// darker as it turns away. Emission and radiance are data and are drawn as they are.
float faceShade(ivec3 v, ivec3 previous, vec3 o, vec3 d) {
    vec3 a = abs(d);
    int axis = a.x > a.y && a.x > a.z ? 0 : (a.y > a.z ? 1 : 2);
    float last = -1e30;
    for (int i = 0; i < 3; ++i) {
        if (v[i] == previous[i] || a[i] < 1e-8) continue;
        float t = (float(d[i] > 0.0 ? v[i] : v[i] + 1) - o[i]) / d[i];
        if (t > last) last = t, axis = i;
    }
    return 0.4 + 0.6 * a[axis];
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_view);
    if (any(greaterThanEqual(pixel, size))) return;
    int channel = u_debug.channel, level = clamp(u_debug.level, 0, textureQueryLevels(s_radiance) - 1);
    int n = max(u_resolution >> level, 1);
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 result = vec4(0.0, 0.0, 0.0, 1.0);
    if (u_debug.sliceAxis >= 0) {
        int axis = u_debug.sliceAxis;
        float position = clamp(u_debug.slicePosition, 0.0, 1.0);
        vec2 st;
        if (slicePixel(pixel, size, axis, position, st, result.rgb)) {
            vec3 c = slicePoint(axis, position, st);
            result.rgb = texelAt(ivec3(min(c * float(n), vec3(n - 1))), channel, level).rgb;
        }
    } else {
        vec4 a = u_invViewProj * vec4(uv * 2.0 - 1.0, -1.0, 1.0), b = u_invViewProj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
        vec3 o = (u_worldToVoxel * vec4(a.xyz / a.w, 1.0)).xyz / float(1 << level);
        vec3 e = (u_worldToVoxel * vec4(b.xyz / b.w, 1.0)).xyz / float(1 << level);
        vec3 d = normalize(e - o);
        // Enter the grid's box, then step a quarter texel at a time.
        vec3 inv = 1.0 / max(abs(d), vec3(1e-8)) * sign(d + 1e-12);
        vec3 t0 = (vec3(0.0) - o) * inv, t1 = (vec3(float(n)) - o) * inv;
        float tIn = max(max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z)), 0.0);
        float tOut = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
        // A wall one finest voxel thick fills 1/2^level of a voxel at `level`: a fixed 0.5 showed
        // nothing of thin walls (a Cornell box) from level 1 on.
        float solid = 0.5 / float(1 << level);
        ivec3 previous = ivec3(floor(o + d * tIn));
        for (float t = tIn; t < tOut && t - tIn < 4.0 * float(n); t += 0.25) {
            ivec3 v = ivec3(floor(o + d * t));
            if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(n)))) continue;
            vec4 s = texelAt(v, channel, level);
            if (texelFetch(s_radiance, v, level).a >= solid || (level == 0 && texelFetch(s_albedo, v, 0).a > 0.0)) {
                result.rgb = channel == 0 || channel == 3 ? s.rgb * faceShade(v, previous, o, d) : s.rgb;
                break;
            }
            previous = v;
        }
    }
    imageStore(i_view, pixel, vec4(finiteOrZero(result.rgb), 1.0));
}
