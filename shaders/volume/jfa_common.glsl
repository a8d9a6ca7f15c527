// The nearest-seed field of the jump flood: one uint per cell, the seed's cell packed 10 bits per
// axis (so resolutions up to 1024), or JFA_NONE where no seed has arrived yet.

const uint JFA_NONE = 0xFFFFFFFFu;

layout(location = US_RESOLUTION) uniform int u_resolution;

uint jfaPack(ivec3 c) { return uint(c.x) | (uint(c.y) << 10) | (uint(c.z) << 20); }
ivec3 jfaUnpack(uint s) { return ivec3(int(s & 1023u), int((s >> 10) & 1023u), int((s >> 20) & 1023u)); }

bool jfaInside(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(u_resolution))); }

// Squared distance in cells: integers, so ties are exact and broken the same way everywhere.
int jfaDistance2(ivec3 a, ivec3 b) {
    ivec3 d = a - b;
    return d.x * d.x + d.y * d.y + d.z * d.z;
}
