// Test harness for hdda.glsl: traces a list of rays through the occupancy hierarchy's cascades and
// writes what the traversal returned (tests/volume/test_hdda.cpp). Not used by the renderer.
#include "volume/hdda.glsl"

layout(local_size_x = 64) in;

struct ProbeRay {
    vec4 origin;     // xyz, w = max distance
    vec4 direction;  // xyz (normalized), w = start offset
};
layout(std430, binding = SV_HDDA_PROBE_RAYS) readonly buffer Rays { ProbeRay rays[]; };
// Per ray: hit voxel xyz + (1 + cascade, 0 = miss); position + steps.
layout(std430, binding = SV_HDDA_PROBE_HITS) writeonly buffer Hits { ivec4 hitVoxels[]; };
layout(std430, binding = SV_HDDA_PROBE_POSITIONS) writeonly buffer HitPositions { vec4 hitPositions[]; };

layout(location = 0) uniform uint u_count;
layout(location = 1) uniform int u_resolution;
layout(location = 2) uniform int u_cascadeCount;
layout(location = 3) uniform vec4 u_cascades[SDF_MAX_CASCADES];
layout(location = 7) uniform int u_maxSteps;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_resolution);
    HddaHit h = hddaTraceCascades(cs, rays[i].origin.xyz, rays[i].direction.xyz, rays[i].direction.w,
                                  rays[i].origin.w, u_maxSteps);
    hitVoxels[i] = h.hit ? ivec4(h.voxel, 1 + h.cascade) : ivec4(0);
    hitPositions[i] = vec4(h.hit ? h.position : vec3(0.0), float(h.steps));
}
