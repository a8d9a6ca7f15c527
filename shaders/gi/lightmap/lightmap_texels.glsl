// The texel flags classify.comp keeps in the position's w (as 1 + flags): bit i, the atlas
// neighbour TEXEL_NEIGHBOURS[i] is blocked; TEXEL_INSIDE, the texel's centre is behind a surface.
const ivec2 TEXEL_NEIGHBOURS[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
const int TEXEL_INSIDE = 16;

// Whether a texel lies on a chart, from its position's w (0 in the gutter between charts).
bool texelOnChart(float w) { return w > 0.0; }

// The flags of a texel from its position's w (0 for a texel on no chart).
int texelFlags(float w) { return texelOnChart(w) ? int(w) - 1 : 0; }

// The bit of the neighbour at `offset` (one of TEXEL_NEIGHBOURS; 0 for any other).
int neighbourBit(ivec2 offset) {
    for (int i = 0; i < 4; ++i)
        if (offset == TEXEL_NEIGHBOURS[i]) return 1 << i;
    return 0;
}
