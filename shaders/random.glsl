// Deterministic per-pixel random numbers: a PCG hash seeds each pixel and sample, then a PCG32
// step (O'Neill 2014) gives the stream. Same seed, same image.
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

struct Rng { uint state; };

Rng makeRng(uvec2 pixel, uint sampleIndex, uint seed) {
    Rng r;
    r.state = pcgHash(pixel.x + pcgHash(pixel.y + pcgHash(sampleIndex + pcgHash(seed))));
    return r;
}

// Uniform in [0, 1): 24 bits so the value is exactly representable and never reaches 1.
float nextFloat(inout Rng r) {
    r.state = r.state * 747796405u + 2891336453u;
    uint word = ((r.state >> ((r.state >> 28u) + 4u)) ^ r.state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8) * (1.0 / 16777216.0);
}

vec2 nextFloat2(inout Rng r) { return vec2(nextFloat(r), nextFloat(r)); }
