// Charts of one mesh: grown over adjacent faces of similar normal, each projected onto the plane
// of its area-weighted normal, turned to its smallest bounding rectangle and scaled to texels.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace gis::lightmap::detail {

struct FlatChart {
    std::vector<uint32_t> triangles;  // input triangles, in chart order
    std::vector<uint32_t> vertices;   // per chart vertex: its input vertex
    std::vector<glm::dvec2> texels;   // per chart vertex: position in texels, min corner at (0,0)
    std::vector<uint32_t> indices;    // into the chart's vertices, 3 per triangle
    glm::dvec2 extent{0.0};           // width >= height
};

// `kept` lists the triangles with area (the caller drops degenerate ones). Every face of a chart
// is within `angleDegrees` of the chart's normal, so projection shrinks no face below
// cos(angle) of its area; charts whose projection folds over itself are split.
std::vector<FlatChart> makeCharts(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                                  const std::vector<uint32_t>& kept, double angleDegrees,
                                  double texelsPerMetre);

}  // namespace gis::lightmap::detail
