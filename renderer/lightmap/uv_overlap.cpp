#include "lightmap/uv_overlap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lightmap/atlas.h"

namespace gis::lightmap {
namespace detail {
namespace {

struct Box {
    glm::dvec2 lo{1e300}, hi{-1e300};
};

Box boxOf(const Tri2& t) {
    Box b;
    for (const glm::dvec2& p : t.p) {
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
    }
    return b;
}

// Separating axes on the six edge normals: two convex polygons' interiors are disjoint exactly
// when one of their edge normals separates them. `eps` lets shared edges and vertices touch.
bool separated(const Tri2& a, const Tri2& b, double eps) {
    for (const Tri2* t : {&a, &b})
        for (int e = 0; e < 3; ++e) {
            const glm::dvec2 d = t->p[(e + 1) % 3] - t->p[e];
            glm::dvec2 n(-d.y, d.x);
            const double len = glm::length(n);
            if (len == 0.0) continue;
            n /= len;
            double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
            for (int k = 0; k < 3; ++k) {
                const double pa = glm::dot(n, a.p[k]), pb = glm::dot(n, b.p[k]);
                amin = std::min(amin, pa), amax = std::max(amax, pa);
                bmin = std::min(bmin, pb), bmax = std::max(bmax, pb);
            }
            if (amax <= bmin + eps || bmax <= amin + eps) return true;
        }
    return false;
}

}  // namespace

std::pair<int, int> findOverlap(const std::vector<Tri2>& tris) {
    const size_t n = tris.size();
    if (n < 2) return {-1, -1};
    std::vector<Box> boxes(n);
    Box all;
    double meanSide = 0.0;
    for (size_t i = 0; i < n; ++i) {
        boxes[i] = boxOf(tris[i]);
        all.lo = glm::min(all.lo, boxes[i].lo);
        all.hi = glm::max(all.hi, boxes[i].hi);
        const glm::dvec2 s = boxes[i].hi - boxes[i].lo;
        meanSide += std::max(s.x, s.y) / double(n);
    }
    const glm::dvec2 extent = glm::max(all.hi - all.lo, glm::dvec2(1e-300));
    const double eps = 1e-9 * std::max(extent.x, extent.y);
    // Cells about one triangle across, but never more than ~4 per triangle (memory).
    double cell = std::max(meanSide, 1e-300);
    auto cells = [&](double c, int axis) { return std::min(4096, int(extent[axis] / c) + 1); };
    while (double(cells(cell, 0)) * cells(cell, 1) > 4.0 * double(n) + 16.0) cell *= 2.0;
    const int gx = cells(cell, 0), gy = cells(cell, 1);
    std::vector<std::vector<int>> grid(size_t(gx) * size_t(gy));
    std::vector<int> testedBy(n, -1);  // the triangle each one was last tested against
    auto cellOf = [&](double v, int axis, int g) {
        return std::clamp(int((v - all.lo[axis]) / cell), 0, g - 1);
    };
    for (size_t i = 0; i < n; ++i) {
        const int x0 = cellOf(boxes[i].lo.x, 0, gx), x1 = cellOf(boxes[i].hi.x, 0, gx);
        const int y0 = cellOf(boxes[i].lo.y, 1, gy), y1 = cellOf(boxes[i].hi.y, 1, gy);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                std::vector<int>& c = grid[size_t(y) * size_t(gx) + size_t(x)];
                for (int j : c) {
                    if (testedBy[size_t(j)] == int(i)) continue;
                    testedBy[size_t(j)] = int(i);
                    const Box& b = boxes[size_t(j)];
                    if (b.hi.x <= boxes[i].lo.x + eps || boxes[i].hi.x <= b.lo.x + eps ||
                        b.hi.y <= boxes[i].lo.y + eps || boxes[i].hi.y <= b.lo.y + eps)
                        continue;
                    if (!separated(tris[i], tris[size_t(j)], eps)) return {j, int(i)};
                }
                c.push_back(int(i));
            }
    }
    return {-1, -1};
}

}  // namespace detail

namespace {
std::string fmt(glm::dvec2 p) {
    std::ostringstream s;
    s.precision(4);
    s << "(" << p.x << ", " << p.y << ")";
    return s.str();
}
}  // namespace

UvCheck checkUvCharts(const std::vector<glm::vec2>& uv, const std::vector<uint32_t>& indices) {
    if (indices.size() % 3 != 0) return {false, "index count is not a multiple of 3"};
    std::vector<detail::Tri2> tris(indices.size() / 3);
    for (size_t t = 0; t < tris.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = indices[3 * t + size_t(k)];
            if (v >= uv.size())
                return {false, "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                   ", which has no UV (" + std::to_string(uv.size()) + " UVs)"};
            const glm::dvec2 p(uv[v]);
            if (!std::isfinite(p.x) || !std::isfinite(p.y))
                return {false, "vertex " + std::to_string(v) + " has a non-finite UV"};
            if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0)
                return {false, "triangle " + std::to_string(t) + " lies outside [0,1] (vertex " +
                                   std::to_string(v) + " at " + fmt(p) + ")"};
            tris[t].p[k] = p;
        }
        const glm::dvec2 e1 = tris[t].p[1] - tris[t].p[0], e2 = tris[t].p[2] - tris[t].p[0];
        // Collapsed to a line or a point: the face's texels would all lie on it. (A tiny but
        // positive area is only a small face, which gets its light from the nearest texel.)
        if (e1.x * e2.y - e1.y * e2.x == 0.0)
            return {false, "triangle " + std::to_string(t) + " has no area in UV space (at " +
                               fmt(tris[t].p[0]) + ")"};
    }
    const auto [a, b] = detail::findOverlap(tris);
    if (a < 0) return {};
    const detail::Tri2& t = tris[size_t(b)];
    return {false, "triangles " + std::to_string(a) + " and " + std::to_string(b) + " overlap (near " +
                       fmt((t.p[0] + t.p[1] + t.p[2]) / 3.0) + "): charts must not share texels"};
}

}  // namespace gis::lightmap
