#include "debug_view.h"

#include "gl/bind.h"
#include "uniforms.h"

namespace gis {

std::vector<ProgramDesc> ChannelDisplay::programs() {
    return {{"view_debug", {"fullscreen.vert", "view_debug.frag"}, {}}};
}

ChannelDisplay::ChannelDisplay() {
    program_ = buildProgram(programs()[0]);
    vao_ = gl::createVertexArray();
    fbo_ = gl::createFramebuffer();
}

void ChannelDisplay::draw(DisplayChannel channel, GLuint source, GLuint depth, const CameraMatrices& cam,
                          float maxDistance, GLuint target, int width, int height) {
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, target, 0);
    gl::checkFramebuffer(fbo_.id(), "debug display");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    const GLuint p = program_.id();
    glUseProgram(p);
    glBindVertexArray(vao_.id());
    gl::bindTextures({{T_DISPLAY_SOURCE, source}, {T_DISPLAY_DEPTH, depth ? depth : source}});
    glProgramUniform1i(p, U_DISPLAY_CHANNEL, int(channel));
    glProgramUniformMatrix4fv(p, U_DISPLAY_INV_VIEW_PROJ, 1, GL_FALSE, &cam.invViewProj[0][0]);
    glProgramUniform3fv(p, U_DISPLAY_CAMERA_POS, 1, &cam.position[0]);
    glProgramUniform1f(p, U_DISPLAY_MAX_DISTANCE, maxDistance);
    glProgramUniform1i(p, U_DISPLAY_HAS_DEPTH, depth ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

namespace {
// The depth display's black point: the far side of the scene's bounds from the camera.
float farthestCorner(const Aabb& b, const glm::vec3& eye) {
    if (b.empty()) return 1.0f;
    float d = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
        d = std::max(d, glm::length(c - eye));
    }
    return std::max(d, 1e-6f);
}
}  // namespace

void drawChannel(DisplayChannel channel, GLuint source, const Frame& frame, GLuint target) {
    const GLuint depth = frame.has(resource::kGbufferDepth) ? frame.texture(resource::kGbufferDepth) : 0;
    frame.channelDisplay->draw(channel, source, depth, frame.camera,
                                         farthestCorner(frame.scene.cpu.bounds, frame.camera.position), target,
                                         frame.settings.width, frame.settings.height);
}

}  // namespace gis
