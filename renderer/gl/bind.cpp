#include "gl/bind.h"

namespace gis::gl {

void bindTextures(std::initializer_list<UnitTexture> textures, GLuint sampler) {
    for (const UnitTexture& t : textures) {
        glBindTextureUnit(GLuint(t.unit), t.texture);
        glBindSampler(GLuint(t.unit), sampler);
    }
}

void bindImages(std::initializer_list<UnitTexture> images) {
    for (const UnitTexture& i : images) glBindImageTextures(GLuint(i.unit), 1, &i.texture);
}

}  // namespace gis::gl
