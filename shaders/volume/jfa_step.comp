// One jump-flood pass: each cell keeps the nearest of the seeds held by itself and by its 26
// neighbours at +-step (Rong & Tan 2006, in 3D). Reads one image and writes the other, so a pass
// never sees its own partial results.
#include "volume/jfa_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = IF_STEP_SOURCE, r32ui) uniform readonly uimage3D i_source;
layout(binding = IF_STEP_TARGET, r32ui) uniform writeonly uimage3D i_target;
layout(location = US_JFA_STEP) uniform int u_step;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (!jfaInside(c)) return;
    uint best = imageLoad(i_source, c).x;
    int bestD = best == JFA_NONE ? 0x7fffffff : jfaDistance2(c, jfaUnpack(best));
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec3 q = c + ivec3(x, y, z) * u_step;
                if ((x == 0 && y == 0 && z == 0) || !jfaInside(q)) continue;
                uint s = imageLoad(i_source, q).x;
                if (s == JFA_NONE) continue;
                int d = jfaDistance2(c, jfaUnpack(s));
                // Equal distances: the smaller packed seed wins, so the result does not depend on
                // the order neighbours are visited in.
                if (d < bestD || (d == bestD && s < best)) {
                    best = s;
                    bestD = d;
                }
            }
    imageStore(i_target, c, uvec4(best));
}
