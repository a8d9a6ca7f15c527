#include "probes/probe_field_pass.h"

#include "volume/volume_fit.h"

namespace gis::probes {

ProbeFieldPass::ProbeFieldPass(const char* name, SceneVolume& volume, gl::MemoryLedger& ledger, const Aabb& sceneBounds,
                               const RenderSettings& settings, const ProbeFieldShape& shape)
    : VolumePass(volume), name_(name), sceneBounds_(sceneBounds), spacing_(shape.spacing) {
    const gl::MemoryScope scope{&ledger, name};
    // The volume was fitted to the scene's air (SceneServices::airBounds): the coarsest grid gets a
    // layer in it.
    field_ = std::make_unique<ProbeField>(scope, volume, cascadeProbeGrids(volume, sceneBounds_, spacing_), shape.field);
    gather_ = std::make_unique<ScreenGather>(scope, settings.width, settings.height, shape.gatherPixels, field_->tracer());
    reflection_ = std::make_unique<ScreenReflection>(scope, settings.width, settings.height, field_->tracer());
}

std::vector<std::string> ProbeFieldPass::ownInputs() const {
    return {resource::kGbufferDepth, resource::kGbufferNormal, resource::kGbufferMaterial};
}

std::vector<std::string> ProbeFieldPass::outputs() const {
    return {resource::kIndirectDiffuse, resource::kIndirectSpecular};
}

// The scene volume rebuilds what the change touched (a light edit relights it alone); the probes
// restart, so the new light is followed at once.
void ProbeFieldPass::invalidate(Changes c) {
    field_->invalidate(c);
    changed_ = true;
}

void ProbeFieldPass::run(Frame& frame) {
    const ProbeFieldLive now = live(frame.settings);
    followCascades(*field_, *volume_, sceneBounds_, spacing_);
    field_->update(frame, now.field);
    {
        auto t = frame.step("gather");
        gather_->run(frame, *field_, now.gather);
    }
    {
        auto t = frame.step("reflection");
        // A point no probe sees is lit by rays of its own through the occupancy (HDDAGI). Not
        // through a distance field (probe GI): from such points in builtin:building's hall, where
        // its coarsest cascade's cells are three times the walls' thickness, the rays found the
        // sunlit outside (renderer/gi/probes/README.md).
        const float unseen = field_->tracer() == Tracer::Occupancy ? now.gather.intensity : 0.0f;
        reflection_->run(frame, *field_, now.field, gather_->result(), now.reflection, changed_, unseen);
    }
    frame.put(resource::kIndirectDiffuse, gather_->result());
    frame.put(resource::kIndirectSpecular, reflection_->result());
    changed_ = false;
}

std::vector<std::string> ProbeFieldPass::stats(const std::string& volumeLine) const {
    std::vector<std::string> out{field_->describe(), volumeLine};
    for (int i = 0; i < volume_->cascadeCount(); ++i) out.push_back(volume_->describeCascade(i));
    out.push_back(reflection_->describe());
    return out;
}

std::vector<ProgramDesc> ProbeFieldPass::programs(const VolumeRequest& volume) {
    std::vector<ProgramDesc> all = SceneVolume::programs(volume);
    for (const auto& list : {fieldPrograms(), ScreenGather::programs(), ScreenReflection::programs()})
        all.insert(all.end(), list.begin(), list.end());
    return all;
}

std::vector<std::pair<std::string, uint64_t>> ProbeFieldPass::estimateMemory(const std::string& method, const Scene& scene,
                                                                             const RenderSettings& s,
                                                                             const ProbeFieldShape& shape) {
    const CascadeLayout layout =  // as SceneServices fits it
        volumeLayout(sceneAirBounds(scene), shape.volume, viewDepthFor(shape.volume, scene, s));
    const int probes = cascadeProbeCount(scene.bounds, layout, shape.spacing);
    return {{method + " scene volume (" + std::to_string(layout.count) + " cascades)",
             uint64_t(sceneVolumeBytes(shape.volume, layout.count))},
            {method + " probes (" + std::to_string(probes) + ": irradiance, distance moments, state)",
             uint64_t(fieldStorageBytes(shape.field, probes))},
            {method + " probe rays", uint64_t(fieldRayBytes(shape.field, probes))},
            {method + " screen gather", uint64_t(ScreenGather::bytes(s.width, s.height, shape.gatherPixels))},
            {method + " reflection (means, specular)", uint64_t(ScreenReflection::bytes(s.width, s.height))}};
}

}  // namespace gis::probes
