// SDF GI's debug views, written into the frame-sized target:
//   0 sdf.slice:   one slice of the distance field (cascade sdf.slice-cascade, a layer of the
//                  field) in the debug slices' frame (debug_slice.glsl; axis, position 0..1),
//                  colour-mapped: blue-white outside, red-orange inside (negative), a band every
//                  cell, black on the zero level set;
//   1 sdf.steps:   the marcher's steps per diffuse ray as a heatmap (black 0 ... white max steps);
//   2 sdf.normals: the normal at the first diffuse ray's hit (* 0.5 + 0.5; black where it missed).
#include "common.glsl"
#include "debug_slice.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = VOLUME_DISTANCE_UNIT) uniform sampler3D s_distance;
layout(binding = TG_DEBUG_INFO) uniform sampler2D s_info;   // mean steps, first hit normal (traced resolution)
layout(rgba16f, binding = IG_DEBUG_TARGET) uniform writeonly image2D i_target;

layout(location = UG_VOLUME) uniform vec4 u_volume;
layout(location = UG_RESOLUTION) uniform int u_resolution;
SdfDebugBlock u_debug;
layout(location = UG_SLICE_CASCADE) uniform int u_layer;
layout(location = UG_SCALE) uniform int u_scale;   // full-resolution pixels per traced pixel

vec3 sliceColour(float d) {
    float cell = u_volume.w / float(u_resolution);
    float x = d / cell;                                  // in cells
    float band = 0.75 + 0.25 * cos(2.0 * PI * x);        // one band per cell
    float t = saturate(abs(x) / (0.5 * float(u_resolution)));
    vec3 outside = mix(vec3(0.85, 0.92, 1.0), vec3(0.05, 0.2, 0.7), t);
    vec3 inside = mix(vec3(1.0, 0.7, 0.3), vec3(0.6, 0.05, 0.02), t);
    vec3 c = (d >= 0.0 ? outside : inside) * band;
    return mix(vec3(0.0), c, smoothstep(0.05, 0.15, abs(x)));   // the zero level set in black
}

// Black - blue - red - yellow - white.
vec3 heat(float t) {
    t = saturate(t);
    vec3 c = mix(vec3(0.0), vec3(0.1, 0.2, 1.0), saturate(t * 4.0));
    c = mix(c, vec3(1.0, 0.1, 0.1), saturate(t * 4.0 - 1.0));
    c = mix(c, vec3(1.0, 0.9, 0.1), saturate(t * 4.0 - 2.0));
    return mix(c, vec3(1.0), saturate(t * 4.0 - 3.0));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(i_target);
    if (any(greaterThanEqual(pixel, size))) return;
    int view = u_debug.view;
    vec3 colour;
    if (view == 0) {
        int axis = u_debug.sliceAxis;
        vec2 st;
        if (slicePixel(pixel, size, axis, u_debug.slicePosition, st, colour)) {
            vec3 uvw = slicePoint(axis, u_debug.slicePosition, st);
            // The cascade's layer of the field (layers stack along z), clamped half a cell inside it.
            int layers = max(textureSize(s_distance, 0).z / u_resolution, 1);
            float halfCell = 0.5 / float(u_resolution);
            uvw.z = (float(u_layer) + clamp(uvw.z, halfCell, 1.0 - halfCell)) / float(layers);
            colour = sliceColour(textureLod(s_distance, uvw, 0.0).r);
        }
    } else {
        ivec2 traced = min(pixel / u_scale, textureSize(s_info, 0) - 1);
        vec4 info = texelFetch(s_info, traced, 0);
        colour = view == 1 ? heat(info.r / max(float(u_debug.maxSteps), 1.0)) : info.gba;
    }
    imageStore(i_target, pixel, vec4(colour, 1.0));
}
