// One probe update, step 1: every probe of the batch (u_batch, most urgent first) shoots u_rays
// rays (a spherical-Fibonacci set under this update's random rotation), sphere-traced through the
// distance field's cascades (volume/sdf_march.glsl), or with PROBE_TRACER_OCCUPANCY walked through
// the occupancy hierarchy by HDDA (volume/hdda.glsl), starting in the finest cascade that holds the
// probe, and shaded as probe_hit_light.glsl shades every ray of a field. One workgroup per probe;
// rays go to the ray buffer for the blend steps, and their count to the change buffer (what a ray
// budget is checked against).
#define PROBE_SEGMENT_TEST 1
#include "probes/probe_common.glsl"
#include "probes/probe_hit_light.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SP_RAYS) writeonly buffer Rays { vec4 rayResults[]; };
layout(std430, binding = SP_CHANGE) buffer Change { uint u_change; uint u_rayCount; };
layout(std430, binding = SP_BATCH) readonly buffer Batch { int u_batch[]; };

layout(location = UP_RAYS) uniform int u_rays;
layout(location = UP_SLOT_OFFSET) uniform int u_slotOffset;  // several dispatches past the work-group limit
layout(location = UP_ROTATION) uniform mat3 u_rotation;

shared uint s_traced;

void main() {
    int slot = u_slotOffset + int(gl_WorkGroupID.x);
    int probe = u_batch[slot];
    bool off = probeOff(probe);
    vec3 origin = probePosition(probe);
    if (gl_LocalInvocationID.x == 0u) s_traced = 0u;
    barrier();
    uint traced = 0u;
    for (int r = int(gl_LocalInvocationID.x); r < u_rays; r += int(gl_WorkGroupSize.x)) {
        vec4 result = vec4(0.0, 0.0, 0.0, u_update.missDistance);
        if (!off) {
            result = fieldRayRadiance(origin, normalize(u_rotation * fibonacciDirection(r, u_rays)), 4.0 * PI / float(u_rays), true);
            ++traced;
        }
        rayResults[slot * u_rays + r] = result;
    }
    atomicAdd(s_traced, traced);
    barrier();
    if (gl_LocalInvocationID.x == 0u) atomicAdd(u_rayCount, s_traced);
}
