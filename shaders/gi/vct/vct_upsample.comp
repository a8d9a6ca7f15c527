// VCT at a trace scale above 1, per full-resolution pixel: this frame's traced texels brought to
// full resolution and gathered with the reprojected history of earlier frames.
//   - The pixel a texel traced this frame (the jitter's pixel of its block) takes that texel: an
//     exact sample, the full-resolution trace's own value.
//   - Another pixel keeps its history when the previous frame saw the same surface there (its
//     stored distance from the previous camera within 2% of this point's, normals agreeing) and
//     the history holds an exact sample; else it takes a joint bilateral upsample of the traced
//     texels around it.
// Cones are deterministic, so one exact sample per pixel is the converged result: a static view
// reaches the full-resolution image after one frame per jitter phase. Alpha of the diffuse output
// says what a pixel holds: 2 an exact sample of this view, 1 an exact sample reprojected from an
// earlier view (the camera moved since), 0 an upsampled estimate.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = TC_UPSAMPLE_DEPTH) uniform sampler2D s_depth;
layout(binding = TC_UPSAMPLE_NORMAL) uniform sampler2D s_gbufNormal;
layout(binding = TC_UPSAMPLE_TRACED_DIFFUSE) uniform sampler2D s_tracedDiffuse;
layout(binding = TC_UPSAMPLE_TRACED_SPECULAR) uniform sampler2D s_tracedSpecular;
layout(binding = TC_UPSAMPLE_HISTORY_DIFFUSE) uniform sampler2D s_historyDiffuse;
layout(binding = TC_UPSAMPLE_HISTORY_SPECULAR) uniform sampler2D s_historySpecular;
layout(binding = TC_UPSAMPLE_HISTORY_GEOMETRY) uniform sampler2D s_historyGeometry;  // normal, distance from that frame's camera (-1: none)
layout(rgba16f, binding = IC_UPSAMPLE_DIFFUSE) uniform writeonly image2D i_diffuse;
layout(rgba16f, binding = IC_UPSAMPLE_SPECULAR) uniform writeonly image2D i_specular;
layout(rgba16f, binding = IC_UPSAMPLE_GEOMETRY) uniform writeonly image2D i_geometry;

layout(location = UV_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UV_CAMERA_POS) uniform vec3 u_cameraPos;
layout(location = UV_TRACE_JITTER) uniform ivec3 u_traceJitter;  // pixels per texel, this frame's pixel in the block
layout(location = UV_PREV_VIEW_PROJ) uniform mat4 u_prevViewProj;
layout(location = UV_PREV_CAMERA_POS) uniform vec3 u_prevCameraPos;
layout(location = UV_HISTORY) uniform ivec2 u_history;  // history valid, camera moved
#include "gi/vct/vct_surface.glsl"

// The full-resolution pixel traced texel `texel` stands for this frame.
ivec2 tracedPixel(ivec2 texel) {
    return min(texel * u_traceJitter.x + u_traceJitter.yz, textureSize(s_depth, 0) - 1);
}

// Joint bilateral upsample: the 3x3 traced texels nearest the pixel, each weighted by its
// distance in pixels, by how far its surface lies off the pixel's tangent plane relative to the
// pixel's depth, and by the normals' agreement. Where no texel is on the pixel's surface (a
// feature thinner than a texel) the one nearest the tangent plane stands in.
void upsample(ivec2 pixel, Surface s, out vec3 diffuse, out vec3 specular) {
    int scale = u_traceJitter.x;
    ivec2 centre = (pixel - u_traceJitter.yz + scale / 2) / scale;
    ivec2 texels = textureSize(s_tracedDiffuse, 0);
    float depth = distance(s.position, u_cameraPos);
    vec4 sumD = vec4(0.0), sumS = vec4(0.0);
    float bestOff = 1e30;
    ivec2 best = clamp(centre, ivec2(0), texels - 1);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 t = centre + ivec2(dx, dy);
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, texels))) continue;
            ivec2 q = tracedPixel(t);
            Surface o = surfaceAt(q);
            if (!o.valid) continue;
            float off = abs(dot(o.position - s.position, s.normal)) / depth;
            if (off < bestOff) {
                bestOff = off;
                best = t;
            }
            vec2 d = vec2(q - pixel) / float(scale);
            float w = exp(-dot(d, d)) * surfaceWeight(s, o, u_cameraPos);
            sumD += w * vec4(texelFetch(s_tracedDiffuse, t, 0).rgb, 1.0);
            sumS += w * vec4(texelFetch(s_tracedSpecular, t, 0).rgb, 1.0);
        }
    if (sumD.w > 1e-4) {
        diffuse = sumD.rgb / sumD.w;
        specular = sumS.rgb / sumS.w;
    } else {
        diffuse = texelFetch(s_tracedDiffuse, best, 0).rgb;
        specular = texelFetch(s_tracedSpecular, best, 0).rgb;
    }
}

// The previous frame's value at this surface point, or false where it saw another surface there
// or held no exact sample.
bool history(Surface s, out vec4 diffuse, out vec3 specular) {
    if (u_history.x == 0) return false;
    vec4 clip = u_prevViewProj * vec4(s.position, 1.0);
    if (clip.w <= 0.0) return false;
    ivec2 size = textureSize(s_depth, 0);
    ivec2 previous = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
    if (any(lessThan(previous, ivec2(0))) || any(greaterThanEqual(previous, size))) return false;
    vec4 geometry = texelFetch(s_historyGeometry, previous, 0);
    float expected = distance(s.position, u_prevCameraPos);
    if (geometry.w <= 0.0 || abs(geometry.w - expected) > 0.02 * expected || dot(geometry.xyz, s.normal) < 0.9)
        return false;
    diffuse = texelFetch(s_historyDiffuse, previous, 0);
    specular = texelFetch(s_historySpecular, previous, 0).rgb;
    return diffuse.a > 0.5;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_diffuse);
    if (any(greaterThanEqual(pixel, size))) return;
    Surface s = surfaceAt(pixel);
    if (!s.valid) {
        imageStore(i_diffuse, pixel, vec4(0.0));
        imageStore(i_specular, pixel, vec4(0.0));
        imageStore(i_geometry, pixel, vec4(0.0, 0.0, 0.0, -1.0));
        return;
    }
    ivec2 texel = (pixel - u_traceJitter.yz) / u_traceJitter.x;
    vec4 diffuse;
    vec3 specular;
    if (all(greaterThanEqual(pixel, u_traceJitter.yz)) && tracedPixel(texel) == pixel) {
        diffuse = vec4(texelFetch(s_tracedDiffuse, texel, 0).rgb, 2.0);
        specular = texelFetch(s_tracedSpecular, texel, 0).rgb;
    } else if (history(s, diffuse, specular)) {
        if (u_history.y != 0) diffuse.a = 1.0;
    } else {
        upsample(pixel, s, diffuse.rgb, specular);
        diffuse.a = 0.0;
    }
    imageStore(i_diffuse, pixel, diffuse);
    imageStore(i_specular, pixel, vec4(specular, 1.0));
    imageStore(i_geometry, pixel, vec4(s.normal, distance(s.position, u_cameraPos)));
}
