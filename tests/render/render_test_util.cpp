#include "render_test_util.h"

#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

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

ImageF renderHdr(const Scene& scene, RenderSettings settings) {
    context();
    settings.hdr32 = true;
    Renderer renderer(scene, settings);
    renderer.renderFrame();
    return renderer.readHdr();
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
