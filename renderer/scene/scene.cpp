// Scene-level operations: finalizeScene (normals, tangents, bounds, validation), the default
// camera, and loadScene's dispatch between built-in scenes and glTF files.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_internal.h"

namespace gis {

namespace detail {

std::string oneLine(const std::string& s, size_t maxLen) {
    std::string out;
    out.reserve(std::min(s.size(), maxLen + 3));
    bool lastSpace = true;  // also trims leading whitespace
    for (unsigned char c : s) {
        const bool space = c < 0x20 || c == 0x7f || c == ' ';
        if (space) {
            if (!lastSpace) out.push_back(' ');
            lastSpace = true;
        } else {
            out.push_back(static_cast<char>(c));
            lastSpace = false;
        }
        if (out.size() >= maxLen) {
            out += "...";
            return out;
        }
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

glm::mat4 composeTrs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
    glm::dquat q = r;
    const double len = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (!(len > 1e-12) || !std::isfinite(len)) {
        q = glm::dquat(1.0, 0.0, 0.0, 0.0);
    } else {
        q = glm::dquat(q.w / len, q.x / len, q.y / len, q.z / len);
    }
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), t) * glm::dmat4(glm::mat3_cast(q)) *
                   glm::scale(glm::dmat4(1.0), s);
    return glm::mat4(m);
}

bool isFinite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

}  // namespace detail

namespace {

bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A normal (or tangent xyz) counts as present when it is finite and not (almost) zero.
bool usable(const glm::vec3& v) {
    return finite3(v) && glm::dot(glm::dvec3(v), glm::dvec3(v)) > 1e-20;
}

// Any unit vector perpendicular to the unit vector n.
glm::vec3 anyPerpendicular(const glm::vec3& n) {
    const glm::vec3 axis = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    glm::vec3 t = glm::cross(n, axis);
    const float len = glm::length(t);
    if (!(len > 1e-12f) || !std::isfinite(len)) return glm::vec3(1, 0, 0);
    return t / len;
}

// Normals: area-weighted face normals (in double, so huge coordinates cannot overflow)
// accumulated on every vertex whose normal is missing (zero or non-finite).
void finalizeNormals(Primitive& p) {
    const size_t nv = p.vertices.size();
    std::vector<char> missingN(nv, 0);
    bool anyMissingN = false;
    for (size_t i = 0; i < nv; ++i) {
        missingN[i] = !usable(p.vertices[i].normal);
        anyMissingN = anyMissingN || missingN[i];
    }
    std::vector<glm::dvec3> faceSum;
    glm::dvec3 total(0.0);
    if (anyMissingN) faceSum.assign(nv, glm::dvec3(0.0));
    for (size_t t = 0; anyMissingN && t + 2 < p.indices.size(); t += 3) {
        const uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
        const glm::dvec3 pa(p.vertices[a].position), pb(p.vertices[b].position),
            pc(p.vertices[c].position);
        const glm::dvec3 n = glm::cross(pb - pa, pc - pa);  // |n| = 2 * area
        if (!finite3(n)) continue;
        faceSum[a] += n;
        faceSum[b] += n;
        faceSum[c] += n;
        total += n;
    }
    glm::vec3 fallback(0.0f, 0.0f, 1.0f);
    {
        const double len = glm::length(total);
        if (len > 0.0 && std::isfinite(len)) fallback = glm::vec3(total / len);
    }
    for (size_t i = 0; i < nv; ++i) {
        Vertex& v = p.vertices[i];
        if (missingN[i]) {
            const double len = glm::length(faceSum[i]);
            glm::vec3 n = (len > 0.0 && std::isfinite(len)) ? glm::vec3(faceSum[i] / len) : fallback;
            v.normal = usable(n) ? n : fallback;
        } else {
            const glm::dvec3 n(v.normal);
            v.normal = glm::vec3(n / glm::length(n));
        }
    }
}

// Per vertex, the area-weighted tangent and bitangent directions of its triangles' UV
// derivatives; triangles with degenerate UVs add nothing.
void accumulateUvTangents(const Primitive& p, std::vector<glm::dvec3>& tSum, std::vector<glm::dvec3>& bSum) {
    const size_t nv = p.vertices.size();
    tSum.assign(nv, glm::dvec3(0.0));
    bSum.assign(nv, glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const uint32_t idx[3] = {p.indices[t], p.indices[t + 1], p.indices[t + 2]};
        const glm::dvec3 p0(p.vertices[idx[0]].position), p1(p.vertices[idx[1]].position),
            p2(p.vertices[idx[2]].position);
        const glm::dvec2 w0(p.vertices[idx[0]].uv), w1(p.vertices[idx[1]].uv),
            w2(p.vertices[idx[2]].uv);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const glm::dvec2 d1 = w1 - w0, d2 = w2 - w0;
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;  // degenerate UVs
        glm::dvec3 tan = (e1 * d2.y - e2 * d1.y) / det;
        glm::dvec3 bit = (e2 * d1.x - e1 * d2.x) / det;
        const double area = glm::length(glm::cross(e1, e2));
        const double tl = glm::length(tan), bl = glm::length(bit);
        if (!(tl > 0.0) || !(bl > 0.0) || !std::isfinite(tl) || !std::isfinite(bl) ||
            !std::isfinite(area))
            continue;
        tan *= area / tl;
        bit *= area / bl;
        for (uint32_t k : idx) {
            tSum[k] += tan;
            bSum[k] += bit;
        }
    }
}

// Tangents: keep usable given ones (orthonormalised against the normal); generate the
// missing ones from UV derivatives when the material has a normal map; otherwise (and as
// the fallback for degenerate UVs) any unit vector perpendicular to the normal.
void finalizeTangents(Primitive& p, bool wantTangents) {
    const size_t nv = p.vertices.size();
    std::vector<char> missingT(nv, 0);
    bool anyMissingT = false;
    for (size_t i = 0; i < nv; ++i) {
        const glm::vec4& t = p.vertices[i].tangent;
        missingT[i] = !usable(glm::vec3(t)) || !std::isfinite(t.w);
        anyMissingT = anyMissingT || missingT[i];
    }
    std::vector<glm::dvec3> tSum, bSum;
    if (anyMissingT && wantTangents) accumulateUvTangents(p, tSum, bSum);
    for (size_t i = 0; i < nv; ++i) {
        Vertex& v = p.vertices[i];
        const glm::dvec3 n(v.normal);
        glm::dvec3 t(0.0);
        double sign = 1.0;
        if (!missingT[i]) {
            t = glm::dvec3(glm::vec3(v.tangent));
            sign = v.tangent.w < 0.0f ? -1.0 : 1.0;
        } else if (!tSum.empty()) {
            t = tSum[i];
            sign = glm::dot(glm::cross(n, t), bSum[i]) < 0.0 ? -1.0 : 1.0;
        }
        t -= n * glm::dot(n, t);
        const double len = glm::length(t);
        glm::vec3 tf;
        if (len > 1e-12 && std::isfinite(len)) {
            tf = glm::vec3(t / len);
            if (!usable(tf)) tf = anyPerpendicular(v.normal);
        } else {
            tf = anyPerpendicular(v.normal);
        }
        v.tangent = glm::vec4(tf, static_cast<float>(sign));
    }
}

void finalizePrimitive(Primitive& p, bool wantTangents, size_t index) {
    const size_t nv = p.vertices.size();
    if (p.indices.size() % 3 != 0)
        throw Error("primitive " + std::to_string(index) + ": index count " +
                    std::to_string(p.indices.size()) + " is not a multiple of 3");
    for (size_t i = 0; i < p.indices.size(); ++i)
        if (p.indices[i] >= nv)
            throw Error("primitive " + std::to_string(index) + ": index " +
                        std::to_string(p.indices[i]) + " at position " + std::to_string(i) +
                        " is out of range (" + std::to_string(nv) + " vertices)");
    p.bounds = Aabb{};
    for (size_t i = 0; i < nv; ++i) {
        if (!finite3(p.vertices[i].position))
            throw Error("primitive " + std::to_string(index) + ": vertex " + std::to_string(i) +
                        " has a non-finite position");
        p.bounds.extend(p.vertices[i].position);
    }
    finalizeNormals(p);
    finalizeTangents(p, wantTangents);
}

}  // namespace

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const DrawItem& d : draws)
        if (d.primitive >= 0 && static_cast<size_t>(d.primitive) < primitives.size())
            n += primitives[static_cast<size_t>(d.primitive)].indices.size() / 3;
    return n;
}

void finalizeScene(Scene& scene) {
    const int nMat = static_cast<int>(scene.materials.size());
    const int nImg = static_cast<int>(scene.images.size());
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        for (int tex : {mat.baseColorTexture, mat.metallicRoughnessTexture, mat.normalTexture,
                        mat.emissiveTexture, mat.occlusionTexture})
            if (tex < -1 || tex >= nImg)
                throw Error("material " + std::to_string(m) + " refers to image " +
                            std::to_string(tex) + ", which does not exist (" +
                            std::to_string(nImg) + " images)");
    }
    for (size_t i = 0; i < scene.images.size(); ++i) {
        const Image& img = scene.images[i];
        if (img.width <= 0 || img.height <= 0 ||
            img.rgba8.size() != size_t(img.width) * size_t(img.height) * 4)
            throw Error("image " + std::to_string(i) + " has inconsistent size");
    }
    for (size_t i = 0; i < scene.primitives.size(); ++i) {
        Primitive& p = scene.primitives[i];
        if (p.material < -1 || p.material >= nMat)
            throw Error("primitive " + std::to_string(i) + " refers to material " +
                        std::to_string(p.material) + ", which does not exist");
        const bool wantTangents =
            p.material >= 0 && scene.materials[size_t(p.material)].normalTexture >= 0;
        finalizePrimitive(p, wantTangents, i);
    }
    scene.bounds = Aabb{};
    for (size_t d = 0; d < scene.draws.size(); ++d) {
        const DrawItem& item = scene.draws[d];
        if (item.primitive < 0 || static_cast<size_t>(item.primitive) >= scene.primitives.size())
            throw Error("draw " + std::to_string(d) + " refers to primitive " +
                        std::to_string(item.primitive) + ", which does not exist");
        if (!detail::isFinite(item.world))
            throw Error("draw " + std::to_string(d) + " has a non-finite world matrix");
        for (const Vertex& v : scene.primitives[size_t(item.primitive)].vertices) {
            const glm::vec3 w = glm::vec3(item.world * glm::vec4(v.position, 1.0f));
            if (!finite3(w))
                throw Error("draw " + std::to_string(d) +
                            ": world-space position overflows the float range");
            scene.bounds.extend(w);
        }
    }
}

Camera defaultCamera(const Aabb& bounds, float aspect) {
    Camera cam;
    cam.name = "default";
    glm::vec3 center(0.0f);
    float radius = 1.0f;
    if (!bounds.empty() && finite3(bounds.min) && finite3(bounds.max)) {
        center = bounds.center();
        radius = 0.5f * glm::length(bounds.extent());
        if (!(radius > 1e-6f) || !std::isfinite(radius)) radius = std::max(1e-3f, 1e-3f * glm::length(center));
    }
    if (!(aspect > 0.0f) || !std::isfinite(aspect)) aspect = 1.0f;
    cam.yfov = 0.6981317f;  // 40 degrees
    const float halfY = 0.5f * cam.yfov;
    const float halfX = std::atan(std::tan(halfY) * aspect);
    const float half = std::min(halfY, halfX);
    const float dist = radius / std::sin(half);
    // From +Z, raised 20 degrees: a flat scene (a ground plane) is not seen edge-on.
    const float elevation = glm::radians(20.0f);
    const glm::vec3 eye = center + dist * glm::vec3(0.0f, std::sin(elevation), std::cos(elevation));
    cam.cameraToWorld = glm::inverse(glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f)));
    cam.znear = std::max(0.5f * (dist - radius), 1e-4f * dist);
    cam.zfar = 2.0f * (dist + radius);
    return cam;
}

Scene loadScene(const std::string& spec) {
    static const std::string kPrefix = "builtin:";
    if (spec.compare(0, kPrefix.size(), kPrefix) == 0)
        return makeBuiltinScene(spec.substr(kPrefix.size()));
    // A file that is no glTF (an image passed by mistake) is named as such, not as broken JSON.
    const size_t dot = spec.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : spec.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext != "gltf" && ext != "glb")
        throw Error(detail::oneLine(spec, 200) + ": not a glTF file (expected a .gltf or .glb file, or builtin:NAME)");
    return loadGltfFile(spec);
}

// A perspective depth buffer stores 1 - znear/z (a 32F G-buffer depth here): its resolution at
// distance z is about 6e-8 * z / znear of z. The rasterizer rebuilds positions from depth, so a
// znear far below the scene's depth breaks shading: on the Cornell box (depth ~5) FLIP against
// znear 0.01 is 0.017 at 1e-4, 0.13 at 1e-5, 0.35 at 1e-6 and black at 1e-7. Reversed-Z
// would lift this, but touches every pass that reads depth; until then such cameras are
// refused below 1e-6 of the scene's depth and warned about below 1e-4.
std::string checkCameraDepth(const Aabb& bounds, glm::vec3 eye, float znear, const std::string& what) {
    if (bounds.empty()) return "";
    float depth = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner(c & 1 ? bounds.max.x : bounds.min.x, c & 2 ? bounds.max.y : bounds.min.y,
                               c & 4 ? bounds.max.z : bounds.min.z);
        depth = std::max(depth, glm::length(corner - eye));
    }
    if (!(depth > 0.0f) || !std::isfinite(depth)) return "";
    const double ratio = double(znear) / double(depth);
    char text[160];
    std::snprintf(text, sizeof text, ": znear %.3g is %.2g of the scene's depth from it (%.3g)", double(znear), ratio,
                  double(depth));
    const std::string problem = what + text;
    if (ratio < 1e-6) {
        std::snprintf(text, sizeof text, "%.3g", double(depth) * 1e-4);
        throw Error(problem + "; the depth buffer cannot resolve that (use znear >= " + text + ")");
    }
    if (ratio < 1e-4) return problem + "; depth precision will show in the rasterizer (a larger znear helps)";
    return "";
}

}  // namespace gis
