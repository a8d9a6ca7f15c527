// Test harness for sdf_march.glsl: marches a list of rays through a field and writes what the
// marcher returned (tests/volume/test_march.cpp). Not used by the renderer.
#include "volume/sdf_march.glsl"

layout(local_size_x = 64) in;

struct ProbeRay {
    vec4 origin;     // xyz, w = max distance
    vec4 direction;  // xyz (normalized), w unused
};
layout(std430, binding = SF_MARCH_PROBE_RAYS) readonly buffer Rays { ProbeRay rays[]; };
// Two vec4 per ray: position + hit (1 + cascade, 0 = miss), normal + steps.
layout(std430, binding = SF_MARCH_PROBE_HITS) writeonly buffer Hits { vec4 hits[]; };
layout(binding = TF_MARCH_PROBE_DISTANCE) uniform sampler3D s_distance;
layout(binding = TF_MARCH_PROBE_COARSE) uniform sampler3D s_coarse;

layout(location = 0) uniform uint u_count;
layout(location = 1) uniform vec4 u_volume;   // origin xyz, size
layout(location = 2) uniform int u_resolution;
SdfMarchBlock u_march;
layout(location = 4) uniform int u_cascadeCount;   // 0: one volume (u_volume); else the cascades below
layout(location = 5) uniform vec4 u_cascades[SDF_MAX_CASCADES];   // origin xyz, edge; finest first

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    SdfVolume vol = SdfVolume(u_volume.xyz, u_volume.w, u_resolution);
    SdfMarchParams p = sdfDefaultParams(rays[i].origin.w);
    p.hitThreshold = u_march.hitThreshold;
    p.relaxation = u_march.relaxation;
    p.maxSteps = u_march.maxSteps;
    p.startOffset = u_march.offset;
    SdfHit h = u_cascadeCount > 0
        ? sdfMarchCascades(s_distance, s_coarse, SdfCascades(u_cascades, u_cascadeCount, u_resolution),
                           rays[i].origin.xyz, rays[i].direction.xyz, p)
        : sdfMarch(s_distance, s_coarse, vol, rays[i].origin.xyz, rays[i].direction.xyz, p);
    // hit: 1 + the cascade it was found in; 0 for a miss
    hits[2 * i] = vec4(h.position, h.hit ? 1.0 + float(h.cascade) : 0.0);
    hits[2 * i + 1] = vec4(h.normal, float(h.steps));
}
