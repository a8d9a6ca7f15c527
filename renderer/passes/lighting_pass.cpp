#include "passes/lighting_pass.h"

#include <cmath>
#include <set>
#include <string>

#include "lights.h"
#include "gl/bind.h"
#include "uniforms.h"

namespace gis {

namespace {
// Largest finite values of the radiance formats: clamping there keeps very bright lights from
// turning into Inf (which tone mapping would show as black).
constexpr float kMaxFloat = 3.0e38f;

// The kinds of shadow map a scene's lights need (shadows.glsl's SHADOW_CUBES / SHADOW_MAPS).
enum ShadowKinds { kCubesOnly, kMapsOnly, kBothKinds, kShadowKindCount };

ShadowKinds shadowKinds(const std::vector<Light>& lights) {
    bool points = false, others = false;
    for (const Light& l : lights) (l.type == LightType::Point ? points : others) = true;
    return others ? (points ? kBothKinds : kMapsOnly) : kCubesOnly;
}

// The terms lighting.frag can output alone, as debug views: the define that selects each.
struct TermView {
    const char* name;
    const char* define;
    const char* help;
};
constexpr TermView kTermViews[] = {
    {"direct", "TERM_DIRECT",
     "radiance of the direct light: punctual lights with their shadows, emissive triangles (and the environment "
     "under emitters.environment) as lights; "
     "direct + indirect.diffuse + indirect.specular + emission = final before tone mapping"},
    {"indirect.diffuse", "TERM_INDIRECT_DIFFUSE",
     "indirect diffuse radiance as lit: the method's indirect.diffuse (or the ambient) x diffuse colour x ao"},
    {"indirect.specular", "TERM_INDIRECT_SPECULAR",
     "indirect specular radiance as lit: the method's indirect.specular (or the ambient) x lobe albedo x ao"},
    {"emission", "TERM_EMISSION", "emitted radiance seen directly: surfaces' emission, the background elsewhere"},
    {"ao", "TERM_AO", "the occlusion the indirect terms got: material occlusion x the method's \"ao\" (1 = open)"},
};
constexpr int kTermViewCount = int(sizeof(kTermViews) / sizeof(kTermViews[0]));

constexpr unsigned kAllModels = (1u << kDiffuseModelCount) - 1;
static_assert(kDiffuseModelCount == kSpecularModelCount, "one mask width for both");

// What one compiled lighting program holds. On llvmpipe a branch no pixel takes still costs every
// pixel a masked pass through its body, so the pass compiles only what its frame can meet: the
// lights as a uniform block when they fit (lights.glsl) or as a storage buffer, the kinds of shadow
// map, the BRDF models (brdf.glsl's BRDF_*_MODELS bits: the render's pair and every material's
// override) and the contract's terms the method gives. Each cut is the same image (tests).
struct LightingVariant {
    bool uniformBlock = true;
    ShadowKinds kinds = kBothKinds;
    unsigned diffuseModels = kAllModels, specularModels = kAllModels;
    bool ao = true, indirectDiffuse = true, indirectSpecular = true;
    bool emitterDirect = true;  // "emitters.direct" (renderer/emitters/)
    int term = -1;              // a kTermViews index: output that term alone; -1: the lit sum

    std::string name() const {
        static const char* kindNames[] = {"-cubes", "-maps", ""};
        return std::string(uniformBlock ? "lighting" : "lighting-many-lights") + kindNames[kinds] + "-d" +
               std::to_string(diffuseModels) + "s" + std::to_string(specularModels) + (ao ? "-ao" : "") +
               (indirectDiffuse ? "-id" : "") + (indirectSpecular ? "-is" : "") + (emitterDirect ? "-em" : "") +
               (term >= 0 ? std::string("-") + kTermViews[term].name : "");
    }
    ProgramDesc program() const {
        auto flag = [](bool b) { return std::string(b ? "1" : "0"); };
        ProgramDesc d{name(),
                      {"fullscreen.vert", "lighting.frag"},
                      {{"SHADOW_CUBES", flag(kinds != kMapsOnly)},
                       {"SHADOW_MAPS", flag(kinds != kCubesOnly)},
                       {"BRDF_DIFFUSE_MODELS", std::to_string(diffuseModels)},
                       {"BRDF_SPECULAR_MODELS", std::to_string(specularModels)},
                       {"AO_INPUT", flag(ao)},
                       {"INDIRECT_DIFFUSE", flag(indirectDiffuse)},
                       {"INDIRECT_SPECULAR", flag(indirectSpecular)},
                       {"EMITTER_DIRECT", flag(emitterDirect)}}};
        if (uniformBlock) d.defines.push_back({"LIGHTS_UNIFORM_BLOCK_CAPACITY", std::to_string(kUniformBlockLights)});
        if (term >= 0) d.defines.push_back({kTermViews[term].define, "1"});
        return d;
    }
};

// The BRDF models a frame can meet: the render's pair and each material's own.
void addModels(const Scene& scene, const RenderSettings& s, LightingVariant& v) {
    v.diffuseModels = 1u << int(s.diffuse);
    v.specularModels = 1u << int(s.specular);
    for (const Material& m : scene.materials) {
        if (m.diffuseModel >= 0) v.diffuseModels |= 1u << m.diffuseModel;
        if (m.specularModel >= 0) v.specularModels |= 1u << m.specularModel;
    }
}
}  // namespace

// Every kind of variant, each with every model and term compiled in (for `gisandbox shaders`: a
// variant with fewer only leaves branches out).
std::vector<ProgramDesc> LightingPass::programs() {
    std::vector<ProgramDesc> all;
    for (bool uniformBlock : {true, false})
        for (int k = 0; k < kShadowKindCount; ++k) {
            LightingVariant v;
            v.uniformBlock = uniformBlock;
            v.kinds = ShadowKinds(k);
            all.push_back(v.program());
        }
    LightingVariant none;
    none.ao = none.indirectDiffuse = none.indirectSpecular = none.emitterDirect = false;
    all.push_back(none.program());
    for (int term = 0; term < kTermViewCount; ++term) {
        LightingVariant v;
        v.term = term;
        all.push_back(v.program());
    }
    return all;
}

LightingPass::LightingPass(int width, int height, bool hdr32, const std::set<std::string>& produced, bool lit,
                           gl::MemoryLedger& ledger)
    : hasAo_(produced.count(resource::kAo) > 0),
      hasDiffuse_(produced.count(resource::kIndirectDiffuse) > 0),
      hasSpecular_(produced.count(resource::kIndirectSpecular) > 0),
      hasEmitters_(produced.count(resource::kEmittersDirect) > 0), lit_(lit) {
    radiance_ = gl::createTexture2D({&ledger, name()}, hdr32 ? GL_RGBA32F : GL_RGBA16F, width, height);
    unit_ = gl::createTexture2D({&ledger, name()}, GL_RG16F, 1, 1);  // samplers stay valid; ao reads 1
    const float one[2] = {1.0f, 0.0f};
    glTextureSubImage2D(unit_.id(), 0, 0, 0, 1, 1, GL_RG, GL_FLOAT, one);
    fbo_ = gl::createColorTarget(radiance_, "lighting");
    viewFbo_ = gl::createFramebuffer();
    vao_ = gl::createVertexArray();
}

// Built on first need: a scene uses one variant, and a light or BRDF edit builds at most one more.
GLuint LightingPass::programFor(const Frame& frame, int term) {
    const std::vector<Light>& lights = frame.scene.cpu.lights;
    LightingVariant v;
    v.uniformBlock = lights.size() <= size_t(kUniformBlockLights);
    v.kinds = shadowKinds(lights);
    addModels(frame.scene.cpu, frame.settings, v);
    v.ao = hasAo_;
    v.indirectDiffuse = hasDiffuse_;
    v.indirectSpecular = hasSpecular_;
    v.emitterDirect = hasEmitters_;
    v.term = term;
    gl::Object& program = programs_[v.name()];
    if (!program.id()) program = buildProgram(v.program());
    return program.id();
}

std::vector<std::string> LightingPass::inputs() const {
    std::vector<std::string> in{resource::kGbufferDepth,    resource::kGbufferBaseColor, resource::kGbufferNormal,
                                resource::kGbufferMaterial, resource::kGbufferEmissive,  resource::kLights,
                                resource::kShadowMaps,      resource::kShadowCubes};
    if (hasAo_) in.push_back(resource::kAo);
    if (hasDiffuse_) in.push_back(resource::kIndirectDiffuse);
    if (hasSpecular_) in.push_back(resource::kIndirectSpecular);
    if (hasEmitters_) in.push_back(resource::kEmittersDirect);
    return in;
}

void LightingPass::execute(Frame& frame) {
    draw(frame, programFor(frame, -1), fbo_.id(),
         radiance_.format == GL_RGBA16F ? gl::kMaxHalfFloat : kMaxFloat);
    frame.put(resource::kRadiance, radiance_);
    stale_ = false;
}

std::vector<std::string> LightingPass::termViewNames() {
    std::vector<std::string> names;
    for (const TermView& t : kTermViews) names.push_back(t.name);
    return names;
}

std::vector<DebugViewDesc> LightingPass::debugViews() const {
    std::vector<DebugViewDesc> views;
    for (const TermView& t : kTermViews) views.push_back({t.name, t.help});
    return views;
}

// The same program with one term kept, into the debug target (RGBA16F).
void LightingPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    int term = 0;
    while (term < kTermViewCount && view != kTermViews[term].name) ++term;
    if (term == kTermViewCount) throw Error("internal: the lighting pass has no view '" + view + "'");
    glNamedFramebufferTexture(viewFbo_.id(), GL_COLOR_ATTACHMENT0, target, 0);
    gl::checkFramebuffer(viewFbo_.id(), "lighting term view");
    draw(frame, programFor(frame, term), viewFbo_.id(), gl::kMaxHalfFloat);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// `maxRadiance`: the largest finite value of the target's format.
void LightingPass::draw(const Frame& frame, GLuint p, GLuint fbo, float maxRadiance) {
    const RenderSettings& s = frame.settings;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, radiance_.width, radiance_.height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(p);
    glBindVertexArray(vao_.id());
    gl::bindTextures({{T_LIGHTING_DEPTH, frame.texture(resource::kGbufferDepth)},
                      {T_LIGHTING_BASE_COLOR, frame.texture(resource::kGbufferBaseColor)},
                      {T_LIGHTING_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {T_LIGHTING_MATERIAL, frame.texture(resource::kGbufferMaterial)},
                      {T_LIGHTING_EMISSIVE, frame.texture(resource::kGbufferEmissive)},
                      {T_LIGHTING_SHADOW_MAPS, frame.texture(resource::kShadowMaps)},
                      {T_LIGHTING_SHADOW_CUBES, frame.texture(resource::kShadowCubes)},
                      {T_LIGHTING_AO, hasAo_ ? frame.texture(resource::kAo) : unit_.id()},
                      {T_LIGHTING_INDIRECT_DIFFUSE, hasDiffuse_ ? frame.texture(resource::kIndirectDiffuse) : unit_.id()},
                      {T_LIGHTING_INDIRECT_SPECULAR, hasSpecular_ ? frame.texture(resource::kIndirectSpecular) : unit_.id()},
                      {T_LIGHTING_EMITTERS_DIRECT, hasEmitters_ ? frame.texture(resource::kEmittersDirect) : unit_.id()}});
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightsBinding, frame.buffer(resource::kLights));
    glBindBufferBase(GL_UNIFORM_BUFFER, kLightsBinding, frame.buffer(resource::kLights));
    glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, U_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, U_LIGHT_COUNT, lit_ ? int(frame.scene.cpu.lights.size()) : 0);
    glProgramUniform3fv(p, U_AMBIENT, 1, &s.ambient[0]);
    frame.bindEnvironment();
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1i(p, U_SHADOWS_ENABLED, s.shadows ? 1 : 0);
    glProgramUniform1f(p, U_MAX_RADIANCE, maxRadiance);
    glDrawArrays(GL_TRIANGLES, 0, 3);
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
    gl::bindTextures({{T_TONEMAP_RADIANCE, frame.texture(resource::kRadiance)}});
    glProgramUniform1f(p, U_EXPOSURE, std::exp2(frame.settings.exposureEV));
    glProgramUniform1i(p, U_TONEMAPPER, int(frame.settings.tonemap));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    frame.put(resource::kDisplay, display_);
    stale_ = false;
}

}  // namespace gis
