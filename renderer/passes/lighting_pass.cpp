#include "passes/lighting_pass.h"

#include <cmath>

#include "uniforms.h"

namespace gis {

namespace {
// Largest finite values of the radiance formats: clamping there keeps very bright lights from
// turning into Inf (which tone mapping would show as black).
constexpr float kMaxHalf = 65504.0f;
constexpr float kMaxFloat = 3.0e38f;
}  // namespace

std::vector<ProgramDesc> LightingPass::programs() {
    return {{"lighting", {"fullscreen.vert", "lighting.frag"}, {}}};
}

LightingPass::LightingPass(int width, int height, int lightCount, bool hdr32, bool useAo, gl::MemoryLedger& ledger)
    : lightCount_(lightCount), useAo_(useAo) {
    radiance_ = gl::createTexture2D({&ledger, name()}, hdr32 ? GL_RGBA32F : GL_RGBA16F, width, height);
    if (!useAo_) {  // without an AO pass the ambient term is unoccluded: a 1x1 texture of ones
        noAo_ = gl::createTexture2D({&ledger, name()}, GL_RG16F, 1, 1);
        const float one[2] = {1.0f, 0.0f};
        glTextureSubImage2D(noAo_.id(), 0, 0, 0, 1, 1, GL_RG, GL_FLOAT, one);
    }
    fbo_ = gl::createColorTarget(radiance_, "lighting");
    program_ = buildProgram(programs()[0]);
    vao_ = gl::createVertexArray();
}

void LightingPass::execute(Frame& frame) {
    const RenderSettings& s = frame.settings;
    const GLuint p = program_.id();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, radiance_.width, radiance_.height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    glBindVertexArray(vao_.id());
    const GLuint textures[8] = {frame.texture("gbuffer.depth"),    frame.texture("gbuffer.baseColor"),
                                frame.texture("gbuffer.normal"),   frame.texture("gbuffer.material"),
                                frame.texture("gbuffer.emissive"), frame.texture("shadow.maps"),
                                frame.texture("shadow.cubes"),     useAo_ ? frame.texture("ao") : noAo_.id()};
    glBindTextures(0, 8, textures);
    glBindSamplers(0, 8, nullptr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, frame.buffer("lights"));
    glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, U_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, U_LIGHT_COUNT, lightCount_);
    glProgramUniform3fv(p, U_AMBIENT, 1, &s.ambient[0]);
    const glm::vec3 background = s.background.value_or(frame.scene.cpu.background);
    glProgramUniform3fv(p, U_BACKGROUND, 1, &background[0]);
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1i(p, U_SHADOWS_ENABLED, s.shadows ? 1 : 0);
    glProgramUniform1i(p, U_DEBUG_VIEW, int(s.view));
    glProgramUniform1f(p, U_MAX_RADIANCE, radiance_.format == GL_RGBA16F ? kMaxHalf : kMaxFloat);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    frame.textures["radiance"] = radiance_.id();
}

std::vector<ProgramDesc> TonemapPass::programs() {
    return {{"tonemap", {"fullscreen.vert", "tonemap.frag"}, {}}};
}

TonemapPass::TonemapPass(int width, int height, gl::MemoryLedger& ledger) {
    display_ = gl::createTexture2D({&ledger, name()}, GL_RGBA8, width, height);
    fbo_ = gl::createColorTarget(display_, "tonemap");
    program_ = buildProgram(programs()[0]);
    vao_ = gl::createVertexArray();
}

void TonemapPass::execute(Frame& frame) {
    const GLuint p = program_.id();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, display_.width, display_.height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    glBindVertexArray(vao_.id());
    const GLuint radiance = frame.texture("radiance");
    glBindTextures(0, 1, &radiance);
    glBindSamplers(0, 1, nullptr);
    glProgramUniform1f(p, U_EXPOSURE, std::exp2(frame.settings.exposureEV));
    glProgramUniform1i(p, U_TONEMAPPER, int(frame.settings.tonemap));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    frame.textures["display"] = display_.id();
}

}  // namespace gis
