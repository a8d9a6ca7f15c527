// The screen gather of a probe field (renderer/probes/screen_gather.h) at one full-resolution
// pixel: the lighting contract's indirect.diffuse (E / pi) from the 8 probes around the shading
// point (in the finest grid that holds it), moved off the surface along the normal and towards
// the eye (DDGI's bias, in units of the smallest probe step) so that a probe's distance moments do
// not shadow the very surface they were measured on. Shared by the gather at the traced
// resolution (screen_gather.comp) and the upsampling's fall-back (screen_upsample.comp). Alpha:
// the share of the pixel's light that probes gave (0 where none sees it).
#include "gbuffer_layout.glsl"
#define PROBE_SEGMENT_TEST 1
#include "probes/probe_common.glsl"
#include "probes/probe_tracer.glsl"

layout(binding = TP_GATHER_DEPTH) uniform sampler2D s_depth;
layout(binding = TP_GATHER_NORMAL) uniform sampler2D s_gbufNormal;
layout(location = UP_INV_VIEW_PROJ) uniform mat4 u_invViewProj;
layout(location = UP_CAMERA_POS) uniform vec3 u_cameraPos;
ProbeGatherBlock u_gather;

struct GatherSurface {
    bool valid;     // false: background
    vec3 position;  // world
    vec3 normal;
};

GatherSurface gatherSurface(ivec2 pixel) {
    pixel = clamp(pixel, ivec2(0), textureSize(s_depth, 0) - 1);
    GatherSurface s;
    s.valid = gbufferPosition(s_depth, u_invViewProj, pixel, s.position);
    s.normal = normalize(texelFetch(s_gbufNormal, pixel, 0).xyz);
    return s;
}

// E / pi, and in a whether any probe counted (0: none sees the point; the screen reflection's rays
// light it, screen_reflection.comp).
vec4 gatherAt(GatherSurface s) {
    vec4 e = sampleProbesSeenFrom(s.position, s.normal, u_cameraPos, u_gather.normalBias, u_gather.visibility);
    return vec4(finiteOrZero(e.rgb * u_gather.intensity), e.a);
}
