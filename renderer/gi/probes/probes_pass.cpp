#include "gi/probes/probes_pass.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gi/method.h"
#include "gl/dispatch.h"
#include "probes/probe_uniforms.h"
#include "services/scene_services.h"

namespace gis {

using namespace probes;

namespace {
// What probes ask of the scene volume: voxels with their distance field (the rays' sphere tracing)
// and their direct light and emission (what the rays see), in cascades around the camera.
VolumeRequest volumeRequest(const ProbeSettings& s) {
    VolumeRequest r;
    r.method = "probes";
    r.resolution = s.sdfResolution;
    r.resolutionKey = "probes.sdf-resolution";
    r.distanceField = true;
    r.albedoAtlas = true;  // the probes' rays light their hits' multi-bounce by it
    r.cascades = s.cascades;
    r.cascadeExtent = s.cascadeExtent;
    return r;
}

// The settings, once checkProbeSettings has found them valid (it throws, naming the parameter).
ProbeSettings checkedSettings(const RenderSettings& settings) {
    const ProbeSettings s = probeParams().read(ProbesPass::kName, settings.params);
    checkProbeSettings(s);
    return s;
}

// What is fixed when the pass is built, from valid settings.
ProbeFieldShape shapeOf(const ProbeSettings& s) { return {volumeRequest(s), s.spacing, s.field(), s.gatherPixels()}; }
}  // namespace

std::vector<ProgramDesc> ProbesPass::programs() { return ProbeFieldPass::programs(volumeRequest(ProbeSettings{})); }

ProbesPass::ProbesPass(SceneServices& services, const RenderSettings& settings)
    : ProbesPass(services, settings, checkedSettings(settings)) {}

ProbesPass::ProbesPass(SceneServices& services, const RenderSettings& settings, const ProbeSettings& valid)
    : ProbeFieldPass(kName, services.volume(volumeRequest(valid)), services.ledger, services.bounds(), settings,
                     shapeOf(valid)),
      built_(valid) {}

ProbeFieldLive ProbesPass::live(const RenderSettings& settings) const {
    const ProbeSettings s = probeParams().read(kName, settings.params);
    return {s.field(), {s.normalBias, s.intensity, s.visibility, s.pathTest}, s};
}

std::vector<DebugViewDesc> ProbesPass::debugViews() const { return field_->debugViews("probes", "probe probes.debug-probe"); }

void ProbesPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    field_->drawDebugView(view.substr(std::string("probes.").size()), frame, target, live(frame.settings).field);
}

GiMethod probesMethod() {
    GiMethod m;
    m.name = "probes";
    m.summary = "irradiance probes sphere-traced through the SDF, SH or octahedral storage, Chebyshev visibility";
    m.environmentLightByDefault = true;
    m.params = probeParams().rows;
    m.presets = {
        {"low", "SH L1, spacing 1/3, 64 rays, 32^3 field",
         {{"probes.spacing", {0.34}}, {"probes.rays", {64.0}}, {"probes.storage", ParamValue::choice("sh1")},
          {"probes.sdf-resolution", {32.0}}}},
        {"medium", "SH L2, spacing 1/8, 32 rays, 64^3 field", {}},
        {"high", "octahedral maps, spacing 1/8, 128 rays, 64^3 field",
         {{"probes.rays", {128.0}}, {"probes.storage", ParamValue::choice("octahedral")}}},
        {"realtime",
         "high's probes within 16384 rays per frame (128 probes), gathered every 4x4 pixels and upsampled, the sky "
         "through its own rays (no environment light in the direct pass)",
         {{"probes.rays", {128.0}},
          {"probes.storage", ParamValue::choice("octahedral")},
          {"probes.ray-budget", {16384.0}},
          {"probes.gather-scale", ParamValue::choice("4")},
          {"emitters.environment", ParamValue::choice("false")}}},
    };
    m.programs = &ProbesPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) {
        return ProbeFieldPass::estimateMemory(ProbesPass::kName, scene, s, shapeOf(probeParams().read(ProbesPass::kName, s.params)));
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<ProbesPass>(b.services, b.settings)); };
    // Updates stop when converged or after max-updates; the bench renders this many frames first.
    // Capped so that a huge max-updates cannot stall it; with a probes.ray-budget below the probe
    // count a pass over all probes takes several frames, which this cannot know (it sees no
    // scene): such a bench row may be scored before convergence.
    m.framesToConverge = [](const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        return std::min(p.maxUpdates, 200);
    };
    return m;
}

std::vector<std::string> ProbesPass::stats() const {
    return ProbeFieldPass::stats(describeVolume(volume_->grid().fit, "voxels / distance-field cells"));
}

}  // namespace gis
