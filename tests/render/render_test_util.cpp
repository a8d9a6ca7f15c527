#include "render_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "environment.h"

namespace gis::test {

GlContext& context() {
    static std::unique_ptr<GlContext> ctx = [] {
        ContextOptions o;
        const char* env = std::getenv("GIS_TEST_BACKEND");
        o.backend = parseBackend(env && *env ? env : "auto");
        return createContext(o);
    }();
    return *ctx;
}

Material lambert(glm::vec3 albedo, bool doubleSided) {
    Material m;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 1.0f;
    m.specularFactor = 0.0f;
    m.doubleSided = doubleSided;
    return m;
}

void addQuad(Scene& scene, glm::vec3 center, glm::vec3 normal, float size, int material) {
    normal = glm::normalize(normal);
    glm::vec3 t = std::abs(normal.y) < 0.9f ? glm::normalize(glm::cross(glm::vec3(0, 1, 0), normal))
                                            : glm::normalize(glm::cross(glm::vec3(1, 0, 0), normal));
    glm::vec3 b = glm::cross(normal, t);
    Primitive p;
    const float h = 0.5f * size;
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const glm::vec2& c : corners) {
        Vertex v;
        v.position = center + (t * c.x + b * c.y) * h;
        v.normal = normal;
        v.uv = c * 0.5f + 0.5f;
        p.vertices.push_back(v);
    }
    // Counter-clockwise seen from the side the normal points to.
    const bool ccw = glm::dot(glm::cross(t, b), normal) > 0.0f;
    p.indices = ccw ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
    p.material = material;
    scene.primitives.push_back(p);
    scene.draws.push_back({int(scene.primitives.size()) - 1, glm::mat4(1.0f)});
}

Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfovDegrees) {
    Camera c;
    glm::vec3 dir = glm::normalize(target - eye);
    glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
    c.yfov = glm::radians(yfovDegrees);
    c.znear = 0.01f;
    c.zfar = 100.0f;
    return c;
}

Scene oneTriangleScene() {
    Scene one;
    one.materials.push_back(lambert(glm::vec3(0.8f)));
    addQuad(one, glm::vec3(0.0f), glm::vec3(0, 0, 1), 1.0f, 0);
    one.primitives[0].indices.resize(3);
    one.cameras.push_back(lookAtCamera({0, 0, 2}, {0, 0, 0}));
    Light l;
    l.type = LightType::Point;
    l.position = {0.2f, 0.2f, 1.0f};
    one.lights.push_back(l);
    finalizeScene(one);
    return one;
}

ImageF renderHdr(const Scene& scene, RenderSettings settings, int maxFrames) {
    context();
    settings.hdr32 = true;
    Renderer renderer(scene, settings);
    int frames = 0;
    do renderer.renderFrame();
    while (!renderer.converged() && ++frames != maxFrames);  // progressive methods: until every sample is in
    const std::string nonFinite = renderer.nonFiniteReport();
    if (!nonFinite.empty()) ADD_FAILURE() << scene.name << " with --gi " << settings.gi << ": " << nonFinite;
    return renderer.readHdr();
}

std::vector<bool> emitterPixels(const Scene& scene, RenderSettings settings) {
    settings.gi = "none";
    settings.view = "emission";
    settings.background = glm::vec3(0.0f);
    settings.environment.clear();
    const ImageF emission = renderHdr(scene, settings);
    std::vector<bool> seen(size_t(emission.width) * emission.height, false);
    for (int y = 0; y < emission.height; ++y)
        for (int x = 0; x < emission.width; ++x) {
            const float* p = emission.at(x, y);
            seen[size_t(y) * emission.width + x] = p[0] + p[1] + p[2] > 0.0f;
        }
    return grownByOnePixel(seen, emission.width, emission.height);
}

std::vector<bool> grownByOnePixel(const std::vector<bool>& mask, int width, int height) {
    std::vector<bool> grown(mask.size(), false);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!mask[size_t(y) * width + x]) continue;
            for (int j = std::max(0, y - 1); j <= std::min(height - 1, y + 1); ++j)
                for (int i = std::max(0, x - 1); i <= std::min(width - 1, x + 1); ++i) grown[size_t(j) * width + i] = true;
        }
    return grown;
}

double meanRgbExcept(const ImageF& img, const std::vector<bool>& skip) {
    double sum = 0.0;
    for (size_t p = 0; p < skip.size(); ++p)
        if (!skip[p]) sum += img.rgba[4 * p] + img.rgba[4 * p + 1] + img.rgba[4 * p + 2];
    return sum / (3.0 * double(skip.size()));
}

double meanAround(const ImageF& img, int x, int y, int r, int c) {
    double sum = 0.0;
    int n = 0;
    for (int j = y - r; j <= y + r; ++j)
        for (int i = x - r; i <= x + r; ++i)
            if (i >= 0 && j >= 0 && i < img.width && j < img.height) {
                sum += img.at(i, j)[c];
                ++n;
            }
    return n ? sum / n : 0.0;
}

glm::ivec2 projectToPixel(const Scene& scene, const RenderSettings& settings, glm::vec3 p) {
    CameraMatrices m = cameraMatrices(scene, settings.camera, float(settings.width) / float(settings.height));
    glm::vec4 clip = m.viewProj * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int(std::floor((ndc.x * 0.5f + 0.5f) * settings.width)),
            int(std::floor((0.5f - ndc.y * 0.5f) * settings.height))};
}

}  // namespace gis::test

namespace gis::test {

namespace {

struct WorldTriangle {
    glm::dvec3 a, b, c, n;
    int region;
};

std::vector<WorldTriangle> worldTriangles(const Scene& s) {
    std::vector<WorldTriangle> out;
    for (size_t d = 0; d < s.draws.size(); ++d) {
        const Primitive& p = s.primitives[s.draws[d].primitive];
        const glm::dmat4 m(s.draws[d].world);
        std::vector<glm::dvec3> planeNormals;  // faces of a box: triangles with the same normal
        for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
            WorldTriangle t;
            t.a = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i]].position), 1.0));
            t.b = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i + 1]].position), 1.0));
            t.c = glm::dvec3(m * glm::dvec4(glm::dvec3(p.vertices[p.indices[i + 2]].position), 1.0));
            const glm::dvec3 n = glm::cross(t.b - t.a, t.c - t.a);
            if (glm::length(n) == 0.0) continue;
            t.n = glm::normalize(n);
            int face = -1;
            for (size_t f = 0; f < planeNormals.size(); ++f)
                if (glm::dot(planeNormals[f], t.n) > 0.999) face = int(f);
            if (face < 0) {
                face = int(planeNormals.size());
                planeNormals.push_back(t.n);
            }
            t.region = int(d) * 8 + std::min(face, 7);
            out.push_back(t);
        }
    }
    return out;
}

// Moller-Trumbore in double precision; the distance, or -1.
double intersect(const WorldTriangle& t, glm::dvec3 o, glm::dvec3 d) {
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

}  // namespace

std::vector<PixelHit> castPixels(const Scene& scene, int camera, int width, int height, const glm::vec3* light) {
    const std::vector<WorldTriangle> tris = worldTriangles(scene);
    const CameraMatrices cam = cameraMatrices(scene, camera, float(width) / float(height));
    std::vector<PixelHit> hits(size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec2 ndc((x + 0.5f) / width * 2.0f - 1.0f, 1.0f - (y + 0.5f) / height * 2.0f);
            const glm::dvec4 nearP = glm::dmat4(cam.invViewProj) * glm::dvec4(ndc, -1.0, 1.0);
            const glm::dvec4 farP = glm::dmat4(cam.invViewProj) * glm::dvec4(ndc, 0.0, 1.0);
            const glm::dvec3 o = glm::dvec3(nearP) / nearP.w;
            const glm::dvec3 d = glm::normalize(glm::dvec3(farP) / farP.w - o);
            double best = 1e300;
            const WorldTriangle* hit = nullptr;
            for (const WorldTriangle& t : tris) {
                const double dist = intersect(t, o, d);
                if (dist > 0.0 && dist < best) {
                    best = dist;
                    hit = &t;
                }
            }
            if (!hit) continue;
            PixelHit& h = hits[size_t(y) * width + x];
            h.region = hit->region;
            if (!light) continue;
            const glm::dvec3 n = glm::dot(hit->n, d) < 0.0 ? hit->n : -hit->n;
            const glm::dvec3 p = o + d * best + n * 1e-6;
            const glm::dvec3 toLight = glm::dvec3(*light) - p;
            const double lightDist = glm::length(toLight);
            h.lit = glm::dot(toLight, hit->n) > 0.0;
            for (const WorldTriangle& t : tris) {
                if (!h.lit) break;
                const double dist = intersect(t, p, toLight / lightDist);
                if (dist > 0.0 && dist < lightDist - 1e-6) h.lit = false;
            }
        }
    return hits;
}

std::vector<bool> interiorPixels(const std::vector<PixelHit>& hits, int width, int height, int edgeRadius,
                                 int shadowRadius) {
    std::vector<bool> keep(hits.size(), false);
    const int r = std::max(edgeRadius, shadowRadius);
    for (int y = r; y < height - r; ++y)
        for (int x = r; x < width - r; ++x) {
            const PixelHit& h = hits[size_t(y) * width + x];
            bool ok = h.region >= 0;
            for (int j = -r; j <= r && ok; ++j)
                for (int i = -r; i <= r && ok; ++i) {
                    const PixelHit& o = hits[size_t(y + j) * width + x + i];
                    if (std::abs(i) <= shadowRadius && std::abs(j) <= shadowRadius && o.lit != h.lit) ok = false;
                    if (std::abs(i) <= edgeRadius && std::abs(j) <= edgeRadius && o.region != h.region) ok = false;
                }
            keep[size_t(y) * width + x] = ok;
        }
    return keep;
}

Scene scaledScene(const Scene& in, float scale) {
    Scene s = in;
    const glm::mat4 m = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
    for (DrawItem& d : s.draws) d.world = m * d.world;
    for (Camera& c : s.cameras) {
        c.cameraToWorld[3] = glm::vec4(glm::vec3(c.cameraToWorld[3]) * scale, 1.0f);
        c.znear *= scale;
        c.zfar *= scale;
    }
    for (Light& l : s.lights) {
        l.position *= scale;
        if (l.type != LightType::Directional) l.intensity *= scale * scale;
        l.range *= scale;
    }
    finalizeScene(s);
    return s;
}

bool allFinite(const ImageF& img) {
    for (float v : img.rgba)
        if (!std::isfinite(v)) return false;
    return true;
}

double regionMean(const ImageF& img, const std::vector<PixelHit>& hits, const std::vector<bool>& interior, int region,
                  int channel) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
        if (!interior[i] || hits[i].region != region) continue;
        const float* p = &img.rgba[i * 4];
        sum += channel < 0 ? (p[0] + p[1] + p[2]) / 3.0 : p[channel];
        ++n;
    }
    return n ? sum / n : 0.0;
}

double darkOverLitRoom(const ImageF& img, double* litSum) {
    double sums[2] = {0.0, 0.0};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const int side = x < img.width * 45 / 100 ? 0 : x > img.width * 55 / 100 ? 1 : -1;
            if (side >= 0) sums[side] += double(img.at(x, y)[0]) + img.at(x, y)[1] + img.at(x, y)[2];
        }
    if (litSum) *litSum = sums[0];
    return sums[0] > 0.0 ? sums[1] / sums[0] : 0.0;
}

double interiorRmse(const ImageF& a, const ImageF& b, const std::vector<bool>& interior) {
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < interior.size(); ++i) {
        if (!interior[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = a.rgba[i * 4 + c] - b.rgba[i * 4 + c];
            sum += d * d;
        }
        n += 3;
    }
    return std::sqrt(sum / std::max(n, 1));
}

double blockRmse(const ImageF& a, const ImageF& b, const std::vector<bool>& interior, int block) {
    double sum = 0.0;
    int weight = 0;
    for (int by = 0; by < a.height; by += block)
        for (int bx = 0; bx < a.width; bx += block) {
            double d[3] = {0.0, 0.0, 0.0};
            int n = 0;
            for (int y = by; y < std::min(by + block, a.height); ++y)
                for (int x = bx; x < std::min(bx + block, a.width); ++x) {
                    const size_t i = size_t(y) * a.width + x;
                    if (!interior[i]) continue;
                    for (int c = 0; c < 3; ++c) d[c] += a.rgba[i * 4 + c] - b.rgba[i * 4 + c];
                    ++n;
                }
            if (n == 0) continue;
            for (double e : d) sum += n * (e / n) * (e / n);
            weight += 3 * n;
        }
    return std::sqrt(sum / std::max(weight, 1));
}

void writeHdrTexels(const std::string& path, int width, int height, const std::function<glm::vec3(glm::vec2)>& radiance) {
    std::ofstream f(path, std::ios::binary);
    f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << height << " +X " << width << "\n";
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 c = radiance({(x + 0.5f) / float(width), (y + 0.5f) / float(height)});
            const float m = std::max(c.r, std::max(c.g, c.b));
            unsigned char rgbe[4] = {0, 0, 0, 0};
            if (m > 1e-32f) {
                int e = 0;
                const float scale = std::frexp(m, &e) * 256.0f / m;
                rgbe[0] = (unsigned char)(c.r * scale), rgbe[1] = (unsigned char)(c.g * scale),
                rgbe[2] = (unsigned char)(c.b * scale), rgbe[3] = (unsigned char)(e + 128);
            }
            f.write(reinterpret_cast<const char*>(rgbe), 4);
        }
}

void writeHdr(const std::string& path, int width, int height, const std::function<glm::vec3(glm::vec3)>& radiance) {
    writeHdrTexels(path, width, height, [&](glm::vec2 uv) { return radiance(equirectToDirection(uv)); });
}

}  // namespace gis::test
