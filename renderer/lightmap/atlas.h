// Lightmap UVs (issue #41): the file's TEXCOORD_1 when its charts do not overlap, otherwise an
// atlas of our own (charts of similar normal, flattened, scaled to a texel density, packed with a
// gutter). No GL: the bake rasterizes what this returns. Method and measured numbers: README.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gis {

struct Scene;

namespace lightmap {

struct AtlasParams {
    float texelsPerMetre = 16.0f;     // texel density on the surfaces (world units are metres)
    float chartAngleDegrees = 30.0f;  // a face joins a chart when its normal is this close to the chart's
    int maxAtlasSize = 2048;          // side of one square atlas, texels
    int maxAtlases = 4;               // charts that do not fit one atlas spill into the next
    int gutter = 2;                   // texels between charts and along the atlas border
    bool useFileUvs = true;           // false: always generate, even where TEXCOORD_1 is valid
};

// One mesh as the lightmap sees it: an instance (a scene draw) in world space, since each instance
// needs texels of its own and the density is in world metres.
struct MeshInput {
    std::vector<glm::vec3> positions;  // world space
    std::vector<uint32_t> indices;     // 3 per triangle
    std::vector<glm::vec2> uv1;        // the file's TEXCOORD_1 (one per position) or empty
};

// The verdict on a set of UV charts: ok, or the first reason found against them.
struct UvCheck {
    bool ok = true;
    std::string reason;
};
// Every triangle must lie within [0,1]^2, be finite, have area, and overlap no other triangle
// (triangles that share an edge or a vertex touch, they do not overlap).
UvCheck checkUvCharts(const std::vector<glm::vec2>& uv, const std::vector<uint32_t>& indices);

// A chart's place: a texel rectangle of one atlas (its gutter lies outside it).
struct Chart {
    int mesh = 0;
    int atlas = 0;
    int x = 0, y = 0, width = 0, height = 0;
    int triangles = 0;
    bool fromFile = false;  // the whole TEXCOORD_1 layout of a mesh, placed as one rectangle
};

// A mesh re-indexed for its lightmap: a vertex on a chart border is repeated once per chart.
struct MeshAtlas {
    std::vector<uint32_t> sourceVertex;    // per vertex: the input vertex it copies
    std::vector<int> chart;                // per vertex: index into Atlas::charts (its atlas is the chart's)
    std::vector<glm::vec2> uv;             // per vertex: in [0,1] of its chart's atlas
    std::vector<uint32_t> indices;         // 3 per kept triangle
    std::vector<uint32_t> sourceTriangle;  // per kept triangle: its input triangle
    bool fileUvs = false;                  // TEXCOORD_1 used as the file laid it out
    std::string fileUvsRejected;           // why the file's TEXCOORD_1 was not used ("" = used or absent)
    int skippedTriangles = 0;              // degenerate in the world (see buildAtlas): no texels, not in indices
};

struct Atlas {
    AtlasParams params;
    std::vector<int> atlasSizes;  // side of each atlas, texels
    std::vector<Chart> charts;
    std::vector<MeshAtlas> meshes;
    double chartTexels = 0.0;     // area of all triangles in the atlases, texels
    std::string hash;             // of the parameters and the result: part of the bake's cache key
    double fill() const;          // chartTexels over the atlases' area
    int atlasOf(size_t mesh, size_t vertex) const { return charts[size_t(meshes[mesh].chart[vertex])].atlas; }
};

// Triangles whose height is below 1e-6 of their longest edge are degenerate (skipped, counted).
// Throws gis::Error (one line naming the parameter or the mesh and vertex) for bad parameters,
// non-finite positions, out-of-range indices, a density whose texels exceed maxAtlases atlases of
// maxAtlasSize, and input without any triangle of area. Deterministic: same input, same hash.
Atlas buildAtlas(const std::vector<MeshInput>& meshes, const AtlasParams& params);

// One MeshInput per scene draw (instances are lit differently, so each has its own texels).
std::vector<MeshInput> meshesFromScene(const Scene& scene);

}  // namespace lightmap
}  // namespace gis
