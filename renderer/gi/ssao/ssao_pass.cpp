#include "gi/ssao/ssao_pass.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "debug_view.h"
#include "gi/method.h"
#include "gi/ssao/ssao_bindings.h"
#include "uniforms.h"

namespace gis {

namespace {
constexpr int kMaxSlices = 64;
constexpr float kTemporalFrames = 16;   // running mean over at most this many frames
constexpr float kTemporalDepthTolerance = 0.02f;

float radicalInverse(uint32_t bits) {  // van der Corput in base 2
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10f;
}

void setTextureFilter(GLuint tex, GLenum filter) {
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace

std::vector<glm::vec4> SsaoPass::kernel(int count) {
    std::vector<glm::vec4> k;
    for (int i = 0; i < count; ++i) {
        const float u = (i + 0.5f) / float(count), v = radicalInverse(uint32_t(i));
        const float r = std::sqrt(u), phi = 6.28318530718f * v;
        k.emplace_back(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u)), 0.0f);
    }
    return k;
}

const ParamTable<SsaoSettings>& ssaoParams() {
    using S = SsaoSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = ParamTable<S>()
        .integer(&S::samples, "samples", "Directions", "directions in the hemisphere kernel", 1, kSsaoMaxKernel, U::Rebuild,
                 "--ao-samples")
        .integer(&S::steps, "steps", "Steps", "points tested along each direction (gtao: per side of a slice)", 1, 64,
                 U::Live, "--ao-steps")
        .real(&S::radius, "radius", "Radius", "world units; 0 = 15% of the scene's diagonal", 0.0, 1e30, U::Live,
              "--ao-radius")
        .real(&S::bias, "bias", "Bias", "depth bias as a fraction of the radius", 0.0, 0.999, U::Live, "--ao-bias")
        .real(&S::power, "power", "Power", "AO^power (contrast)", 0.001, 64.0, U::Live, "--ao-power")
        .boolean(&S::blur, "blur", "Bilateral blur", "bilateral 4x4 blur over the noise tile", U::Rebuild)
        .boolean(&S::halfResolution, "half-res", "Half resolution", "compute AO at half resolution", U::Rebuild,
                 "--ao-half-res")
        .boolean(&S::temporal, "temporal", "Temporal", "reprojected accumulation, per-frame noise rotation",
                 U::Rebuild, "--ao-temporal")
        .choice(&S::kernel, "kernel", "Kernel",
                "hemisphere: normal-oriented directions marched through the depth buffer; gtao: horizons per slice "
                "with the analytic cosine integral (Jimenez et al. 2016)",
                {"hemisphere", "gtao"}, U::Rebuild)
        .integer(&S::slices, "slices", "Slices", "gtao: slices through the view vector per pixel", 1, kMaxSlices,
                 U::Live);
    return table;
}

// The floor only keeps a flat or point-sized scene's radius above 0: an absolute 1e-6 made the
// radius 3.4x the default on the Cornell box modelled at 1e-6 units (-2.0% mean AO'd radiance).
float resolveAoRadius(float radius, const Scene& scene) {
    if (radius > 0.0f) return radius;
    return scene.bounds.empty() ? 1.0f : std::max(0.15f * glm::length(scene.bounds.extent()), 1e-30f);
}

// In this order: the hemisphere kernel, the blur, temporal accumulation, the GTAO kernel.
std::vector<ProgramDesc> SsaoPass::programs() {
    return {{"ssao", {"fullscreen.vert", "gi/ssao/ssao.frag"}, {}},
            {"ssao_blur", {"fullscreen.vert", "gi/ssao/ssao_blur.frag"}, {}},
            {"ssao_temporal", {"fullscreen.vert", "gi/ssao/ssao_temporal.frag"}, {}},
            {"ssao_gtao", {"fullscreen.vert", "gi/ssao/gtao.frag"}, {}}};
}

SsaoPass::SsaoPass(const RenderSettings& s, gl::MemoryLedger& ledger)
    : params_(ssaoParams().read("ssao", s.params)),
      width_(params_.halfResolution ? std::max(1, s.width / 2) : s.width),
      height_(params_.halfResolution ? std::max(1, s.height / 2) : s.height),
      kernel_(gtao() ? std::vector<glm::vec4>{} : kernel(std::min(params_.samples, kSsaoMaxKernel))),
      samples_({&ledger, name()}), temporal_({&ledger, name()}) {
    const gl::MemoryScope scope{&ledger, name()};
    raw_ = gl::createTexture2D(scope, GL_RG16F, width_, height_);
    rawFbo_ = gl::createColorTarget(raw_, "SSAO");
    if (params_.blur) {
        blurred_ = gl::createTexture2D(scope, GL_RG16F, width_, height_);
        blurFbo_ = gl::createColorTarget(blurred_, "SSAO blur");
    }
    if (params_.temporal)
        for (int i = 0; i < 2; ++i) {
            history_[i] = gl::createTexture2D(scope, GL_RGBA16F, width_, height_);
            historyFbo_[i] = gl::createColorTarget(history_[i], "SSAO history");
        }
    for (const gl::Texture* t : {&raw_, &blurred_, &history_[0], &history_[1]})
        if (t->id()) setTextureFilter(t->id(), GL_LINEAR);
    // 4x4 random rotations (unit vectors in the tangent plane), fixed seed: deterministic images.
    noise_ = gl::createTexture2D(scope, GL_RG16F, 4, 4);
    float rotations[32];
    uint32_t state = 12345u;
    for (int i = 0; i < 16; ++i) {
        state = state * 747796405u + 2891336453u;
        const float angle = 6.28318530718f * float(state >> 8) / 16777216.0f;
        rotations[2 * i] = std::cos(angle);
        rotations[2 * i + 1] = std::sin(angle);
    }
    glTextureSubImage2D(noise_.id(), 0, 0, 0, 4, 4, GL_RG, GL_FLOAT, rotations);
    setTextureFilter(noise_.id(), GL_NEAREST);
    const auto progs = programs();
    aoProgram_ = buildProgram(progs[gtao() ? 3 : 0]);  // only the kernel this pass runs
    blurProgram_ = buildProgram(progs[1]);
    temporalProgram_ = buildProgram(progs[2]);
    vao_ = gl::createVertexArray();
    sampler_ = gl::createSampler();
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void SsaoPass::execute(Frame& frame) {
    const SsaoSettings live = ssaoParams().read("ssao", frame.settings.params);  // steps, radius, bias, power
    const float radius = resolveAoRadius(live.radius, frame.scene.cpu);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vao_.id());
    glViewport(0, 0, width_, height_);
    const GLuint samplers[3] = {sampler_.id(), 0, 0};  // linear depth for the sample tests
    glBindSamplers(ssao::TA_DEPTH, 3, samplers);

    // 1. Raw AO.
    GLuint p = aoProgram_.id();
    glUseProgram(p);
    glBindFramebuffer(GL_FRAMEBUFFER, rawFbo_.id());
    const GLuint inputs[3] = {frame.texture(resource::kGbufferDepth), frame.texture(resource::kGbufferNormal), noise_.id()};
    glBindTextures(ssao::TA_DEPTH, 3, inputs);
    const glm::mat4 invProj = glm::inverse(frame.camera.proj);
    glProgramUniformMatrix4fv(p, U_PROJ, 1, GL_FALSE, &frame.camera.proj[0][0]);
    glProgramUniformMatrix4fv(p, U_INV_PROJ, 1, GL_FALSE, &invProj[0][0]);
    glProgramUniformMatrix4fv(p, U_VIEW, 1, GL_FALSE, &frame.camera.view[0][0]);
    glProgramUniform1f(p, U_AO_RADIUS, radius);
    // With temporal accumulation the noise tile shifts every frame, so the running mean sees
    // every rotation; without it the pattern stays put (no flicker on a still camera).
    SsaoBlock samples;
    samples.bias = live.bias;
    samples.power = live.power;
    samples.steps = live.steps;
    samples.noiseOffset = params_.temporal ? int(frame.index % 16) : 0;
    samples_.set(samples);
    if (gtao()) {
        glProgramUniform1i(p, U_AO_KERNEL_SIZE, live.slices);
    } else {
        glProgramUniform1i(p, U_AO_KERNEL_SIZE, int(kernel_.size()));
        glProgramUniform4fv(p, U_AO_KERNEL, GLsizei(kernel_.size()), &kernel_[0][0]);
    }
    glDrawArrays(GL_TRIANGLES, 0, 3);
    const gl::Texture* result = &raw_;

    // 2. Bilateral blur over the noise tile.
    if (blurred_.id()) {
        glBindSamplers(ssao::TA_DEPTH, 3, nullptr);
        glUseProgram(blurProgram_.id());
        glProgramUniformMatrix4fv(blurProgram_.id(), U_INV_PROJ, 1, GL_FALSE, &invProj[0][0]);
        glProgramUniformMatrix4fv(blurProgram_.id(), U_VIEW, 1, GL_FALSE, &frame.camera.view[0][0]);
        glBindFramebuffer(GL_FRAMEBUFFER, blurFbo_.id());
        const GLuint blurInputs[2] = {result->id(), frame.texture(resource::kGbufferNormal)};
        glBindTextures(ssao::TA_BLUR_AO, 2, blurInputs);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        result = &blurred_;
    }

    // 3. Temporal accumulation into the history texture we did not read last frame.
    if (history_[0].id()) {
        const int next = 1 - current_;
        p = temporalProgram_.id();
        glUseProgram(p);
        glBindFramebuffer(GL_FRAMEBUFFER, historyFbo_[next].id());
        const GLuint temporalInputs[3] = {result->id(), history_[current_].id(), frame.texture(resource::kGbufferDepth)};
        glBindTextures(ssao::TA_TEMPORAL_AO, 3, temporalInputs);
        glProgramUniformMatrix4fv(p, U_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
        glProgramUniformMatrix4fv(p, U_PREV_VIEW_PROJ, 1, GL_FALSE, &prevViewProj_[0][0]);
        SsaoTemporalBlock temporal;
        temporal.maxFrames = kTemporalFrames;
        temporal.hasHistory = hasHistory_ ? 1 : 0;
        temporal.depthTolerance = kTemporalDepthTolerance;
        temporal_.set(temporal);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        current_ = next;
        hasHistory_ = true;
        prevViewProj_ = frame.camera.viewProj;
        result = &history_[current_];
    }
    frame.put(resource::kAo, *result);
    result_ = result;
    ++stillFrames_;
}

bool SsaoPass::settled() const { return stillFrames_ >= (params_.temporal ? int(kTemporalFrames) : 1); }

void SsaoPass::drawDebugView(const std::string&, const Frame& frame, GLuint target) {
    drawChannel(DisplayChannel::Grey, result_->id(), frame, target);
}

namespace {
// The kernel the plain low/medium/high presets use; the other kernel's presets carry its name
// as a prefix ("hemisphere-medium"), so `bench --presets` can set the two side by side. GTAO:
// each of its presets is both faster and closer to ray-traced AO than the hemisphere's preset of
// the same name (renderer/gi/ssao/README.md).
constexpr SsaoKernel kPresetKernel = SsaoKernel::Gtao;

void addPresets(GiMethod& m, SsaoKernel kernel, const std::string& prefix) {
    const bool gtao = kernel == SsaoKernel::Gtao;
    // Directions (hemisphere) or slices (gtao) x points per direction or side, and resolution.
    const int counts[3] = {gtao ? 3 : 8, gtao ? 3 : 16, gtao ? 8 : 64};
    const int steps[3] = {gtao ? 4 : 2, gtao ? 4 : 4, gtao ? 8 : 8};
    const bool half[3] = {true, false, false};
    for (int i = 0; i < 3; ++i)
        m.presets.push_back({prefix + presetNames()[i],
                             std::string(gtao ? "GTAO, " : "hemisphere, ") + std::to_string(counts[i]) +
                                 (gtao ? " slices x " : " directions x ") + std::to_string(steps[i]) +
                                 (gtao ? " steps per side" : " steps") + (half[i] ? ", half resolution" : ""),
                             {{"ssao.kernel", ParamValue::choice(gtao ? "gtao" : "hemisphere")},
                              {gtao ? "ssao.slices" : "ssao.samples", {double(counts[i])}},
                              {"ssao.steps", {double(steps[i])}},
                              {"ssao.half-res", {half[i] ? 1.0 : 0.0}}}});
}
}  // namespace

GiMethod ssaoMethod() {
    GiMethod m;
    m.name = "ssao";
    m.scoredAgainstAo = true;
    m.summary = "screen-space ambient occlusion of the constant ambient term (hemisphere or GTAO kernel, blur, temporal)";
    m.params = ssaoParams().rows;
    m.shaderTables.bindings = tableRows(ssao::kSsaoBindings);
    const SsaoKernel other = kPresetKernel == SsaoKernel::Gtao ? SsaoKernel::Hemisphere : SsaoKernel::Gtao;
    addPresets(m, kPresetKernel, "");
    addPresets(m, other, other == SsaoKernel::Gtao ? "gtao-" : "hemisphere-");
    m.programs = &SsaoPass::programs;
    m.estimateMemory = [](const Scene&, const RenderSettings& s) {
        // RG16F raw (+ blurred) AO and two RGBA16F history images when temporal, at the pass's
        // own (maybe half) resolution: the targets the constructor creates.
        const SsaoSettings p = ssaoParams().read("ssao", s.params);
        const uint64_t w = uint64_t(p.halfResolution ? std::max(1, s.width / 2) : s.width);
        const uint64_t h = uint64_t(p.halfResolution ? std::max(1, s.height / 2) : s.height);
        const uint64_t perPixel = 4 + (p.blur ? 4 : 0) + (p.temporal ? 16 : 0);
        return std::vector<std::pair<std::string, uint64_t>>{{"SSAO", w * h * perPixel}};
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<SsaoPass>(b.settings, b.ledger)); };
    // Temporal accumulation averages up to 16 frames.
    m.framesToConverge = [](const RenderSettings& s) { return ssaoParams().read("ssao", s.params).temporal ? 16 : 1; };
    return m;
}

}  // namespace gis
