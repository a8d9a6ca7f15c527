#include "lights.h"

#include <cmath>

namespace gis {

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
