#include "voxel_test_util.h"

#include <algorithm>
#include <cmath>

namespace gis::test {

Scene triangleScene(const std::vector<Triangle>& triangles, glm::vec3 albedo, glm::vec3 emissive) {
    Scene s;
    Material m;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.emissive = emissive;
    m.metallicFactor = 0.0f;
    m.specularFactor = 0.0f;
    s.materials.push_back(m);
    Primitive p;
    p.material = 0;
    for (const Triangle& t : triangles) {
        const glm::vec3 n = glm::cross(t.b - t.a, t.c - t.a);
        const glm::vec3 normal = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0);
        for (const glm::vec3& q : {t.a, t.b, t.c}) {
            Vertex v;
            v.position = q;
            v.normal = normal;
            p.indices.push_back(uint32_t(p.vertices.size()));
            p.vertices.push_back(v);
        }
    }
    if (!p.vertices.empty()) {
        s.primitives.push_back(p);
        s.draws.push_back(DrawItem{0, glm::mat4(1.0f)});
    }
    finalizeScene(s);
    return s;
}

std::vector<uint8_t> readVoxelsRgba8(const gl::Texture& t) {
    std::vector<uint8_t> out(size_t(t.width) * t.height * t.depth * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
    return out;
}

std::vector<float> readVoxelsRgba16f(const gl::Texture& t, int level) {
    const int w = std::max(t.width >> level, 1), h = std::max(t.height >> level, 1), d = std::max(t.depth >> level, 1);
    std::vector<float> out(size_t(w) * h * d * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(t.id(), level, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
    return out;
}

namespace {
// Projections of the triangle and the box (half size `half`) onto `axis` are disjoint.
bool separated(const glm::dvec3 (&v)[3], glm::dvec3 axis, double half) {
    if (glm::dot(axis, axis) < 1e-24) return false;  // parallel edges: no axis here
    const double p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
    const double r = half * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}
}  // namespace

bool triangleBoxOverlap(const Triangle& t, glm::dvec3 center, double half) {
    const glm::dvec3 v[3] = {glm::dvec3(t.a) - center, glm::dvec3(t.b) - center, glm::dvec3(t.c) - center};
    const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const glm::dvec3& a : axes)
        if (separated(v, a, half)) return false;
    if (separated(v, glm::cross(e[0], e[1]), half)) return false;
    for (const glm::dvec3& a : axes)
        for (const glm::dvec3& edge : e)
            if (separated(v, glm::cross(a, edge), half)) return false;
    return true;
}

std::vector<uint8_t> exactVoxels(const std::vector<Triangle>& triangles, int n, double half) {
    std::vector<uint8_t> marked(size_t(n) * n * n, 0);
    for (const Triangle& t : triangles) {
        const glm::ivec3 lo = glm::clamp(glm::ivec3(glm::floor(glm::min(t.a, glm::min(t.b, t.c)))) - 1, 0, n - 1);
        const glm::ivec3 hi = glm::clamp(glm::ivec3(glm::floor(glm::max(t.a, glm::max(t.b, t.c)))) + 1, 0, n - 1);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    if (triangleBoxOverlap(t, glm::dvec3(x, y, z) + 0.5, half)) marked[(size_t(z) * n + y) * n + x] = 1;
    }
    return marked;
}

}  // namespace gis::test
