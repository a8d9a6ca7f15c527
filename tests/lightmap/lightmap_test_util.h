// Helpers for the lightmap tests: meshes in world space and the checks every atlas must pass.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "error.h"
#include "lightmap/atlas.h"
#include "scene/mesh_builders.h"
#include "scene/scene.h"
#include "scene/test_util.h"

namespace lmtest {

using gis::lightmap::Atlas;
using gis::lightmap::AtlasParams;
using gis::lightmap::MeshInput;
using gistest::errorOf;

inline MeshInput meshOf(const gis::Primitive& p, const glm::mat4& world = glm::mat4(1.0f)) {
    MeshInput m;
    for (const gis::Vertex& v : p.vertices) m.positions.push_back(glm::vec3(world * glm::vec4(v.position, 1.0f)));
    m.indices = p.indices;
    m.uv1 = p.uv1;
    return m;
}

// The built-in unit cube (faces do not share vertices) scaled to `side` metres.
inline MeshInput cube(float side = 1.0f) {
    return meshOf(gis::detail::unitCube(0), glm::scale(glm::mat4(1.0f), glm::vec3(side)));
}

inline double area2(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
inline double area3(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) { return 0.5 * glm::length(glm::cross(b - a, c - a)); }

// What every atlas must satisfy, whatever the input: chart rectangles `gutter` apart and inside
// their atlas with the gutter to the border, every vertex inside its chart's rectangle, and no two
// output triangles of one atlas overlapping (the same check the file's UVs get). A triangle far
// below a texel may round to no area in float UVs: it is left out of the overlap check and
// counted in `collapsed`.
inline void expectValidLayout(const Atlas& a, size_t* collapsed = nullptr) {
    const int g = a.params.gutter;
    for (size_t i = 0; i < a.charts.size(); ++i) {
        const auto& c = a.charts[i];
        const int side = a.atlasSizes[size_t(c.atlas)];
        EXPECT_TRUE(c.x >= g && c.y >= g && c.x + c.width + g <= side && c.y + c.height + g <= side)
            << "chart " << i << " at " << c.x << "," << c.y << " size " << c.width << "x" << c.height;
        for (size_t j = i + 1; j < a.charts.size(); ++j) {
            const auto& d = a.charts[j];
            if (d.atlas != c.atlas) continue;
            const bool apart = c.x + c.width + g <= d.x || d.x + d.width + g <= c.x ||
                               c.y + c.height + g <= d.y || d.y + d.height + g <= c.y;
            EXPECT_TRUE(apart) << "charts " << i << " and " << j << " closer than the gutter";
        }
    }
    std::vector<std::vector<glm::vec2>> uvs(a.atlasSizes.size());
    std::vector<std::vector<uint32_t>> tris(a.atlasSizes.size());
    size_t flat = 0;
    for (const auto& m : a.meshes) {
        for (size_t v = 0; v < m.uv.size(); ++v) {
            const auto& c = a.charts[size_t(m.chart[v])];
            const glm::dvec2 t = glm::dvec2(m.uv[v]) * double(a.atlasSizes[size_t(c.atlas)]);
            const double eps = 1e-3;
            EXPECT_TRUE(t.x >= c.x - eps && t.x <= c.x + c.width + eps && t.y >= c.y - eps &&
                        t.y <= c.y + c.height + eps)
                << "vertex outside its chart: " << t.x << "," << t.y;
        }
        for (size_t i = 0; i < m.indices.size(); i += 3) {
            const int chart = m.chart[m.indices[i]];
            ASSERT_TRUE(m.chart[m.indices[i + 1]] == chart && m.chart[m.indices[i + 2]] == chart);
            const size_t atlas = size_t(a.charts[size_t(chart)].atlas);
            const glm::dvec2 p0(m.uv[m.indices[i]]), p1(m.uv[m.indices[i + 1]]), p2(m.uv[m.indices[i + 2]]);
            if (area2(p0, p1, p2) == 0.0) {
                ++flat;
                continue;
            }
            for (int k = 0; k < 3; ++k) {
                tris[atlas].push_back(uint32_t(uvs[atlas].size()));
                uvs[atlas].push_back(m.uv[m.indices[i + size_t(k)]]);
            }
        }
    }
    for (size_t k = 0; k < uvs.size(); ++k) {
        const gis::lightmap::UvCheck check = gis::lightmap::checkUvCharts(uvs[k], tris[k]);
        EXPECT_TRUE(check.ok) << "atlas " << k << ": " << check.reason;
    }
    if (collapsed) *collapsed = flat;
}

// Texel area over world area of every kept triangle, over density squared: 1 for a planar chart.
inline std::vector<double> densityRatios(const Atlas& a, const std::vector<MeshInput>& in) {
    std::vector<double> r;
    const double d2 = double(a.params.texelsPerMetre) * a.params.texelsPerMetre;
    for (size_t mi = 0; mi < in.size(); ++mi) {
        const auto& m = a.meshes[mi];
        for (size_t t = 0; t < m.sourceTriangle.size(); ++t) {
            glm::dvec2 uv[3];
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = m.indices[3 * t + size_t(k)];
                uv[k] = glm::dvec2(m.uv[v]) * double(a.atlasSizes[size_t(a.charts[size_t(m.chart[v])].atlas)]);
                p[k] = glm::dvec3(in[mi].positions[m.sourceVertex[v]]);
            }
            r.push_back(area2(uv[0], uv[1], uv[2]) / (area3(p[0], p[1], p[2]) * d2));
        }
    }
    return r;
}

}  // namespace lmtest
