// Do triangles in a plane overlap? One test for the file's TEXCOORD_1 and for our own flattened
// charts (a projection of a curved chart can fold over itself).
#pragma once

#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace gis::lightmap::detail {

struct Tri2 {
    glm::dvec2 p[3];
};

// Two triangles whose interiors overlap (indices into `tris`, first found), or {-1, -1}.
// Triangles sharing an edge or a vertex only touch. Grid-bucketed: each triangle is tested
// against those already in the cells its bounding box covers, so the cost grows with the
// triangles near each other, not with all pairs.
std::pair<int, int> findOverlap(const std::vector<Tri2>& tris);

}  // namespace gis::lightmap::detail
