// One probe update, steps 2 and 3: the batch's rays blended into each probe's irradiance
// (u_mode 0: SH projection or the cosine-weighted mean per octahedral texel) or distance moments
// (u_mode 1: mean and mean^2 of the hit distance under a sharp cosine power per texel). A probe's
// first u_update.replacingUpdates updates replace its irradiance (each one more bounce of the multi-bounce
// recursion: renderer/probes/probe_field.cpp, bounceUpdates), the next ones are a growing-weight
// running mean (weight 2/(n+2)), later ones an exponential moving average of weight
// 1 - hysteresis: noise falls fast at first and a light change is still followed. The
// largest relative change of the irradiance level goes to the probe's state (its own convergence)
// and to u_change (atomicMax on the float's bits, which order like the floats for non-negative
// values: the batch's largest).
#include "probes/probe_common.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = SP_RAYS) readonly buffer Rays { vec4 rayResults[]; };
layout(std430, binding = SP_CHANGE) buffer Change { uint u_change; uint u_rayCount; };
layout(std430, binding = SP_BATCH) readonly buffer Batch { int u_batch[]; };
layout(location = UP_RAYS) uniform int u_rays;
layout(location = UP_SLOT_OFFSET) uniform int u_slotOffset;  // several dispatches past the work-group limit
layout(location = UP_ROTATION) uniform mat3 u_rotation;
ProbeUpdateBlock u_update;
layout(location = UP_MODE) uniform int u_mode;

const int MAX_RAYS = 512;
shared vec4 s_rays[MAX_RAYS];
shared vec3 s_dirs[MAX_RAYS];
shared uint s_change;


// 2 / (n + 2): a mean whose weights grow linearly with the update's number, so the first updates,
// whose multi-bounce term still comes from probes that had not converged (or from before a light
// edit), fade as 1/n^2 instead of 1/n; the hysteresis floor then keeps a moving average.
float newWeight(float updates) {
    float bounceUpdates = u_update.replacingUpdates;
    if (updates < bounceUpdates) return 1.0;
    float averaged = updates - bounceUpdates;
    return averaged < 0.5 ? 1.0 : max(2.0 / (averaged + 2.0), 1.0 - u_update.hysteresis);
}

vec4 blendIrradiance(int slot, int c) {
    vec3 n = octTexelDirection(c, OCT_IRRADIANCE_SIZE);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int r = 0; r < u_rays; ++r) {
        float w = u_storage == PROBE_OCTAHEDRAL ? max(0.0, dot(n, s_dirs[r])) : shBasis(c, s_dirs[r]);
        sum += w * s_rays[r].rgb;
        weights += abs(w);
    }
    // SH: L_lm = 4 pi / n sum L Y_lm (uniform directions). Octahedral: the cosine-weighted mean.
    if (u_storage != PROBE_OCTAHEDRAL) return vec4(sum * (4.0 * PI / float(u_rays)), 1.0);
    return weights > 0.0 ? vec4(sum / weights, 1.0) : vec4(0.0);
}

vec4 blendDistance(int c) {
    vec3 n = octTexelDirection(c, OCT_DISTANCE_SIZE);
    vec2 sum = vec2(0.0);
    float weights = 0.0;
    for (int r = 0; r < u_rays; ++r) {
        float cosine = max(0.0, dot(n, s_dirs[r]));
        float w = pow(cosine, 50.0);  // DDGI's sharp lobe: the distance right along the texel
        float d = s_rays[r].w;
        sum += w * vec2(d, d * d);
        weights += w;
    }
    return weights > 1e-12 ? vec4(sum / weights, 1.0, 0.0) : vec4(0.0);
}

void main() {
    int slot = u_slotOffset + int(gl_WorkGroupID.x);
    int probe = u_batch[slot];
    if (gl_LocalInvocationID.x == 0u) s_change = 0u;
    for (int r = int(gl_LocalInvocationID.x); r < u_rays; r += int(gl_WorkGroupSize.x)) {
        s_rays[r] = rayResults[slot * u_rays + r];
        s_dirs[r] = normalize(u_rotation * fibonacciDirection(r, u_rays));
    }
    float updates = probeState[2 * probe + 1].x;
    barrier();
    if (!probeOff(probe)) {
        float w = newWeight(updates);
        if (u_mode == 0) {
            int stride = irradianceStride();
            int base = probe * stride;
            // Relative to the probe's level (its DC term or texel), floored so a black probe's
            // rounding noise is not a change.
            float level = luminance(abs(probeIrradiance[base].rgb)) + 1e-4;
            for (int c = int(gl_LocalInvocationID.x); c < stride; c += int(gl_WorkGroupSize.x)) {
                vec3 old = probeIrradiance[base + c].rgb;
                vec3 value = finiteOrZero(mix(old, blendIrradiance(slot, c).rgb, w));
                probeIrradiance[base + c] = vec4(value, 1.0);
                // SH: the level (DC) alone; the higher coefficients' estimates are noisier and matter
                // less. Octahedral: every texel, each already a cosine-weighted mean.
                bool measured = u_storage == PROBE_OCTAHEDRAL || c == 0;
                float ref = u_storage == PROBE_OCTAHEDRAL ? luminance(old) + 1e-4 : level;
                if (updates > 0.5 && measured) atomicMax(s_change, floatBitsToUint(luminance(abs(value - old)) / ref));
            }
        } else {
            int size = OCT_DISTANCE_SIZE * OCT_DISTANCE_SIZE;
            for (int c = int(gl_LocalInvocationID.x); c < size; c += int(gl_WorkGroupSize.x)) {
                vec4 fresh = blendDistance(c);
                int at = probe * size + c;
                if (fresh.z > 0.5) probeDistance[at] = updates < 0.5 ? fresh.xy : mix(probeDistance[at], fresh.xy, w);
            }
        }
    }
    barrier();
    // The irradiance step records the change; the distance step runs last in an update: it counts it.
    if (u_mode == 0 && gl_LocalInvocationID.x == 0u) {
        probeState[2 * probe + 1].y = uintBitsToFloat(s_change);
        atomicMax(u_change, s_change);
    }
    if (u_mode == 1 && gl_LocalInvocationID.x == 0u) probeState[2 * probe + 1].x = updates + 1.0;
}
