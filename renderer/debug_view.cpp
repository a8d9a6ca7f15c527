#include "debug_view.h"

namespace gis {

std::vector<ProgramDesc> GBufferVisualizer::programs() {
    return {{"view_debug", {"fullscreen.vert", "view_debug.frag"}, {}}};
}

GBufferVisualizer::GBufferVisualizer() {
    program_ = buildProgram(programs()[0]);
    vao_ = gl::createVertexArray();
    fbo_ = gl::createFramebuffer();
}

void GBufferVisualizer::draw(const Renderer& renderer, GBufferChannel channel, float maxDistance, GLuint target) {
    static const char* const sources[] = {"gbuffer.depth", "gbuffer.normal", "gbuffer.baseColor", "gbuffer.material",
                                          "gbuffer.emissive"};
    const GLuint depth = renderer.frameTexture("gbuffer.depth");
    const GLuint source = renderer.frameTexture(sources[int(channel)]);
    if (!depth || !source) throw Error("internal: the G-buffer display needs a frame with a G-buffer");
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, target, 0);
    gl::checkFramebuffer(fbo_.id(), "G-buffer display");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, renderer.settings().width, renderer.settings().height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    const GLuint p = program_.id();
    glUseProgram(p);
    glBindVertexArray(vao_.id());
    const GLuint textures[2] = {source, depth};
    glBindTextures(0, 2, textures);
    glBindSamplers(0, 2, nullptr);
    const CameraMatrices& cam = renderer.camera();
    glProgramUniform1i(p, 0, int(channel));
    glProgramUniformMatrix4fv(p, 1, 1, GL_FALSE, &cam.invViewProj[0][0]);
    glProgramUniform3fv(p, 2, 1, &cam.position[0]);
    glProgramUniform1f(p, 3, maxDistance);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace gis
