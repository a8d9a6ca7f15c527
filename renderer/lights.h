// Punctual lights as the shaders see them (shaders/lights.glsl). Shared by the rasterizer's
// lighting (with shadow-map fields filled in by the shadow pass) and the ray tracers (none).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace gis {

constexpr int kLightDirectional = 0, kLightPoint = 1, kLightSpot = 2;

struct GpuLight {  // std430, mirrors shaders/lights.glsl
    glm::vec4 positionType;    // xyz world position, w = type
    glm::vec4 directionRange;  // xyz unit direction the light travels, w = range (0: infinite)
    glm::vec4 radiance;        // rgb colour * intensity
    glm::vec4 cone;            // cos(outer), cos(inner), shadow layer (-1: none), unused
    glm::vec4 shadowParams;    // filled by the shadow pass
    glm::mat4 shadowMatrix;    // filled by the shadow pass
};

// One GpuLight per scene light, with no shadow map.
std::vector<GpuLight> makeGpuLights(const Scene& scene);

}  // namespace gis
