// Punctual lights as the shaders see them (shaders/lights.glsl). Shared by the rasterizer's
// lighting (with shadow-map fields filled in by the shadow pass) and the ray tracers (none).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/storage_struct.h"
#include "scene/scene.h"

namespace gis {

constexpr int kLightDirectional = 0, kLightPoint = 1, kLightSpot = 2;

// One light as shaders/lights.glsl reads it, from a storage buffer or a uniform block (vec4s and a
// mat4 lay out alike in std430 and std140). positionType: xyz world position, w = type;
// directionRange: xyz unit direction the light travels, w = range (0: infinite); radiance: rgb
// colour * intensity (W/sr for point and spot, W/m^2 for directional); cone: cos(outer),
// cos(inner), shadow layer (-1: none), unused. Filled by the shadow pass: shadowParams (texel world
// size = x + y * distance; z = near, w = far for a point light), shadowMatrix (world to shadow
// clip, directional and spot) and, for a directional light, viewCascade: its map around the
// camera (the layer after the scene's), as a scale and offset of the scene map's clip x and y
// (xy scale, zw offset; x = 0 while the camera's map would be no finer than the scene's).
#define GIS_GPU_LIGHT(M)                                                                                    \
    M(vec4, positionType) M(vec4, directionRange) M(vec4, radiance) M(vec4, cone) M(vec4, shadowParams) \
    M(mat4, shadowMatrix) M(vec4, viewCascade)
GIS_STORAGE_STRUCT(GpuLight, GIS_GPU_LIGHT)

// Lights the lighting pass reads as a uniform block (lights.glsl's LIGHTS_UNIFORM_BLOCK_CAPACITY):
// 100 x 160 bytes fits the 16 KiB every GL 4.5 driver must allow a block. The light buffer holds at
// least this many entries so the block is always backed; scenes with more use the storage buffer.
constexpr int kUniformBlockLights = 100;
// The lights' binding point, as a uniform block and as a storage buffer (GLSL's LIGHTS_BINDING);
// parameter blocks (gl/uniform_block.h) start above it.
constexpr int kLightsBinding = 0;
static_assert(kUniformBlockLights * sizeof(GpuLight) <= 16384, "GL_MAX_UNIFORM_BLOCK_SIZE is at least 16 KiB");

// GL_MAX_ARRAY_TEXTURE_LAYERS's GL 4.5 minimum (2048 on most drivers): what a check without a
// context (the viewer's panel and scripts) can count on.
constexpr int kMinArrayTextureLayers = 2048;

// 2D shadow-map layers a directional light takes: the map fitted to the scene (the volume's light
// injection and every lookup outside the camera's map) and the one fitted to the camera's view.
constexpr int kDirectionalShadowLayers = 2;

// The shadow maps are layers of one array texture: 6 per point light (a cube), 1 per spot light,
// kDirectionalShadowLayers per directional light. Throws when `lights` need more than `maxLayers` (past it allocation fails
// with an incomplete framebuffer that names no cause); the message ends in `remedy`.
void checkShadowLayers(const std::vector<Light>& lights, int maxLayers, const std::string& remedy);
// The 2D layers (spot and directional) and the cubes (point) `lights` take.
int shadowMapLayers(const std::vector<Light>& lights);
int shadowCubes(const std::vector<Light>& lights);

// One GpuLight per scene light, with no shadow map.
std::vector<GpuLight> makeGpuLights(const Scene& scene);

}  // namespace gis
