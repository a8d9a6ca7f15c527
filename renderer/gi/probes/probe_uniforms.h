// Explicit uniform locations of probe GI: shaders/gi/probes/probe_uniforms.glsl mirrors it.
#pragma once

namespace gis::probes {
enum ProbeUniform : int {
    UP_GRID_FIRST = 500,     // world position of probe (0, 0, 0)
    UP_GRID_STEP = 501,      // world step between neighbours per axis
    UP_GRID_COUNTS = 502,    // probes per axis
    UP_STORAGE = 503,        // 0 sh1, 1 sh2, 2 octahedral
    UP_RAYS = 504,           // rays per probe
    UP_FIRST_PROBE = 505,    // first probe of this update's batch (round robin)
    UP_ROTATION = 506,       // mat3: this update's random rotation of the ray set
    UP_ENVIRONMENT = 507,    // sky radiance for rays that miss
    UP_VOLUME = 508,         // distance field: origin xyz, edge
    UP_SDF_RESOLUTION = 509,
    UP_BLEND_PARAMS = 510,   // hysteresis, multi-bounce on, miss distance, visibility on
    UP_INV_VIEW_PROJ = 511,
    UP_CAMERA_POS = 512,
    UP_SHADE_PARAMS = 513,   // bias (x min probe step), intensity, visibility on, probe radius (debug)
    UP_MODE = 514,           // blend: 0 irradiance, 1 distance; classify: 0 relocate, 1 off; views: mode / probe
    UP_VIEW_PROJ = 515,
    UP_SLOT_OFFSET = 516,    // trace/blend: batch slot of work group 0 (a batch past the group limit is split)
};
}  // namespace gis::probes
