// Procedural meshes the built-in scenes are made of (internal to the scene library).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace gis::detail {

// One quad (two triangles 0-1-2, 0-2-3 as in the reference generator) with a constant normal.
void addQuad(Primitive& p, const glm::vec3 (&c)[4], const glm::vec3& n);
// An ideal Lambertian (KHR_materials_specular.specularFactor = 0), single-sided.
Material lambert(const std::string& name, const glm::vec3& albedo);
// Unit cube centred at the origin, faces +Z, -Z, +X, -X, +Y, -Y, outward, CCW.
Primitive unitCube(int material);
// UV sphere of radius r centred at the origin: `segments` around +Y, `rings` from pole to pole.
Primitive uvSphere(float r, int segments, int rings, int material);
// Open cylinder from y = 0 to `height` around +Y, outward normals.
Primitive cylinder(float radius, float height, int segments, int rings, int material);
// A semicircular arch band of the given span, depth (z) and thickness, springing at y = 0.
Primitive archBand(float span, float depth, float thickness, int segments, int material);
// A tiled floor of nx x nz slightly raised tiles in the XZ plane, centred at the origin.
Primitive grid(const glm::vec2& size, int nx, int nz, float bump, int material);
// A hanging cloth, width x height, nx x ny quads, bulging by `sag`.
Primitive banner(float width, float height, int nx, int ny, float sag, int material);

int addMaterial(Scene& s, const Material& m);
int addPrimitive(Scene& s, Primitive p);
// A draw of `cubePrimitive` (a unitCube) scaled and moved to fill the box [lo, hi].
void addBox(Scene& s, int cubePrimitive, const glm::vec3& lo, const glm::vec3& hi);

}  // namespace gis::detail
