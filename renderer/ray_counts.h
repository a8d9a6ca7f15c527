// Rays a ray-tracing pass traced, by kind: what passes report (Pass::raysTraced) and the ray
// scene's counter buffer holds (ray_scene.h).
#pragma once

#include <cstdint>

namespace gis {

// primary (from the camera), bounce (path continuation), shadow (visibility towards a light or
// emitter).
struct RayCounts {
    uint64_t primary = 0, bounce = 0, shadow = 0;
    uint64_t total() const { return primary + bounce + shadow; }
};

}  // namespace gis
