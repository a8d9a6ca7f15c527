// What the progressive ray methods (pathtrace, ao-reference) register alike: presets that trade
// samples per pixel for time, the accumulation as their GPU memory, and their one pass.
#pragma once

#include <initializer_list>
#include <utility>

#include "gi/method.h"
#include "passes/progressive_ray_pass.h"

namespace gis {

// `sampleKey` is the row the presets set ("pathtrace.spp"), `unit` what the description counts.
template <class RayPass>
void addProgressiveRayParts(GiMethod& m, const char* sampleKey, const char* unit,
                            std::initializer_list<std::pair<const char*, int>> presetSamples) {
    for (auto [preset, samples] : presetSamples)
        m.presets.push_back({preset, std::to_string(samples) + " " + unit, {{sampleKey, {double(samples)}}}});
    m.programs = &RayPass::programs;
    m.estimateMemory = [part = m.name + " accumulation (2 x RGBA32F)"](const Scene&, const RenderSettings& s) {
        return std::vector<std::pair<std::string, uint64_t>>{{part, ProgressiveRayPass::accumulationBytes(s)}};
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<RayPass>(b.services, b.settings, b.ledger)); };
}

}  // namespace gis
