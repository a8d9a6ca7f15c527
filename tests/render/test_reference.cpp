// The rasterizer's direct lighting of builtin:cornell against Blender Cycles' direct-lighting pass
// of the same scene (shared/assets/reference/refs/cornell_point/direct.exr, 256x256, 2048 spp).
//
// Cycles averages each pixel over its footprint and casts hard shadows from the zero-radius point
// light; the rasterizer samples the pixel centre once and filters its shadow map (PCF). So pixels
// near geometric edges and near shadow boundaries are masked out, using a CPU ray cast of the same
// scene: a pixel is kept only if every pixel within EDGE_RADIUS sees the same face, and every pixel
// within PENUMBRA_RADIUS has the same visibility to the light. Means are then compared per face.
#include <cstdio>
#include <map>

#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 256;
constexpr int EDGE_RADIUS = 1;
constexpr int PENUMBRA_RADIUS = 3;
constexpr double kTolerance = 0.03;  // relative, per region mean (reference noise is ~0.2% per region)

struct Triangle {
    glm::dvec3 a, b, c, n;
    int region;  // draw index * 8 + face id
};

std::vector<Triangle> worldTriangles(const Scene& s) {
    std::vector<Triangle> out;
    for (size_t d = 0; d < s.draws.size(); ++d) {
        const Primitive& p = s.primitives[s.draws[d].primitive];
        const glm::dmat4 m(s.draws[d].world);
        std::vector<glm::dvec3> faceNormals;
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            Triangle t;
            t.a = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i]].position), 1.0));
            t.b = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i + 1]].position), 1.0));
            t.c = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i + 2]].position), 1.0));
            t.n = glm::normalize(glm::cross(t.b - t.a, t.c - t.a));
            // Faces of a box: triangles with the same normal belong to the same face.
            int face = -1;
            for (size_t f = 0; f < faceNormals.size(); ++f)
                if (glm::dot(faceNormals[f], t.n) > 0.999) face = int(f);
            if (face < 0) {
                face = int(faceNormals.size());
                faceNormals.push_back(t.n);
            }
            t.region = int(d) * 8 + face;
            out.push_back(t);
        }
    }
    return out;
}

// Moller-Trumbore; returns the distance or -1.
double intersect(const Triangle& t, glm::dvec3 o, glm::dvec3 d) {
    const glm::dvec3 e1 = t.b - t.a, e2 = t.c - t.a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-14) return -1.0;
    const glm::dvec3 s = o - t.a;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) return -1.0;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det;
    if (v < 0.0 || u + v > 1.0) return -1.0;
    const double dist = glm::dot(e2, q) / det;
    return dist > 1e-9 ? dist : -1.0;
}

struct Hit {
    int region = -1;
    bool lit = false;
};

TEST(Reference, CornellDirectLightingMatchesCycles) {
    const std::string refPath = std::string(GIS_SHARED_DIR) + "/assets/reference/refs/cornell_point/direct.exr";
    const ImageF ref = readExr(refPath);
    ASSERT_EQ(ref.width, kSize);
    ASSERT_EQ(ref.height, kSize);

    const Scene scene = makeBuiltinScene("cornell");
    ASSERT_EQ(scene.lights.size(), 1u);
    RenderSettings r;
    r.width = r.height = kSize;
    r.ambient = glm::vec3(0.0f);
    const ImageF img = renderHdr(scene, r);

    // CPU ray cast through every pixel centre: visible face and visibility to the light.
    const std::vector<Triangle> tris = worldTriangles(scene);
    const CameraMatrices cam = cameraMatrices(scene, 0, 1.0f);
    const glm::dvec3 light(scene.lights[0].position);
    std::vector<Hit> hits(size_t(kSize) * kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const glm::vec2 ndc((x + 0.5f) / kSize * 2.0f - 1.0f, 1.0f - (y + 0.5f) / kSize * 2.0f);
            const glm::vec4 far = cam.invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::dvec3 o(cam.position);
            const glm::dvec3 d = glm::normalize(glm::dvec3(far) / double(far.w) - o);
            double best = 1e30;
            const Triangle* hit = nullptr;
            for (const Triangle& t : tris) {
                const double dist = intersect(t, o, d);
                if (dist > 0.0 && dist < best) { best = dist; hit = &t; }
            }
            if (!hit) continue;
            Hit& h = hits[size_t(y) * kSize + x];
            h.region = hit->region;
            const glm::dvec3 p = o + d * best + hit->n * 1e-6;
            const glm::dvec3 toLight = light - p;
            const double lightDist = glm::length(toLight);
            h.lit = glm::dot(toLight, hit->n) > 0.0;
            for (const Triangle& t : tris) {
                if (!h.lit) break;
                const double dist = intersect(t, p, toLight / lightDist);
                if (dist > 0.0 && dist < lightDist - 1e-6) h.lit = false;
            }
        }

    struct Sum { double ours[3] = {}, cycles[3] = {}; int n = 0; };
    std::map<int, Sum> regions;
    int kept = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const Hit& h = hits[size_t(y) * kSize + x];
            if (h.region < 0) continue;
            bool keep = true;
            for (int j = -PENUMBRA_RADIUS; j <= PENUMBRA_RADIUS && keep; ++j)
                for (int i = -PENUMBRA_RADIUS; i <= PENUMBRA_RADIUS && keep; ++i) {
                    const int xi = x + i, yj = y + j;
                    if (xi < 0 || yj < 0 || xi >= kSize || yj >= kSize) { keep = false; break; }
                    const Hit& o = hits[size_t(yj) * kSize + xi];
                    if (o.lit != h.lit) keep = false;
                    if (std::abs(i) <= EDGE_RADIUS && std::abs(j) <= EDGE_RADIUS && o.region != h.region) keep = false;
                }
            if (!keep) continue;
            Sum& s = regions[h.region];
            for (int c = 0; c < 3; ++c) {
                s.ours[c] += img.at(x, y)[c];
                s.cycles[c] += ref.at(x, y)[c];
            }
            ++s.n;
            ++kept;
        }

    std::printf("%-8s %6s %28s %28s %8s\n", "region", "pixels", "ours (r g b)", "cycles (r g b)", "error");
    int compared = 0, unlit = 0;
    double worst = 0.0;
    for (const auto& [region, s] : regions) {
        if (s.n < 30) continue;  // slivers: too few pixels for a stable mean
        const double ours = s.ours[0] + s.ours[1] + s.ours[2], cycles = s.cycles[0] + s.cycles[1] + s.cycles[2];
        if (cycles / (3.0 * s.n) < 1e-3) {  // a face turned away from the light: both must be ~0
            std::printf("%3d/%-4d %6d   unlit: ours %.2e, cycles %.2e\n", region / 8, region % 8, s.n,
                        ours / (3.0 * s.n), cycles / (3.0 * s.n));
            EXPECT_LT(ours / (3.0 * s.n), 1e-3) << "region " << region;
            ++unlit;
            continue;
        }
        const double err = std::abs(ours - cycles) / cycles;
        worst = std::max(worst, err);
        std::printf("%3d/%-4d %6d %9.5f %9.5f %9.5f %9.5f %9.5f %9.5f %7.2f%%\n", region / 8, region % 8, s.n,
                    s.ours[0] / s.n, s.ours[1] / s.n, s.ours[2] / s.n, s.cycles[0] / s.n, s.cycles[1] / s.n,
                    s.cycles[2] / s.n, 100.0 * err);
        EXPECT_LT(err, kTolerance) << "draw " << region / 8 << " face " << region % 8;
        ++compared;
    }
    std::printf("%d pixels kept, %d lit regions compared, %d unlit, worst %.2f%% (tolerance %.0f%%)\n", kept,
                compared, unlit, 100.0 * worst, 100.0 * kTolerance);
    // Lit: floor, ceiling, back, left, right walls, the tall block's front, the short block's top.
    EXPECT_GE(compared, 7);
    EXPECT_GT(kept, kSize * kSize / 3);
}

}  // namespace
}  // namespace gis::test
