#include "passes/gbuffer_pass.h"

#include <iterator>
#include <string>

#include "debug_view.h"
#include "gl/dispatch.h"
#include "scene_draw.h"

#include "uniforms.h"

namespace gis {

namespace {
constexpr unsigned kAllTextures = 31;  // GpuMaterial::textures
// Samples per draw (4x MSAA, which llvmpipe offers for float colour and depth textures too) and
// draws: offset by (+-1/16, +-1/16) pixel, the common rotated-grid 4x pattern's x and y positions
// (multiples of 1/4 apart) become 8 evenly spaced ones per axis, so an edge along a pixel row is
// covered in eighths instead of quarters.
constexpr int kEmissionSamples = 4;
constexpr int kEmissionDraws = 4;
const ProgramDesc kEmissionResolveProgram{"emission_resolve", {"emission_resolve.comp"}, {}};
constexpr int kResolveGroup = 8;  // emission_resolve.comp's local size
// What every target is cleared to before a draw.
constexpr float kNoColour[4] = {0.0f, 0.0f, 0.0f, 0.0f};
constexpr float kFarDepth = 1.0f;
constexpr int64_t kEmissionSampleBytes = 8 + 4;  // RGBA16F emission, 32-bit float depth

// The G-buffer program for materials with the textures in `textures` (material.glsl's
// MATERIAL_TEXTURES): a texture the material lacks is not sampled at all.
ProgramDesc gbufferProgram(unsigned textures) {
    return {"gbuffer-t" + std::to_string(textures), {"scene.vert", "gbuffer.frag"},
            {{"MATERIAL_TEXTURES", std::to_string(textures)}}};
}
}  // namespace

// Every texture and none (for `gisandbox shaders`; the others only leave lookups out).
std::vector<ProgramDesc> GBufferPass::programs() {
    return {gbufferProgram(kAllTextures), gbufferProgram(0), kEmissionResolveProgram};
}

// Built on first need: one per set of textures the scene's materials have.
GLuint GBufferPass::programFor(const GpuMaterial& material) {
    gl::Object& program = programs_[material.textures];
    if (!program.id()) program = buildProgram(gbufferProgram(material.textures));
    return program.id();
}

int emissionSamples(const Scene& scene) {
    for (const DrawItem& d : scene.draws) {
        const Primitive& p = scene.primitives[size_t(d.primitive)];
        if (p.material >= 0 && glm::any(glm::greaterThan(scene.materials[size_t(p.material)].emissive, glm::vec3(0.0f))))
            return kEmissionSamples;
    }
    return 0;
}

int64_t emissionAntialiasingBytes(const Scene& scene, int width, int height) {
    return int64_t(width) * height * emissionSamples(scene) * kEmissionSampleBytes;
}

GBufferPass::GBufferPass(const Scene& scene, int width, int height, gl::MemoryLedger& ledger) {
    const gl::MemoryScope scope{&ledger, name()};
    depth_ = gl::createTexture2D(scope, GL_DEPTH_COMPONENT32F, width, height);
    // sRGB storage keeps dark albedos (0.05) precise to ~0.1% instead of 8-bit linear's ~2%.
    baseColor_ = gl::createTexture2D(scope, GL_SRGB8_ALPHA8, width, height);
    normal_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    material_ = gl::createTexture2D(scope, GL_RGBA8, width, height);
    emissive_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    fbo_ = gl::createFramebuffer();
    const GLuint f = fbo_.id();
    glNamedFramebufferTexture(f, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0, baseColor_.id(), 0);
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT1, normal_.id(), 0);
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT2, material_.id(), 0);
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT3, emissive_.id(), 0);
    const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(f, 4, buffers);
    gl::checkFramebuffer(f, "G-buffer");
    const int samples = emissionSamples(scene);
    if (samples == 0) return;
    multisampleDepth_ = gl::createTexture2DMultisample(scope, GL_DEPTH_COMPONENT32F, width, height, samples);
    multisampleEmissive_ = gl::createTexture2DMultisample(scope, GL_RGBA16F, width, height, samples);
    multisampleFbo_ = gl::createFramebuffer();
    const GLuint m = multisampleFbo_.id();
    glNamedFramebufferTexture(m, GL_DEPTH_ATTACHMENT, multisampleDepth_.id(), 0);
    glNamedFramebufferTexture(m, GL_COLOR_ATTACHMENT3, multisampleEmissive_.id(), 0);
    // gbuffer.frag's outputs 0-2 go nowhere: the same program writes the emission alone.
    const GLenum emissionOnly[4] = {GL_NONE, GL_NONE, GL_NONE, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(m, 4, emissionOnly);
    gl::checkFramebuffer(m, "G-buffer emission (multisampled)");
    resolveProgram_ = buildProgram(kEmissionResolveProgram);
}

void GBufferPass::execute(Frame& frame) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, depth_.width, depth_.height);
    glEnable(GL_FRAMEBUFFER_SRGB);  // encode base colour into its sRGB target
    for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, i, kNoColour);
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &kFarDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    drawScene(frame, frame.camera.viewProj);
    if (multisampleFbo_.id()) antialiasEmission(frame);
    glDisable(GL_CULL_FACE);
    glDisable(GL_FRAMEBUFFER_SRGB);
    frame.put(resource::kGbufferDepth, depth_);
    frame.put(resource::kGbufferBaseColor, baseColor_);
    frame.put(resource::kGbufferNormal, normal_);
    frame.put(resource::kGbufferMaterial, material_);
    frame.put(resource::kGbufferEmissive, emissive_);
    stale_ = false;
}

void GBufferPass::antialiasEmission(const Frame& frame) {
    const GLuint m = multisampleFbo_.id(), resolve = resolveProgram_.id();
    const int w = depth_.width, h = depth_.height;
    glBindFramebuffer(GL_FRAMEBUFFER, m);
    glEnable(GL_MULTISAMPLE);
    for (int k = 0; k < kEmissionDraws; ++k) {
        // The offset in NDC: a pixel is 2 / size.
        glm::mat4 offset(1.0f);
        offset[3][0] = ((k & 1) ? 1.0f : -1.0f) / 16.0f * 2.0f / float(w);
        offset[3][1] = ((k & 2) ? 1.0f : -1.0f) / 16.0f * 2.0f / float(h);
        glClearNamedFramebufferfv(m, GL_COLOR, 3, kNoColour);
        glClearNamedFramebufferfv(m, GL_DEPTH, 0, &kFarDepth);
        drawScene(frame, offset * frame.camera.viewProj);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glUseProgram(resolve);
        glProgramUniform2i(resolve, U_EMISSION_PASS, k, kEmissionDraws);
        glBindTextureUnit(T_EMISSION_SAMPLES, multisampleEmissive_.id());
        glBindSampler(T_EMISSION_SAMPLES, 0);
        glBindImageTexture(I_EMISSION, emissive_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        gl::dispatchCompute(gl::groupsFor(w, kResolveGroup), gl::groupsFor(h, kResolveGroup), 1, "G-buffer emission resolve");
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
}

void GBufferPass::drawScene(const Frame& frame, const glm::mat4& viewProj) {
    const GpuScene& scene = frame.scene;
    glFrontFace(GL_CCW);
    glBindVertexArray(scene.vao.id());
    for (const GpuDraw& d : scene.draws) {
        const GpuMaterial& m = scene.materials[d.material];
        const GLuint program = programFor(m);
        glUseProgram(program);
        glProgramUniformMatrix4fv(program, U_VIEW_PROJ, 1, GL_FALSE, &viewProj[0][0]);
        if (m.params.doubleSided) glDisable(GL_CULL_FACE);
        else glEnable(GL_CULL_FACE);
        // A mirroring transform (negative determinant) flips the winding.
        glFrontFace(glm::determinant(glm::mat3(d.world)) < 0.0f ? GL_CW : GL_CCW);
        drawWithMaterial(scene, program, d);
    }
    glFrontFace(GL_CCW);
}

namespace {
struct GBufferView {
    const char* name;
    const char* help;
    DisplayChannel channel;
};
const GBufferView kGBufferViews[] = {
    {"gbuffer.depth", "distance from the camera (white near, black at the scene's far side)", DisplayChannel::Depth},
    {"gbuffer.normal", "world-space shading normal, N * 0.5 + 0.5", DisplayChannel::Normal},
    {"gbuffer.basecolor", "base colour (sRGB)", DisplayChannel::BaseColor},
    {"gbuffer.material", "metallic, roughness, occlusion as R, G, B", DisplayChannel::Material},
    {"gbuffer.emissive", "emitted radiance, Reinhard-compressed", DisplayChannel::Emissive},
};
}  // namespace

std::vector<DebugViewDesc> GBufferPass::views() {
    std::vector<DebugViewDesc> views;
    for (const GBufferView& v : kGBufferViews) views.push_back({v.name, v.help});
    return views;
}

void GBufferPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    const gl::Texture* sources[] = {&depth_, &normal_, &baseColor_, &material_, &emissive_};
    for (size_t i = 0; i < std::size(kGBufferViews); ++i)
        if (view == kGBufferViews[i].name) drawChannel(kGBufferViews[i].channel, sources[i]->id(), frame, target);
}

}  // namespace gis
