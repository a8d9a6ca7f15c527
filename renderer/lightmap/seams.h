// Seams of a lightmap (issue #41; Godot #90929): an edge of a smooth surface whose two triangles lie
// in different charts (or far apart in one file layout). Each side's texels are baked, denoised and
// looked up on their own, so the two sides' light differs along it by the bake's noise, and the
// edge shows as a line. Stitching makes them agree: points along each seam are looked up on both
// sides as the lookup does (bilinear over the texels with light of their own) and the texels are
// moved, as little as possible, until both sides read the same (the least-change solution of all
// the points' equations, by conjugate gradients on their normal equations). A crease (the
// normals differ across the edge: a box's corner) is no seam: its light differs in truth. No GL.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace gis::lightmap {

// A vertex of the atlas's triangles as the bake draws them: world position and normal, its place
// in the atlas array (texels from the layer's corner) and the layer.
struct SeamVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 texel;
    int layer = 0;
    bool unstitched = false;  // its chart is left alone (too narrow for its seams to agree)
};

// One point of a seam, where the two sides' lookups must agree: each side's place in texels.
struct SeamPoint {
    glm::vec2 a, b;
    int layerA = 0, layerB = 0;
};

// Points along every seam: edges two triangles share by position and normal at both ends (bit for
// bit, as a mesh's welded or split vertices hold them) whose atlas places differ, about
// `perTexel` points per texel of the longer side; none where either side is `unstitched`.
std::vector<SeamPoint> findSeams(const std::vector<SeamVertex>& vertices, const std::vector<uint32_t>& indices,
                                 float perTexel = 2.0f);

// The lightmap on the CPU: RGBA per texel, `side` x `side` x layers; alpha 1 marks a texel with
// light of its own (the others are neither read nor moved).
struct TexelImage {
    std::vector<float> rgba;
    int side = 0, layers = 0;
    float* at(int x, int y, int layer) { return &rgba[((size_t(layer) * side + size_t(y)) * side + size_t(x)) * 4]; }
};

// What the lookup reads at `texel` of `layer` (apply.frag: bilinear over the texels with light of
// their own, renormalised); false where none is in its footprint.
bool lookUp(const TexelImage& image, glm::vec2 texel, int layer, glm::vec3& out);

// The largest difference between a point's two sides, over the mean value along the seams, before
// and after stitching.
struct StitchGaps {
    float before = 0.0f, after = 0.0f;
};
// Moves the texels with light of their own until both sides of every point read the same
// (`iterations` of conjugate gradients); `light`: the values are light, never moved below 0 (a
// direction's components may be).
StitchGaps stitchSeams(const std::vector<SeamPoint>& points, TexelImage& image, int iterations = 256, bool light = true);

}  // namespace gis::lightmap
