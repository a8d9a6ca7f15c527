#include "gi/pathtrace/pathtrace_pass.h"

#include <algorithm>

#include "gi/progressive_method.h"
#include "uniforms.h"

namespace gis {

namespace {

// The term views in pathtrace.comp's u_term order (1 ... 5): direct + emission + pathtrace.indirect
// add up to the final image, and indirect.diffuse + indirect.specular to pathtrace.indirect.
const std::vector<DebugViewDesc>& termViews() {
    static const std::vector<DebugViewDesc> views{
        {"direct", "radiance the first surface receives straight from the lights and emitters, and from the "
                   "environment under emitters.environment (as the lighting pass's direct term); direct + emission "
                   "+ pathtrace.indirect = final before tone mapping"},
        {"emission", "emitted radiance seen directly: surfaces' emission, the background elsewhere"},
        {"pathtrace.indirect", "everything after the first bounce: final - direct - emission (indirect diffuse and "
                               "specular together, the environment's light on the first surface included unless it is a "
                               "light of the direct pass)"},
        {"indirect.diffuse", "the indirect light the first surface's diffuse lobe reflects (pathtrace.indirect split by the "
                             "lobe of its first bounce, per channel)"},
        {"indirect.specular", "the indirect light the first surface's specular lobe reflects: indirect.diffuse + "
                              "indirect.specular = pathtrace.indirect"}};
    return views;
}

int termOf(const std::string& view) {
    for (size_t i = 0; i < termViews().size(); ++i)
        if (termViews()[i].name == view) return int(i) + 1;
    return 0;
}
}  // namespace

std::vector<DebugViewDesc> PathTracePass::debugViews() const { return termViews(); }

// The paths kept only the viewed term: their mean is the view, written as it is.
void PathTracePass::drawDebugView(const std::string&, const Frame& frame, GLuint target) {
    if (!readFbo_) readFbo_ = gl::createFramebuffer(), drawFbo_ = gl::createFramebuffer();
    glNamedFramebufferTexture(readFbo_.id(), GL_COLOR_ATTACHMENT0, samples_.mean.id(), 0);
    glNamedFramebufferTexture(drawFbo_.id(), GL_COLOR_ATTACHMENT0, target, 0);
    const int w = frame.settings.width, h = frame.settings.height;
    glBlitNamedFramebuffer(readFbo_.id(), drawFbo_.id(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

const ParamTable<PathTraceSettings>& pathTraceParams() {
    using S = PathTraceSettings;
    static const ParamTable<S> table = ParamTable<S>()
        .integer(&S::spp, "spp", "Samples per pixel", "samples per pixel to accumulate", 1, 1 << 20,
                 ParamUpdate::Live, "--spp")
        .integer(&S::bounces, "bounces", "Max bounces", "indirect bounces (0 = direct light only)", 0, 1024,
                 ParamUpdate::Live, "--max-bounces")
        .integer(&S::russianRouletteStart, "rr-start", "Roulette from bounce",
                 "bounce from which Russian roulette may end a path", 0, 1024, ParamUpdate::Live)
        .boolean(&S::caustics, "caustics", "Caustics",
                 "false: after a diffuse bounce no glossy/specular light is picked up (Cycles' caustics switches)",
                 ParamUpdate::Live)
        .boolean(&S::environmentSampling, "env-sampling", "Sample the environment",
                 "true: an --environment map is also sampled by its luminance, weighted by MIS; false: BSDF samples "
                 "alone reach it (the same mean, noisier)",
                 ParamUpdate::Live);
    return table;
}

std::vector<ProgramDesc> PathTracePass::programs() { return {{"pathtrace", {"gi/pathtrace/pathtrace.comp"}, {}}}; }

PathTracePass::PathTracePass(SceneServices& services, const RenderSettings& settings, gl::MemoryLedger& ledger)
    : ProgressiveRayPass(kName, services.rays(), settings, ledger, programs()[0]),
      params_(pathTraceParams().read("pathtrace", settings.params)), term_(termOf(settings.view)) {
    samples_.target = params_.spp;
    rayCounts_ = createRayCounts({&ledger, name()});
}

std::optional<RayCounts> PathTracePass::raysTraced() const { return readRayCounts(rayCounts_); }

void PathTracePass::execute(Frame& frame) {
    const RenderSettings& s = frame.settings;
    // Live parameters: a new sample count only moves the target; new bounces restart.
    const PathTraceSettings now = pathTraceParams().read("pathtrace", s.params);
    const bool restart = now.bounces != params_.bounces || now.russianRouletteStart != params_.russianRouletteStart ||
                         now.caustics != params_.caustics || now.environmentSampling != params_.environmentSampling;
    params_ = now;
    if (!beginFrame(frame, params_.spp, restart)) return;  // converged to the requested sample count
    const GLuint p = program();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRayCountsBinding, rayCounts_.id());
    frame.bindEnvironment();
    glProgramUniform1i(p, U_LIGHT_COUNT, int(frame.scene.cpu.lights.size()));
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1i(p, U_MAX_BOUNCES, params_.bounces);
    glProgramUniform1i(p, U_EMITTER_COUNT, int(rays_.emitterCount));
    glProgramUniform1i(p, U_RR_START, params_.russianRouletteStart);
    glProgramUniform1i(p, U_CAUSTICS, params_.caustics ? 1 : 0);
    glProgramUniform1i(p, U_ENV_SAMPLING, params_.environmentSampling ? 1 : 0);
    glProgramUniform1i(p, U_PT_TERM, term_);
    runBatch();
}

GiMethod pathtraceMethod() {
    GiMethod m;
    m.name = "pathtrace";
    m.summary = "GPU path tracer (BVH, NEE + MIS, progressive): the reference every method is scored against";
    m.pipeline = MethodPipeline::Standalone;
    m.role = MethodRole::Reference;
    m.physicalBrdfsOnly = true;
    m.termViews = {"direct", "emission", "indirect.diffuse", "indirect.specular"};
    m.params = pathTraceParams().rows;
    // At low sample counts: the reference's own speed/noise trade.
    addProgressiveRayParts<PathTracePass>(m, "pathtrace.spp", "spp", {{"low", 4}, {"medium", 16}, {"high", 64}});
    return m;
}

}  // namespace gis
