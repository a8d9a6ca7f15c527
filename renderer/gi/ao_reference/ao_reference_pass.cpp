#include "gi/ao_reference/ao_reference_pass.h"

#include "debug_view.h"
#include "gi/progressive_method.h"
#include "gi/ssao/ssao_pass.h"
#include "uniforms.h"

namespace gis {

const ParamTable<AoReferenceSettings>& aoReferenceParams() {
    using S = AoReferenceSettings;
    static const ParamTable<S> table = ParamTable<S>()
        .integer(&S::spp, "spp", "Rays per pixel", "cosine-distributed rays per pixel to accumulate", 1, 1 << 20,
                 ParamUpdate::Live, "--spp")
        .real(&S::radius, "radius", "Radius", "world units; 0 = 15% of the scene's diagonal", 0.0, 1e30,
              ParamUpdate::Live, "--ao-radius");
    return table;
}

std::vector<ProgramDesc> AoReferencePass::programs() {
    return {{"ao_reference", {"gi/ao_reference/ao_reference.comp"}, {}}};
}

AoReferencePass::AoReferencePass(SceneServices& services, const RenderSettings& s, gl::MemoryLedger& ledger)
    : ProgressiveRayPass(kName, services.rays(), s, ledger, programs()[0]),
      params_(aoReferenceParams().read("ao-reference", s.params)) {
    samples_.target = params_.spp;
}

void AoReferencePass::execute(Frame& frame) {
    const AoReferenceSettings now = aoReferenceParams().read("ao-reference", frame.settings.params);
    const bool restart = now.radius != params_.radius;
    params_ = now;
    if (!beginFrame(frame, params_.spp, restart)) return;
    glProgramUniform1f(program(), U_AO_RADIUS, resolveAoRadius(params_.radius, frame.scene.cpu));
    runBatch();
}

void AoReferencePass::drawDebugView(const std::string&, const Frame& frame, GLuint target) {
    drawChannel(DisplayChannel::Grey, samples_.mean.id(), frame, target);
}

GiMethod aoReferenceMethod() {
    GiMethod m;
    m.name = "ao-reference";
    m.summary = "ray-traced ambient occlusion within the AO radius: the truth SSAO is scored against";
    m.pipeline = MethodPipeline::Standalone;
    m.image = MethodImage::AmbientOcclusion;
    m.role = MethodRole::AoReference;
    m.benchmarked = false;
    m.params = aoReferenceParams().rows;
    addProgressiveRayParts<AoReferencePass>(m, "ao-reference.spp", "rays per pixel",
                                            {{"low", 16}, {"medium", 64}, {"high", 256}});
    return m;
}

}  // namespace gis
