// Voxel cone tracing's parameters (issue 11's names: vct.resolution, vct.conservative,
// vct.anisotropic, vct.bounces, ...), their defaults and the low/medium/high presets. A plain
// struct until the method registry lands; then each field becomes one row of its parameter table.
#pragma once

#include <string>

#include "voxel/voxelizer.h"

namespace gis {

struct VctSettings {
    int resolution = 64;                 // vct.resolution: voxels per edge, power of two in [8, 512] (rebuild)
    ConservativeMode conservative = ConservativeMode::Hardware;  // vct.conservative (rebuild)
    bool anisotropic = true;             // vct.anisotropic: six directional mip chains (rebuild)
    int bounces = 1;                     // vct.bounces: 1 = direct light re-emitted once; 2+ = more (rebuild)
    int coneSet = 0;                     // vct.cones: 0 = six 60-degree cones (Godot), 1 = four 90-degree (live)
    float stepFactor = 0.5f;             // vct.step: step as a fraction of the cone diameter, (0, 2] (live)
    float maxDistance = 1.0f;            // vct.max_distance: fraction of the volume's edge, (0, 2] (live)
    float offset = 1.5f;                 // vct.offset: self-occlusion offset along the normal, voxels, [0, 8] (live)
    float intensity = 1.0f;              // vct.intensity: scales the indirect terms, [0, 16] (live)
    bool specular = true;                // vct.specular: trace the specular cone (live)
    // Debug views (live): "vct.voxels" ray-marches the grid, "vct.slice" shows one slice.
    enum class DebugView { None, Voxels, Slice };
    DebugView debugView = DebugView::None;
    int debugChannel = 0;                // vct.debug_channel: 0 albedo, 1 emission, 2 radiance, 3 occupancy
    int debugLevel = 0;                  // vct.debug_level: mip level (radiance and occupancy)
    int sliceAxis = 2;                   // vct.slice_axis: 0 x, 1 y, 2 z
    float slicePosition = 0.5f;          // vct.slice_position: 0..1 across the volume
};

// Throws gis::Error naming the parameter and its range.
void checkVctSettings(const VctSettings& s);
// low / medium / high (the benchmark's rows); throws on any other name.
VctSettings vctPreset(const std::string& name);

}  // namespace gis
