#include "volume/volume_fit.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace gis {

glm::mat4 VolumeFit::worldToVoxelMatrix() const {
    return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / voxelSize())) * glm::translate(glm::mat4(1.0f), -origin);
}

glm::mat4 VolumeFit::voxelToWorldMatrix() const {
    return glm::translate(glm::mat4(1.0f), origin) * glm::scale(glm::mat4(1.0f), glm::vec3(voxelSize()));
}

VolumeFit fitVolume(const Aabb& bounds, int resolution, float marginVoxels) {
    if (resolution < 1 || resolution > 4096)
        throw Error("volume resolution " + std::to_string(resolution) + " is out of range [1, 4096]");
    if (!std::isfinite(marginVoxels) || marginVoxels < 0.0f || 2.0f * marginVoxels >= float(resolution))
        marginVoxels = 0.0f;  // a tiny grid cannot spare voxels for a margin
    VolumeFit f;
    f.resolution = resolution;
    f.bounds = bounds;
    if (bounds.empty()) {
        f.origin = glm::vec3(-0.5f);
        f.size = 1.0f;
        return f;
    }
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(bounds.min[c]) || !std::isfinite(bounds.max[c]))
            throw Error("cannot fit a volume to non-finite scene bounds");
    const glm::vec3 center = bounds.center();
    const glm::vec3 extent = bounds.extent();
    float longest = std::max({extent.x, extent.y, extent.z});
    // A point-like scene: size it from where it is, so float voxel coordinates stay meaningful.
    const float magnitude = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
    const float floorSize = std::max(magnitude * 1e-4f, 1e-30f);
    longest = std::max(longest, floorSize);
    // The cube holds `resolution - 2 * margin` voxels of scene and `margin` empty ones each side.
    f.size = longest * float(resolution) / (float(resolution) - 2.0f * marginVoxels);
    f.origin = center - glm::vec3(0.5f * f.size);
    return f;
}

namespace {

struct FacingTriangle {
    glm::vec3 p0, p1, p2;
    glm::vec3 normal;       // the mean of its vertex normals, world space
    bool doubleSided;
};

std::vector<FacingTriangle> facingTriangles(const Scene& scene) {
    std::vector<FacingTriangle> out;
    for (const DrawItem& d : scene.draws) {
        const Primitive& p = scene.primitives[size_t(d.primitive)];
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(d.world)));
        const bool doubleSided = p.material >= 0 && p.material < int(scene.materials.size()) &&
                                 scene.materials[size_t(p.material)].doubleSided;
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            FacingTriangle t;
            const Vertex* v[3] = {&p.vertices[p.indices[i]], &p.vertices[p.indices[i + 1]], &p.vertices[p.indices[i + 2]]};
            t.p0 = glm::vec3(d.world * glm::vec4(v[0]->position, 1.0f));
            t.p1 = glm::vec3(d.world * glm::vec4(v[1]->position, 1.0f));
            t.p2 = glm::vec3(d.world * glm::vec4(v[2]->position, 1.0f));
            t.normal = normalMatrix * (v[0]->normal + v[1]->normal + v[2]->normal);
            t.doubleSided = doubleSided;
            out.push_back(t);
        }
    }
    return out;
}

// Distance along the ray to the triangle (Moller & Trumbore 1997), or a negative value for none.
float hitDistance(const glm::vec3& o, const glm::vec3& dir, const FacingTriangle& t) {
    const glm::vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
    const glm::vec3 p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-30f) return -1.0f;
    const glm::vec3 s = o - t.p0;
    const float u = glm::dot(s, p) / det;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) / det;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return glm::dot(e2, q) / det;
}

// Whether the ray from `o` along `dir` enters, within `depth`, a surface that faces it, with no
// surface behind it for `skin` more: the solid of an object, not the shell of a room.
bool entersSolid(const std::vector<const FacingTriangle*>& near, const glm::vec3& o, const glm::vec3& dir,
                 float depth, float skin) {
    float entry = depth;
    const FacingTriangle* first = nullptr;
    for (const FacingTriangle* t : near) {
        const float d = hitDistance(o, dir, *t);
        if (d >= 0.0f && d <= entry) {
            entry = d;
            first = t;
        }
    }
    if (!first || !(first->doubleSided || glm::dot(first->normal, -dir) > 0.0f)) return false;
    // Past the entry by more than float noise (the quad's other triangle shares its edges).
    const float after = entry + 1e-3f * skin;
    for (const FacingTriangle* t : near) {
        const float d = hitDistance(o, dir, *t);
        if (t != first && d > after && d <= entry + skin) return false;
    }
    return true;
}

// Whether rays cast inward at face f, on a grid over it, enter the solid of the scene on the
// face over at least 1 / kOutwardFaceShare of it. Only triangles reaching that deep can be met, and
// a ray along the axis only by the triangles whose bounds, seen along it, hold its origin: each
// ray tests the triangles binned to its grid point (in the scene's order, as one list would).
bool facesOut(const std::vector<FacingTriangle>& all, const Aabb& b, int f, float depth, float skin) {
    constexpr int kSamples = 32;  // per edge of the face: a surface a voxel of a 32^3 volume wide is met
    const int a = f / 2, u = (a + 1) % 3, w = (a + 2) % 3;
    const float side = f % 2 == 0 ? -1.0f : 1.0f;
    const float plane = f % 2 == 0 ? b.min[a] : b.max[a];
    const float reach = 2.0f * depth + skin;
    const auto sample = [&](int axis, int i) {
        return b.min[axis] + (float(i) + 0.5f) / float(kSamples) * (b.max[axis] - b.min[axis]);
    };
    // The grid points within [lo, hi] (widened by a float step's worth) along one of the face's axes.
    const auto samplesWithin = [&](int axis, float lo, float hi) {
        const float step = (b.max[axis] - b.min[axis]) / float(kSamples), slack = 1e-4f * step;
        if (!(step > 0.0f)) return std::pair<int, int>{0, kSamples - 1};
        const int first = std::max(0, int(std::ceil((lo - slack - b.min[axis]) / step - 0.5f)));
        const int last = std::min(kSamples - 1, int(std::floor((hi + slack - b.min[axis]) / step - 0.5f)));
        return std::pair<int, int>{first, last};
    };
    std::vector<std::vector<const FacingTriangle*>> near(size_t(kSamples * kSamples));
    for (const FacingTriangle& t : all) {
        const float lo = std::min({t.p0[a], t.p1[a], t.p2[a]}), hi = std::max({t.p0[a], t.p1[a], t.p2[a]});
        if (!(side > 0.0f ? hi >= plane - reach : lo <= plane + reach)) continue;
        const auto [i0, i1] = samplesWithin(u, std::min({t.p0[u], t.p1[u], t.p2[u]}), std::max({t.p0[u], t.p1[u], t.p2[u]}));
        const auto [j0, j1] = samplesWithin(w, std::min({t.p0[w], t.p1[w], t.p2[w]}), std::max({t.p0[w], t.p1[w], t.p2[w]}));
        for (int i = i0; i <= i1; ++i)
            for (int j = j0; j <= j1; ++j) near[size_t(i * kSamples + j)].push_back(&t);
    }
    glm::vec3 dir(0.0f);
    dir[a] = -side;
    int solid = 0;
    for (int i = 0; i < kSamples; ++i)
        for (int j = 0; j < kSamples; ++j) {
            glm::vec3 o;
            o[a] = plane + side * depth;
            o[u] = sample(u, i);
            o[w] = sample(w, j);
            if (entersSolid(near[size_t(i * kSamples + j)], o, dir, 2.0f * depth, skin)) ++solid;
        }
    return solid * kOutwardFaceShare >= kSamples * kSamples;
}

}  // namespace

BoxFaces outwardFaces(const Scene& scene) {
    BoxFaces faces{};
    const Aabb& b = scene.bounds;
    if (b.empty()) return faces;
    const glm::vec3 e = b.extent();
    const float largest = std::max({e.x, e.y, e.z});
    const float depth = kOutwardFaceDepth * largest, skin = kOutwardSkinDepth * largest;
    if (!(depth > 0.0f) || !std::isfinite(largest)) return faces;
    const std::vector<FacingTriangle> triangles = facingTriangles(scene);
    for (int f = 0; f < 6; ++f) faces[size_t(f)] = facesOut(triangles, b, f, depth, skin);
    return faces;
}

Aabb sceneAirBounds(const Scene& scene) {
    Aabb air = scene.bounds;
    if (air.empty()) return air;
    const BoxFaces faces = outwardFaces(scene);
    const glm::vec3 e = air.extent();
    const float margin = kAirFraction * std::max({e.x, e.y, e.z});
    for (int f = 0; f < 6; ++f) {
        if (!faces[size_t(f)]) continue;
        if (f % 2 == 0)
            air.min[f / 2] -= margin;
        else
            air.max[f / 2] += margin;
    }
    return air;
}

}  // namespace gis
