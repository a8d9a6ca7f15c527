// Probes inside solid geometry (negative distance) see only the inside of a wall and would leak
// it into every room around: each is pushed out along the field's gradient to where the field is
// half a cell outside, when that is within 0.45 of a probe step (u_mode 0, relocate), else (and
// always with u_mode 1, off) switched off. The field is read in the finest cascade that holds the
// probe. With PROBE_TRACER_OCCUPANCY (no distance field) a probe in an occupied voxel is moved to
// the nearest free voxel centre along the six axes within that reach, else switched off. Writes
// the state of grid u_classifyGrid's probes (offset, 0 active / 1 relocated / 2 off) and clears
// their update counts.
#include "probes/probe_common.glsl"
#include "probes/probe_tracer.glsl"

layout(local_size_x = 64) in;
layout(location = UP_MODE) uniform int u_mode;
layout(location = UP_CLASSIFY_GRID) uniform int u_classifyGrid;

#ifdef PROBE_TRACER_OCCUPANCY
vec4 classify(int i) {
    HddaCascades cs = HddaCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    vec3 p = probeGridPosition(i);
    int c = hddaCascadeAt(cs, p);
    float cell = cs.volumes[c].w / float(cs.resolution);
    ivec3 v = ivec3(floor((p - cs.volumes[c].xyz) / cell));
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(cs.resolution))) || !occVoxel(c, v, cs.resolution))
        return vec4(0.0);
    int reach = int(floor(0.45 * gridMinStep(probeGrid(i)) / cell + 0.5));
    for (int k = 1; u_mode == 0 && k <= reach; ++k)
        for (int a = 0; a < 6; ++a) {
            ivec3 d = ivec3(0);
            d[a >> 1] = (a & 1) == 0 ? k : -k;
            ivec3 w = v + d;
            if (any(lessThan(w, ivec3(0))) || any(greaterThanEqual(w, ivec3(cs.resolution))) || occVoxel(c, w, cs.resolution))
                continue;
            vec3 centre = cs.volumes[c].xyz + (vec3(w) + 0.5) * cell;
            return vec4(centre - p, 1.0);
        }
    return vec4(0.0, 0.0, 0.0, PROBE_OFF);
}
#else
vec4 classify(int i) {
    SdfCascades cs = SdfCascades(u_cascades, u_cascadeCount, u_sdfResolution);
    vec3 p = probeGridPosition(i);
    int layer = sdfCascadeAt(cs, p);
    SdfVolume vol = sdfCascadeVolume(cs, layer);
    float d = sdfSample(s_distance, vol, layer, p);
    vec4 state = vec4(0.0);
    if (d < 0.0) {
        // Walk out along the gradient from |d| until the field says "outside by half a cell": the
        // zero level set of a jump-flooded field sits on the seed voxels' centres, not exactly at
        // |d| (and at a block's centre the gradient is only a tie-break direction).
        vec3 n = sdfNormal(s_distance, vol, layer, p);
        float cell = sdfCellSize(vol);
        float limit = 0.45 * gridMinStep(probeGrid(i));
        state = vec4(0.0, 0.0, 0.0, PROBE_OFF);
        for (float t = -d; u_mode == 0 && t <= limit; t += 0.5 * cell) {
            if (sdfSample(s_distance, vol, layer, p + n * t) > 0.5 * cell) {
                state = vec4(n * t, 1.0);
                break;
            }
        }
    }
    return state;
}
#endif

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= probeCount() || (u_classifyGrid >= 0 && probeGrid(i) != u_classifyGrid)) return;
    probeState[2 * i] = classify(i);
    probeState[2 * i + 1] = vec4(0.0);
}
