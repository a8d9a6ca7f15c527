// Debug displays of `gisandbox view`: a G-buffer channel (depth, normal, base colour, material,
// emission) drawn into an RGBA8 image of display values (shaders/view_debug.frag).
#pragma once

#include "renderer.h"

namespace gis {

enum class GBufferChannel { Depth = 0, Normal = 1, BaseColor = 2, Material = 3, Emissive = 4 };

class GBufferVisualizer {
public:
    GBufferVisualizer();  // needs a current GL context
    // Draws `channel` of a finished frame of `renderer` (which must have a G-buffer) into `target`
    // (an RGBA8 texture of the renderer's size). `maxDistance`: the depth display's black point.
    void draw(const Renderer& renderer, GBufferChannel channel, float maxDistance, GLuint target);
    static std::vector<ProgramDesc> programs();

private:
    gl::Object program_, vao_, fbo_;
};

}  // namespace gis
