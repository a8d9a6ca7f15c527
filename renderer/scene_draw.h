// One draw of the scene (gpu_scene.h) through a raster program that reads the fixed locations of
// shaders/scene_vertex.glsl and material.glsl: the G-buffer, the shadow maps and the voxelizer
// draw the scene this way. The caller binds the program's framebuffer, the scene's vertex array
// and whatever else its program reads.
#pragma once

#include "gl/gl.h"
#include "gpu_scene.h"

namespace gis {

// Sets `draw`'s transform and material factors on `program`, binds the material's textures and
// draws its triangles.
void drawWithMaterial(const GpuScene& scene, GLuint program, const GpuDraw& draw);

}  // namespace gis
