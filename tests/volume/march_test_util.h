// The sphere tracer (shaders/volume/sdf_march.glsl) run on the GPU for a list of rays, through
// shaders/volume/sdf_march_probe.comp: the distance-field tests march analytic and jump-flooded
// fields with it, the SDF GI tests a scene volume's cascades.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "volume/distance_field.h"

namespace gis::test {

struct Ray {
    glm::vec4 origin;     // w = max distance
    glm::vec4 direction;
};
struct Hit {
    glm::vec3 position;
    bool hit = false;
    glm::vec3 normal;
    int steps = 0;
    int cascade = -1;   // the layer the hit was found in (-1: a miss)
};

struct MarchSettings {
    float threshold = 0.5f, relaxation = 1.2f;
    int maxSteps = 128;
    float startOffset = 0.0f;
};

// A layered field is marched as cascades (layer 0 the finest), a single one as one volume.
std::vector<Hit> march(const DistanceField& field, const std::vector<Ray>& rays, const MarchSettings& m = {});

}  // namespace gis::test
