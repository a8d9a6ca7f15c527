// Debug displays: one channel of a frame texture (G-buffer depth, normal, base colour, material,
// emission, or a grey data value such as AO) drawn as display values into a target texture
// (shaders/view_debug.frag). Passes use it for the debug views they offer.
#pragma once

#include "frame.h"
#include "gl/shader.h"

namespace gis {

enum class DisplayChannel { Depth = 0, Normal = 1, BaseColor = 2, Material = 3, Emissive = 4, Grey = 5 };

class ChannelDisplay {
public:
    ChannelDisplay();  // needs a current GL context
    // `depth` 0: no G-buffer (every pixel is shown). `maxDistance`: the depth display's black point.
    void draw(DisplayChannel channel, GLuint source, GLuint depth, const CameraMatrices& camera, float maxDistance,
              GLuint target, int width, int height);
    static std::vector<ProgramDesc> programs();

private:
    gl::Object program_, vao_, fbo_;
};

// Draws `channel` of `source` for the frame's camera into `target` (the frame's size), with the
// frame's G-buffer depth as the mask where it has one. The renderer's ChannelDisplay is used.
void drawChannel(DisplayChannel channel, GLuint source, const Frame& frame, GLuint target);

}  // namespace gis
