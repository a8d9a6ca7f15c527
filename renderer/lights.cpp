#include "lights.h"

#include <algorithm>
#include <cmath>

namespace gis {

int shadowMapLayers(const std::vector<Light>& lights) {
    int layers = 0;
    for (const Light& l : lights)
        layers += l.type == LightType::Directional ? kDirectionalShadowLayers : l.type == LightType::Spot ? 1 : 0;
    return layers;
}

int shadowCubes(const std::vector<Light>& lights) {
    return int(std::count_if(lights.begin(), lights.end(), [](const Light& l) { return l.type == LightType::Point; }));
}

void checkShadowLayers(const std::vector<Light>& lights, int maxLayers, const std::string& remedy) {
    const size_t points = size_t(shadowCubes(lights)), flat = size_t(shadowMapLayers(lights));
    const size_t maxPoints = size_t(maxLayers) / 6;
    if (points > maxPoints)
        throw Error("the scene has " + std::to_string(points) + " point lights; shadow cube maps hold at most " +
                    std::to_string(maxPoints) + " (GL_MAX_ARRAY_TEXTURE_LAYERS " + std::to_string(maxLayers) +
                    " / 6): " + remedy);
    if (flat > size_t(maxLayers))
        throw Error("the scene's spot and directional lights need " + std::to_string(flat) +
                    " shadow-map layers; shadow maps hold at most " +
                    std::to_string(maxLayers) + " (GL_MAX_ARRAY_TEXTURE_LAYERS): " + remedy);
}

std::vector<GpuLight> makeGpuLights(const Scene& scene) {
    std::vector<GpuLight> out;
    for (const Light& l : scene.lights) {
        GpuLight g{};
        const int type = l.type == LightType::Directional ? kLightDirectional
                         : l.type == LightType::Point     ? kLightPoint
                                                          : kLightSpot;
        g.positionType = glm::vec4(l.position, float(type));
        const float len = glm::length(l.direction);
        g.directionRange = glm::vec4(len > 0.0f ? l.direction / len : glm::vec3(0, 0, -1), l.range);
        g.radiance = glm::vec4(l.color * l.intensity, 0.0f);
        g.cone = glm::vec4(std::cos(l.outerConeAngle), std::cos(l.innerConeAngle), -1.0f, 0.0f);
        g.shadowMatrix = glm::mat4(1.0f);
        out.push_back(g);
    }
    return out;
}

}  // namespace gis
