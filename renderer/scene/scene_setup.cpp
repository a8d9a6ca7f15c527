// Light and camera for scenes that bring none: most glTF files carry no lights (27 of the 30
// sample models render nearly black with only the 0.03 ambient) and some no usable camera.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "scene/scene_internal.h"
#include "scene/scene_lighting.h"

namespace gis {

LightingMode parseLightingMode(const std::string& s) {
    if (s == "auto") return LightingMode::Auto;
    if (s == "scene") return LightingMode::Scene;
    if (s == "default") return LightingMode::Default;
    if (s == "none") return LightingMode::None;
    throw Error("unknown lighting '" + detail::oneLine(s, 40) + "' (expected auto, scene, default or none)");
}

const char* lightingModeName(LightingMode m) {
    switch (m) {
        case LightingMode::Auto: return "auto";
        case LightingMode::Scene: return "scene";
        case LightingMode::Default: return "default";
        case LightingMode::None: return "none";
    }
    return "?";
}

namespace {

double srgbDecode(uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Linear emission texel at `uv` (nearest, repeat): the emissive texture's factor, 1 without one.
glm::dvec3 emissiveTexel(const Scene& scene, int texture, glm::vec2 uv) {
    if (texture < 0 || size_t(texture) >= scene.images.size()) return glm::dvec3(1.0);
    const Image& img = scene.images[size_t(texture)];
    if (img.width <= 0 || img.height <= 0 || img.rgba8.size() < size_t(img.width) * size_t(img.height) * 4)
        return glm::dvec3(1.0);
    auto wrap = [](float t, int n) {
        const float f = t - std::floor(t);
        return std::min(int(f * float(n)), n - 1);
    };
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    const size_t i = (size_t(wrap(uv.y, img.height)) * size_t(img.width) + size_t(wrap(uv.x, img.width))) * 4;
    return {srgbDecode(img.rgba8[i]), srgbDecode(img.rgba8[i + 1]), srgbDecode(img.rgba8[i + 2])};
}

}  // namespace

double meanEmittedRadiance(const Scene& scene) {
    // Sum of area * emitted luminance over every placed triangle, the texture read at the
    // triangle's UV centroid: an area-sampled estimate of the emitted power, which is what lights
    // the scene (a texture's unused atlas space does not dilute it).
    double area = 0.0, power = 0.0;
    for (const DrawItem& d : scene.draws) {
        if (d.primitive < 0 || size_t(d.primitive) >= scene.primitives.size()) continue;
        const Primitive& p = scene.primitives[size_t(d.primitive)];
        const Material* m = p.material >= 0 && size_t(p.material) < scene.materials.size()
                                ? &scene.materials[size_t(p.material)] : nullptr;
        const glm::dvec3 factor = m ? glm::dvec3(m->emissive) : glm::dvec3(0.0);
        const bool emits = factor != glm::dvec3(0.0);
        for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
            const Vertex* v[3] = {&p.vertices[p.indices[t]], &p.vertices[p.indices[t + 1]], &p.vertices[p.indices[t + 2]]};
            glm::vec3 w[3];
            for (int k = 0; k < 3; ++k) w[k] = glm::vec3(d.world * glm::vec4(v[k]->position, 1.0f));
            const double a = 0.5 * double(glm::length(glm::cross(w[1] - w[0], w[2] - w[0])));
            if (!std::isfinite(a)) continue;
            area += a;
            if (!emits) continue;
            const glm::dvec3 e = factor * emissiveTexel(scene, m->emissiveTexture, (v[0]->uv + v[1]->uv + v[2]->uv) / 3.0f);
            power += a * (0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z);
        }
    }
    return area > 0.0 ? power / area : 0.0;
}

bool emissionLightsScene(const Scene& scene) { return meanEmittedRadiance(scene) >= kEmitterLightingFloor; }

int feedbackBouncesFor(const Scene& scene) {
    constexpr float kResidual = 0.01f;
    float albedo = 0.0f;
    for (const Material& m : scene.materials) {
        const glm::vec3 c = glm::vec3(m.baseColorFactor) * (1.0f - m.metallicFactor);
        albedo = std::max({albedo, c.r, c.g, c.b});
    }
    if (albedo <= kResidual) return 1;
    if (albedo >= 0.93f) return kMaxFeedbackBounces;
    return std::min(int(std::ceil(std::log(kResidual) / std::log(albedo))), kMaxFeedbackBounces);
}

bool hasOwnLighting(const Scene& scene) { return !scene.lights.empty() || emissionLightsScene(scene); }

LightingMode lightingUnderEnvironment(LightingMode mode, bool environmentMap) {
    return mode == LightingMode::Auto && environmentMap ? LightingMode::Scene : mode;
}

bool applyLighting(Scene& scene, LightingMode mode) {
    if (mode == LightingMode::Scene) return false;
    if (mode == LightingMode::None) {
        scene.lights.clear();
        return false;
    }
    if (mode == LightingMode::Auto && hasOwnLighting(scene)) return false;
    scene.lights.clear();
    Light sun;
    sun.name = "default sun";
    sun.type = LightType::Directional;
    sun.intensity = kDefaultSunIrradiance;
    const float e = glm::radians(kDefaultSunElevationDegrees), a = glm::radians(kDefaultSunAzimuthDegrees);
    sun.direction = -glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
    scene.lights.push_back(sun);
    scene.background = glm::vec3(kDefaultSkyRadiance);
    return true;
}

int resolveCamera(Scene& scene, const CameraRequest& r, float aspect) {
    if (r.hasPosition) {
        const glm::vec3 forward = r.lookAt - r.position;
        if (!(glm::length(forward) > 0.0f) || !std::isfinite(glm::length(forward)))
            throw Error("--look-at must differ from --camera-pos");
        if (!(r.fovDegrees > 0.0f && r.fovDegrees < 180.0f)) throw Error("--fov must be in (0, 180) degrees");
        const glm::vec3 dir = glm::normalize(forward);
        const glm::vec3 up = std::abs(dir.y) > 0.999f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
        Camera c = defaultCamera(scene.bounds, aspect);  // near/far sized from the scene
        c.name = "command line";
        c.cameraToWorld = glm::inverse(glm::lookAt(r.position, r.lookAt, up));
        c.yfov = glm::radians(r.fovDegrees);
        // Near and far from the distance to the scene's bounds, so any placement sees all of it.
        const float radius = scene.bounds.empty() ? 1.0f : 0.5f * glm::length(scene.bounds.extent());
        const float reach = glm::length(r.position - (scene.bounds.empty() ? glm::vec3(0) : scene.bounds.center())) + radius;
        c.znear = std::max(1e-4f * reach, 1e-6f);
        c.zfar = 2.0f * reach;
        scene.cameras.push_back(c);
        return int(scene.cameras.size()) - 1;
    }
    if (r.index >= 0) {
        if (r.index >= int(scene.cameras.size()))
            throw Error("camera " + std::to_string(r.index) + " does not exist (the scene has " +
                        (scene.cameras.empty() ? std::string("no cameras; --camera auto frames it")
                                               : std::to_string(scene.cameras.size())) +
                        ")");
        return r.index;
    }
    if (r.autoFrame || scene.cameras.empty()) {
        scene.cameras.push_back(defaultCamera(scene.bounds, aspect));
        return int(scene.cameras.size()) - 1;
    }
    return 0;
}

}  // namespace gis
