// Where the scene volume binds itself into a program (SceneVolume::bind), declared once: the C++
// bind calls use these, and GLSL declares the volume's samplers with the defines emitted from them
// (renderer/shader_constants.cpp: VOLUME_DISTANCE_UNIT, ...). Above the units a method uses for its
// own inputs (0-10) and the environment's (ENV_*_UNIT, 11-15), so no method picks one of them.
#pragma once

namespace gis {

constexpr int kVolumeDistanceUnit = 16;                   // the distance field, a layer per cascade
constexpr int kVolumeCoarseUnit = kVolumeDistanceUnit + 1;  // its coarse level (empty-space skipping)
// The light the volume's tracers read: level 0 (a layer per cascade with more than one), then with
// one cascade its six directional mips (shaders/volume/cone_trace.glsl), then the slab voxels' sides
// (VoxelRadiance::sides, a layer per cascade like level 0): eight units.
constexpr int kVolumeRadianceUnit = kVolumeCoarseUnit + 1;
constexpr int kVolumeRadianceUnits = 8;
constexpr int kVolumeAlbedoUnit = kVolumeRadianceUnit + kVolumeRadianceUnits;  // the voxels' albedo (a = occupancy)
constexpr int kVolumeEmissionUnit = kVolumeAlbedoUnit + 1;
constexpr int kVolumePunctualUnit = kVolumeEmissionUnit + 1;  // level 0's share of the punctual lights (VoxelRadiance::punctual)
// The frame's shadow maps, by which the tracers light their hits (shaders/volume/hit_light.glsl).
constexpr int kVolumeShadowMapsUnit = kVolumePunctualUnit + 1;
constexpr int kVolumeShadowCubesUnit = kVolumeShadowMapsUnit + 1;
// And the frame's lights, at a storage binding of their own: a ray scene binds its own copy of the
// lights, without shadow maps, at the usual one. Above every other storage binding (the non-finite
// counters' is 8).
constexpr int kVolumeHitLightsBinding = 9;

}  // namespace gis
