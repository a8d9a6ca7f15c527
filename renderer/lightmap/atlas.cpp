#include "lightmap/atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "error.h"
#include "lightmap/charts.h"
#include "lightmap/content_id.h"
#include "lightmap/pack.h"
#include "scene/scene.h"

namespace gis::lightmap {
namespace {

std::string num(double v) {
    std::ostringstream s;
    s.precision(4);
    s << v;
    return s.str();
}

[[noreturn]] void fail(const std::string& what) { throw Error("lightmap atlas: " + what); }

void checkParams(const AtlasParams& p) {
    if (!std::isfinite(p.texelsPerMetre) || p.texelsPerMetre <= 0.0f)
        fail("texelsPerMetre " + num(p.texelsPerMetre) + " must be a finite number above 0");
    // At 90 degrees or more a chart's faces could project edge-on or flipped.
    if (!(p.chartAngleDegrees > 0.0f && p.chartAngleDegrees < 90.0f))
        fail("chartAngleDegrees " + num(p.chartAngleDegrees) + " must lie in (0, 90)");
    if (p.maxAtlasSize < 16 || p.maxAtlasSize > 16384)
        fail("maxAtlasSize " + std::to_string(p.maxAtlasSize) + " must lie in [16, 16384]");
    if (p.maxAtlases < 1 || p.maxAtlases > 64)
        fail("maxAtlases " + std::to_string(p.maxAtlases) + " must lie in [1, 64]");
    if (p.gutter < 0 || 4 * p.gutter >= p.maxAtlasSize)
        fail("gutter " + std::to_string(p.gutter) + " must lie in [0, maxAtlasSize/4)");
}

// The triangles with area, and their world area. Degenerate triangles get no texels and are
// counted as skipped: those whose height is below 1e-6 of their longest edge, about eight float
// steps, where the corners' rounding decides the normal.
std::vector<uint32_t> keptTriangles(const MeshInput& m, size_t mesh, double& area) {
    const std::string where = "mesh " + std::to_string(mesh);
    if (m.indices.size() % 3 != 0)
        fail(where + ": index count " + std::to_string(m.indices.size()) + " is not a multiple of 3");
    if (!m.uv1.empty() && m.uv1.size() != m.positions.size())
        fail(where + ": " + std::to_string(m.uv1.size()) + " TEXCOORD_1 values for " +
             std::to_string(m.positions.size()) + " positions");
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const glm::vec3& p = m.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(where + ": position of vertex " + std::to_string(v) + " is not finite (NaN or Inf)");
    }
    std::vector<uint32_t> kept;
    area = 0.0;
    for (size_t t = 0; t < m.indices.size() / 3; ++t) {
        glm::dvec3 c[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = m.indices[3 * t + size_t(k)];
            if (v >= m.positions.size())
                fail(where + ": index " + std::to_string(v) + " of triangle " + std::to_string(t) +
                     " is out of range (" + std::to_string(m.positions.size()) + " vertices)");
            c[k] = glm::dvec3(m.positions[v]);
        }
        const double a = 0.5 * glm::length(glm::cross(c[1] - c[0], c[2] - c[0]));
        const double edge = std::max({glm::length(c[1] - c[0]), glm::length(c[2] - c[1]), glm::length(c[0] - c[2])});
        if (a > 0.5e-6 * edge * edge && std::isfinite(a)) {
            kept.push_back(uint32_t(t));
            area += a;
        }
    }
    return kept;
}

// What one mesh brings to the packing: its charts in texels, or the file's layout as one.
struct MeshCharts {
    std::vector<detail::FlatChart> charts;
    bool fromFile = false;
};

// The file's TEXCOORD_1 as one chart: the bounding box of the kept triangles' UVs, scaled so
// that its mean texel density is the requested one (sqrt of world over UV area, times density).
detail::FlatChart fileChart(const MeshInput& m, const std::vector<uint32_t>& kept, double worldArea, double density) {
    detail::FlatChart fc;
    std::vector<int> local(m.positions.size(), -1);
    glm::dvec2 lo(1e300), hi(-1e300);
    double uvArea = 0.0;
    for (uint32_t t : kept) {
        glm::dvec2 c[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = m.indices[3 * t + uint32_t(k)];
            c[k] = glm::dvec2(m.uv1[v]);
            lo = glm::min(lo, c[k]), hi = glm::max(hi, c[k]);
            if (local[v] < 0) {
                local[v] = int(fc.vertices.size());
                fc.vertices.push_back(v);
            }
            fc.indices.push_back(uint32_t(local[v]));
        }
        uvArea += 0.5 * std::abs((c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x));
        fc.triangles.push_back(t);
    }
    const double scale = std::sqrt(worldArea / uvArea) * density;
    for (uint32_t v : fc.vertices) fc.texels.push_back((glm::dvec2(m.uv1[v]) - lo) * scale);
    fc.extent = (hi - lo) * scale;
    return fc;
}

MeshCharts chartsOf(const MeshInput& m, const std::vector<uint32_t>& kept, double area, const AtlasParams& p,
                    MeshAtlas& out) {
    MeshCharts mc;
    if (p.useFileUvs && !m.uv1.empty()) {
        std::vector<uint32_t> tris;
        for (uint32_t t : kept) tris.insert(tris.end(), m.indices.begin() + 3 * t, m.indices.begin() + 3 * t + 3);
        const UvCheck check = checkUvCharts(m.uv1, tris);
        if (check.ok) {
            mc.charts.push_back(fileChart(m, kept, area, p.texelsPerMetre));
            mc.fromFile = true;
            return mc;
        }
        out.fileUvsRejected = "TEXCOORD_1 not used: " + check.reason;
        if (kept.size() * 3 != m.indices.size())
            out.fileUvsRejected += " (triangle numbers count only the " + std::to_string(kept.size()) +
                                   " triangles with area)";
    }
    mc.charts = detail::makeCharts(m.positions, m.indices, kept, p.chartAngleDegrees, p.texelsPerMetre);
    return mc;
}

// Texels are sized before any is allocated: the charts together need at least the surface area
// times the density squared.
void checkBudget(double area, const AtlasParams& p) {
    const double need = area * double(p.texelsPerMetre) * double(p.texelsPerMetre);
    const double have = double(p.maxAtlases) * double(p.maxAtlasSize) * double(p.maxAtlasSize);
    if (!(need <= have))
        fail("texelsPerMetre " + num(p.texelsPerMetre) + " needs " + num(need) + " texels for " + num(area) +
             " m^2 of surface, more than maxAtlases " + std::to_string(p.maxAtlases) + " x maxAtlasSize " +
             std::to_string(p.maxAtlasSize) + "^2 = " + num(have) + "; lower texelsPerMetre (below " +
             num(p.texelsPerMetre * std::sqrt(have / need)) + ")");
}

std::string hashOf(const Atlas& a) {
    ContentId f;
    const AtlasParams& p = a.params;
    const int ints[] = {p.maxAtlasSize, p.maxAtlases, p.gutter, p.useFileUvs ? 1 : 0};
    const float floats[] = {p.texelsPerMetre, p.chartAngleDegrees};
    f.add(ints, sizeof ints);
    f.add(floats, sizeof floats);
    f.vec(a.atlasSizes);
    for (const Chart& c : a.charts) {
        const int v[] = {c.mesh, c.atlas, c.x, c.y, c.width, c.height, c.triangles, c.fromFile ? 1 : 0};
        f.add(v, sizeof v);
    }
    for (const MeshAtlas& m : a.meshes) {
        f.vec(m.sourceVertex), f.vec(m.chart), f.vec(m.uv), f.vec(m.indices), f.vec(m.sourceTriangle);
    }
    return f.hex();
}

}  // namespace

namespace {

// Writes the placed charts of every mesh: vertices per chart, UVs in their atlas, chart records.
void emit(const std::vector<MeshCharts>& charts, const detail::Packing& packing, Atlas& a) {
    size_t g = 0;
    for (size_t mesh = 0; mesh < charts.size(); ++mesh) {
        MeshAtlas& out = a.meshes[mesh];
        out.fileUvs = charts[mesh].fromFile;
        for (const detail::FlatChart& fc : charts[mesh].charts) {
            const detail::Placement& at = packing.places[g++];
            const double side = a.atlasSizes[size_t(at.atlas)];
            const uint32_t base = uint32_t(out.sourceVertex.size());
            for (size_t k = 0; k < fc.vertices.size(); ++k) {
                out.sourceVertex.push_back(fc.vertices[k]);
                out.chart.push_back(int(a.charts.size()));
                out.uv.push_back(glm::vec2((fc.texels[k] + glm::dvec2(at.at)) / side));
            }
            for (uint32_t i : fc.indices) out.indices.push_back(base + i);
            out.sourceTriangle.insert(out.sourceTriangle.end(), fc.triangles.begin(), fc.triangles.end());
            for (size_t t = 0; t < fc.triangles.size(); ++t) {
                const glm::dvec2 p0 = fc.texels[fc.indices[3 * t]], p1 = fc.texels[fc.indices[3 * t + 1]],
                                 p2 = fc.texels[fc.indices[3 * t + 2]];
                a.chartTexels += 0.5 * std::abs((p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x));
            }
            Chart c;
            c.mesh = int(mesh), c.atlas = at.atlas, c.x = at.at.x, c.y = at.at.y;
            c.width = std::max(1, int(std::ceil(fc.extent.x))), c.height = std::max(1, int(std::ceil(fc.extent.y)));
            c.triangles = int(fc.triangles.size());
            c.fromFile = charts[mesh].fromFile;
            a.charts.push_back(c);
        }
    }
}

}  // namespace

double Atlas::fill() const {
    double texels = 0.0;
    for (int s : atlasSizes) texels += double(s) * double(s);
    return texels > 0.0 ? chartTexels / texels : 0.0;
}

Atlas buildAtlas(const std::vector<MeshInput>& meshes, const AtlasParams& params) {
    checkParams(params);
    Atlas a;
    a.params = params;
    a.meshes.resize(meshes.size());
    std::vector<std::vector<uint32_t>> kept(meshes.size());
    std::vector<double> area(meshes.size());
    double total = 0.0;
    for (size_t i = 0; i < meshes.size(); ++i) {
        kept[i] = keptTriangles(meshes[i], i, area[i]);
        a.meshes[i].skippedTriangles = int(meshes[i].indices.size() / 3 - kept[i].size());
        total += area[i];
    }
    if (!(total > 0.0)) fail("no triangle has area (" + std::to_string(meshes.size()) + " meshes): nothing to light");
    checkBudget(total, params);
    std::vector<MeshCharts> charts(meshes.size());
    std::vector<glm::ivec2> sizes;
    for (size_t i = 0; i < meshes.size(); ++i) {
        if (kept[i].empty()) continue;
        charts[i] = chartsOf(meshes[i], kept[i], area[i], params, a.meshes[i]);
        for (const detail::FlatChart& fc : charts[i].charts) {
            // Checked in floating point: a long sliver can outgrow an atlas that its area fits.
            if (!(fc.extent.x <= params.maxAtlasSize && fc.extent.y <= params.maxAtlasSize))
                fail("texelsPerMetre " + num(params.texelsPerMetre) + " makes a chart of mesh " + std::to_string(i) +
                     " " + num(fc.extent.x) + "x" + num(fc.extent.y) + " texels, more than maxAtlasSize " +
                     std::to_string(params.maxAtlasSize));
            sizes.push_back(glm::max(glm::ivec2(1), glm::ivec2(glm::ceil(fc.extent))));
        }
    }
    detail::Packing packing;
    try {
        packing = detail::pack(sizes, params.gutter, params.maxAtlasSize, params.maxAtlases);
    } catch (const Error& e) {
        fail(std::string(e.what()) + " at texelsPerMetre " + num(params.texelsPerMetre) +
             "; lower texelsPerMetre or raise maxAtlasSize or maxAtlases");
    }
    a.atlasSizes = packing.atlasSizes;
    emit(charts, packing, a);
    a.hash = hashOf(a);
    return a;
}

std::vector<MeshInput> meshesFromScene(const Scene& scene) {
    std::vector<MeshInput> out;
    for (const DrawItem& d : scene.draws) {
        const Primitive& p = scene.primitives[size_t(d.primitive)];
        MeshInput m;
        m.positions.reserve(p.vertices.size());
        for (const Vertex& v : p.vertices) m.positions.push_back(glm::vec3(d.world * glm::vec4(v.position, 1.0f)));
        m.indices = p.indices;
        m.uv1 = p.uv1;
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace gis::lightmap
