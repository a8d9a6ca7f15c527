// Binding textures by their declared units (the binding tables of gl/uniform_table.h): each texture
// names its unit, so no call depends on the order of an array matching consecutive units.
#pragma once

#include <glad/gl.h>

#include <initializer_list>

namespace gis::gl {

struct UnitTexture {
    int unit;
    GLuint texture;
};

// Binds each texture at its unit, sampled through `sampler` (0: the texture's own sampling state).
void bindTextures(std::initializer_list<UnitTexture> textures, GLuint sampler = 0);
// Binds level 0 of each texture (every layer) as the image at its unit, in the texture's format.
void bindImages(std::initializer_list<UnitTexture> images);

}  // namespace gis::gl
