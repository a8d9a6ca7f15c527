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
ParamValue choiceValue(const char* name) {
    ParamValue v;
    v.text = name;
    return v;
}
}  // namespace

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

// The request of valid settings (checkProbeSettings throws first, naming the parameter).
VolumeRequest checkedVolumeRequest(const RenderSettings& settings) {
    const ProbeSettings s = probeParams().read("probes", settings.params);
    checkProbeSettings(s);
    return volumeRequest(s);
}
}  // namespace

std::vector<ProgramDesc> ProbesPass::programs() {
    std::vector<ProgramDesc> all = SceneVolume::programs(volumeRequest(ProbeSettings{}));
    for (const auto& list : {fieldPrograms(), ScreenGather::programs(), ScreenReflection::programs()}) all.insert(all.end(), list.begin(), list.end());
    return all;
}

ProbesPass::ProbesPass(SceneServices& services, const RenderSettings& settings)
    : VolumePass(services.volume(checkedVolumeRequest(settings))), built_(probeParams().read("probes", settings.params)) {
    const gl::MemoryScope scope{&services.ledger, name()};
    // The volume was fitted to the scene's air (SceneServices::airBounds): the coarsest grid gets a
    // layer in it.
    sceneBounds_ = services.bounds();
    field_ = std::make_unique<ProbeField>(scope, *volume_, cascadeProbeGrids(*volume_, sceneBounds_, built_.spacing), built_.field());
    gather_ = std::make_unique<ScreenGather>(scope, settings.width, settings.height, built_.gatherPixels(), field_->tracer());
    reflection_ = std::make_unique<ScreenReflection>(scope, settings.width, settings.height, field_->tracer());
}

// The scene volume rebuilds what the change touched (a light edit relights it alone); the probes
// restart, so the new light is followed at once.
void ProbesPass::invalidate(Changes c) {
    field_->invalidate(c);
    changed_ = true;
}

Pass::Progress ProbesPass::progress() const { return reflection_->progress(field_->progress(), field_->converged()); }

void ProbesPass::run(Frame& frame) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    followCascades(*field_, *volume_, sceneBounds_, built_.spacing);
    field_->update(frame, live.field());
    {
        auto t = frame.step("shade");
        gather_->run(frame, *field_, {live.normalBias, live.intensity, live.visibility, live.pathTest});
    }
    {
        auto t = frame.step("reflection");
        reflection_->run(frame, *field_, live.field(), gather_->result(), live, changed_);
    }
    frame.put(resource::kIndirectDiffuse, gather_->result());
    frame.put(resource::kIndirectSpecular, reflection_->result());
    changed_ = false;
}

std::vector<DebugViewDesc> ProbesPass::debugViews() const { return field_->debugViews("probes", "probe probes.debug-probe"); }

void ProbesPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    field_->drawDebugView(view.substr(std::string("probes.").size()), frame, target, live.field());
}

GiMethod probesMethod() {
    GiMethod m;
    m.name = "probes";
    m.summary = "irradiance probes sphere-traced through the SDF, SH or octahedral storage, Chebyshev visibility";
    m.params = probeParams().rows;
    m.presets = {
        {"low", "SH L1, spacing 1/3, 64 rays, 32^3 field",
         {{"probes.spacing", {0.34}}, {"probes.rays", {64.0}}, {"probes.storage", choiceValue("sh1")},
          {"probes.sdf-resolution", {32.0}}}},
        {"medium", "SH L2, spacing 1/8, 32 rays, 64^3 field", {}},
        {"high", "octahedral maps, spacing 1/8, 128 rays, 64^3 field",
         {{"probes.rays", {128.0}}, {"probes.storage", choiceValue("octahedral")}}},
        {"realtime", "high's probes within 16384 rays per frame (128 probes), gathered every 4x4 pixels and upsampled",
         {{"probes.rays", {128.0}},
          {"probes.storage", choiceValue("octahedral")},
          {"probes.ray-budget", {16384.0}},
          {"probes.gather-scale", choiceValue("4")}}},
    };
    m.programs = &ProbesPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        const VolumeRequest request = volumeRequest(p);
        const CascadeLayout layout = volumeLayout(sceneAirBounds(scene), request);  // as SceneServices fits it
        const int cascades = layout.count;
        const int probes = cascadeProbeCount(scene.bounds, layout, p.spacing);
        return std::vector<std::pair<std::string, uint64_t>>{
            {"probe voxels and distance field", uint64_t(sceneVolumeBytes(request, cascades))},
            {"probes (irradiance, distance moments, state)", uint64_t(fieldStorageBytes(p.field(), probes))},
            {"probe rays", uint64_t(fieldRayBytes(p.field(), probes))},
            {"probe screen target", uint64_t(ScreenGather::bytes(s.width, s.height, p.gatherPixels()))},
            {"probe reflection (mean, specular)", uint64_t(ScreenReflection::bytes(s.width, s.height))}};
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
    std::vector<std::string> out{field_->describe(), describeVolume(volume_->grid().fit, "voxels / distance-field cells")};
    for (int i = 0; i < volume_->cascadeCount(); ++i) out.push_back(volume_->describeCascade(i));
    out.push_back(reflection_->describe());
    return out;
}

}  // namespace gis
