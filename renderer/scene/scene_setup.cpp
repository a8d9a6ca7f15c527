// Light and camera for scenes that bring none: most glTF files carry no lights (27 of the 30
// sample models render nearly black with only the 0.03 ambient) and some no usable camera.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "scene/scene_internal.h"

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

bool hasOwnLighting(const Scene& scene) {
    if (!scene.lights.empty()) return true;
    for (const Material& m : scene.materials)
        if (m.emissive != glm::vec3(0.0f)) return true;
    return false;
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
