#include "lightmap/charts.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "lightmap/uv_overlap.h"

namespace gis::lightmap::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Below this the halving of a folding chart's angle stops and its faces become charts of their
// own: coplanar duplicates (z-fighting copies) fold at any angle.
constexpr double kMinAngleDegrees = 0.5;

// Welds vertices at the same position, within a tolerance: glTF splits a vertex wherever its
// normal or UV changes, and charts must grow across such splits; an exporter that computes a
// shared corner once per face leaves the copies a few float steps apart (the atrium's floor:
// every 0.3 m cell a chart of its own, until this tolerance). The tolerance is a millionth of the
// mesh's size plus a few float steps of its largest coordinate. Returns, per vertex, the vertex it
// is welded to: the first in sorted order within the tolerance that is welded to none before it
// (no chaining), so the result does not depend on hashing; its position stands for all of them.
std::vector<uint32_t> weld(const std::vector<glm::vec3>& positions) {
    std::vector<uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    auto less = [&](uint32_t a, uint32_t b) {
        const glm::vec3 &p = positions[a], &q = positions[b];
        if (p.x != q.x) return p.x < q.x;
        if (p.y != q.y) return p.y < q.y;
        if (p.z != q.z) return p.z < q.z;
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::vec3& p : positions) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    const double largest = positions.empty() ? 0.0 : std::max(glm::length(lo), glm::length(hi));
    const double tolerance = 1e-6 * glm::length(hi - lo) + 4.0 * largest * 1.2e-7;
    std::vector<uint32_t> to(positions.size());
    if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {  // one point, or none: exact equality
        for (size_t k = 0; k < order.size(); ++k)
            to[order[k]] = (k > 0 && positions[order[k]] == positions[order[k - 1]]) ? to[order[k - 1]] : order[k];
        return to;
    }
    // Representatives by grid cell of the tolerance's size: a match lies in one of the 27 around.
    auto cellOf = [&](const glm::vec3& p) { return glm::i64vec3(glm::floor((glm::dvec3(p) - lo) / tolerance)); };
    auto key = [](glm::i64vec3 c) { return uint64_t(c.x) * 73856093u ^ uint64_t(c.y) * 19349663u ^ uint64_t(c.z) * 83492791u; };
    std::unordered_multimap<uint64_t, uint32_t> representatives;  // cell key -> vertex
    for (const uint32_t v : order) {
        const glm::i64vec3 c = cellOf(positions[v]);
        uint32_t found = UINT32_MAX;
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::i64vec3 n = c + glm::i64vec3(dx, dy, dz);
                    auto [first, last] = representatives.equal_range(key(n));
                    for (auto it = first; it != last; ++it) {
                        const glm::dvec3 d = glm::dvec3(positions[it->second]) - glm::dvec3(positions[v]);
                        if (cellOf(positions[it->second]) == n && std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) <= tolerance &&
                            (found == UINT32_MAX || less(it->second, found)))
                            found = it->second;
                    }
                }
        to[v] = found != UINT32_MAX ? found : v;
        if (found == UINT32_MAX) representatives.emplace(key(c), v);
    }
    return to;
}

class Charter {
public:
    Charter(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
            const std::vector<uint32_t>& kept, double texelsPerMetre)
        : P_(positions), I_(indices), density_(texelsPerMetre), normal_(indices.size() / 3),
          area_(indices.size() / 3, 0.0), adj_(indices.size() / 3), mark_(indices.size() / 3, -2) {
        for (uint32_t t : kept) {
            const glm::dvec3 c = glm::cross(pos(t, 1) - pos(t, 0), pos(t, 2) - pos(t, 0));
            area_[t] = 0.5 * glm::length(c);
            normal_[t] = glm::normalize(c);
        }
        buildAdjacency(kept);
    }

    void run(const std::vector<uint32_t>& subset, double angleDegrees, std::vector<FlatChart>& out) {
        if (angleDegrees < kMinAngleDegrees) {
            for (uint32_t t : subset) {
                out.emplace_back();
                flatten({t}, -1.0, out.back());  // one face: no angle to hold, nothing to fold
            }
            return;
        }
        const double cosMax = std::cos(angleDegrees * kPi / 180.0);
        for (const std::vector<uint32_t>& chart : grow(subset, cosMax)) {
            FlatChart fc;
            if (flatten(chart, cosMax, fc))
                out.push_back(std::move(fc));
            else
                run(chart, 0.5 * angleDegrees, out);  // it folds: smaller charts of flatter faces
        }
    }

private:
    glm::dvec3 pos(uint32_t t, int k) const { return glm::dvec3(P_[I_[3 * t + uint32_t(k)]]); }

    // Triangles across each welded edge; non-manifold edges join all their triangles.
    void buildAdjacency(const std::vector<uint32_t>& kept) {
        // A welded corner's copies take one position in the chart (flatten), so faces across the
        // weld meet exactly in the plane (float steps apart they could cross and read as a fold).
        welded_ = weld(P_);
        struct Edge {
            uint32_t a, b, t;
            bool operator<(const Edge& o) const { return std::tie(a, b, t) < std::tie(o.a, o.b, o.t); }
        };
        std::vector<Edge> edges;
        for (uint32_t t : kept)
            for (uint32_t k = 0; k < 3; ++k) {
                uint32_t a = welded_[I_[3 * t + k]], b = welded_[I_[3 * t + (k + 1) % 3]];
                if (a > b) std::swap(a, b);
                if (a != b) edges.push_back({a, b, t});
            }
        std::sort(edges.begin(), edges.end());
        for (size_t i = 0; i < edges.size();) {
            size_t j = i;
            while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
            for (size_t x = i; x < j; ++x)
                for (size_t y = i; y < j; ++y)
                    if (edges[x].t != edges[y].t) adj_[edges[x].t].push_back(edges[y].t);
            i = j;
        }
        for (auto& list : adj_) {
            std::sort(list.begin(), list.end());
            list.erase(std::unique(list.begin(), list.end()), list.end());
        }
    }

    // Charts over `subset`, each grown breadth-first from the largest free face. Faces that end
    // up beyond the angle of the chart's final normal are freed again and seed later charts.
    std::vector<std::vector<uint32_t>> grow(const std::vector<uint32_t>& subset, double cosMax) {
        std::vector<uint32_t> order = subset;
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
            return area_[a] != area_[b] ? area_[a] > area_[b] : a < b;
        });
        for (uint32_t t : subset) mark_[t] = -1;
        std::vector<std::vector<uint32_t>> charts;
        for (bool again = true; again;) {
            again = false;
            for (uint32_t seed : order)
                if (mark_[seed] == -1) {
                    charts.push_back(growOne(seed, int(charts.size()), cosMax));
                    again = true;
                }
        }
        for (uint32_t t : subset) mark_[t] = -2;
        return charts;
    }

    std::vector<uint32_t> growOne(uint32_t seed, int id, double cosMax) {
        std::vector<uint32_t> chart{seed};
        mark_[seed] = id;
        glm::dvec3 sum = normal_[seed] * area_[seed];
        for (size_t q = 0; q < chart.size(); ++q)
            for (uint32_t nb : adj_[chart[q]]) {
                if (mark_[nb] != -1 || glm::dot(normal_[nb], glm::normalize(sum)) < cosMax) continue;
                mark_[nb] = id;
                chart.push_back(nb);
                sum += normal_[nb] * area_[nb];
            }
        for (int pass = 0; pass < 4; ++pass) {
            const glm::dvec3 mean = glm::normalize(sum);
            size_t keep = 1;  // the seed stays: every chart has at least one face
            for (size_t i = 1; i < chart.size(); ++i) {
                const uint32_t t = chart[i];
                if (glm::dot(normal_[t], mean) >= cosMax) {
                    chart[keep++] = t;
                } else {
                    mark_[t] = -1;
                    sum -= normal_[t] * area_[t];
                }
            }
            const bool dropped = keep < chart.size();
            chart.resize(keep);
            if (!dropped) break;
        }
        return chart;
    }

    bool flatten(const std::vector<uint32_t>& tris, double cosMax, FlatChart& fc) const;

    const std::vector<glm::vec3>& P_;
    const std::vector<uint32_t>& I_;
    double density_;
    std::vector<glm::dvec3> normal_;
    std::vector<double> area_;
    std::vector<std::vector<uint32_t>> adj_;
    std::vector<int> mark_;  // per triangle: -2 outside the subset, -1 free, else its chart
    std::vector<uint32_t> welded_;  // per vertex: the vertex it is welded to (weld; itself if none)
};

double cross2(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain.
std::vector<glm::dvec2> convexHull(std::vector<glm::dvec2> p) {
    std::sort(p.begin(), p.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    if (p.size() < 3) return p;
    std::vector<glm::dvec2> h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

// Turns the chart to its smallest bounding rectangle (one side lies along a hull edge, Freeman &
// Shapira 1975), landscape, with its min corner at the origin: less empty atlas around it.
void orient(FlatChart& fc) {
    const std::vector<glm::dvec2> hull = convexHull(fc.texels);
    glm::dvec2 bestAxis(1.0, 0.0);
    double bestArea = 1e300;
    const size_t step = std::max<size_t>(1, hull.size() / 256);  // enough directions for a long hull
    for (size_t e = 0; e < hull.size(); e += step) {
        const glm::dvec2 d = hull[(e + 1) % hull.size()] - hull[e];
        if (glm::length(d) == 0.0) continue;
        const glm::dvec2 ax = glm::normalize(d), ay(-ax.y, ax.x);
        glm::dvec2 lo(1e300), hi(-1e300);
        for (const glm::dvec2& p : hull) {
            const glm::dvec2 q(glm::dot(p, ax), glm::dot(p, ay));
            lo = glm::min(lo, q), hi = glm::max(hi, q);
        }
        const double area = (hi.x - lo.x) * (hi.y - lo.y);
        if (area < bestArea) bestArea = area, bestAxis = ax;
    }
    glm::dvec2 lo(1e300), hi(-1e300);
    for (glm::dvec2& p : fc.texels) {
        p = glm::dvec2(glm::dot(p, bestAxis), -bestAxis.y * p.x + bestAxis.x * p.y);
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const bool portrait = hi.y - lo.y > hi.x - lo.x;
    for (glm::dvec2& p : fc.texels) {
        p -= lo;
        if (portrait) p = glm::dvec2(p.y, hi.x - lo.x - p.x);  // a quarter turn keeps the winding
    }
    fc.extent = portrait ? glm::dvec2(hi.y - lo.y, hi.x - lo.x) : hi - lo;
}

// Projects the chart onto the plane of its area-weighted normal. Fails (the caller splits the
// chart) when a face is beyond the angle of that normal or the projection folds over itself.
bool Charter::flatten(const std::vector<uint32_t>& tris, double cosMax, FlatChart& fc) const {
    glm::dvec3 sum(0.0);
    for (uint32_t t : tris) sum += normal_[t] * area_[t];
    const glm::dvec3 n = glm::normalize(sum);
    for (uint32_t t : tris)
        if (glm::dot(normal_[t], n) < cosMax - 1e-12) return false;
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, n)), v = glm::cross(n, u);  // u x v = n
    const glm::dvec3 origin = pos(tris[0], 0);
    std::unordered_map<uint32_t, uint32_t> local;
    std::vector<Tri2> flat(tris.size());
    fc.triangles = tris;
    for (size_t i = 0; i < tris.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const uint32_t src = I_[3 * tris[i] + uint32_t(k)];
            auto [it, added] = local.emplace(src, uint32_t(fc.vertices.size()));
            if (added) {
                const glm::dvec3 p = glm::dvec3(P_[welded_[src]]) - origin;
                fc.vertices.push_back(src);
                fc.texels.push_back(glm::dvec2(glm::dot(p, u), glm::dot(p, v)) * density_);
            }
            fc.indices.push_back(it->second);
            flat[i].p[k] = fc.texels[it->second];
        }
    if (findOverlap(flat).first >= 0) return false;
    orient(fc);
    return true;
}

}  // namespace

std::vector<FlatChart> makeCharts(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                                  const std::vector<uint32_t>& kept, double angleDegrees,
                                  double texelsPerMetre) {
    Charter charter(positions, indices, kept, texelsPerMetre);
    std::vector<FlatChart> out;
    charter.run(kept, angleDegrees, out);
    return out;
}

}  // namespace gis::lightmap::detail
