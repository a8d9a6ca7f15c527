// Refusing renders that cannot fit before anything is allocated: the whole frame with its method,
// beside the registry that knows each method's own estimate. The estimate follows the formats
// the passes allocate (what the MemoryLedger reports once they exist: `--timings`, `info`); the
// budget is gl/gpu_budget.h's. Exceeding it is an error whose message carries the estimate.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gl/gpu_budget.h"

namespace gis {

struct Scene;
struct RenderSettings;

struct MemoryEstimate {
    std::vector<std::pair<std::string, uint64_t>> parts;  // (what, bytes), largest first
    uint64_t total() const;
};

// Bytes of GPU memory a Renderer with these settings will hold for this scene.
MemoryEstimate estimateGpuMemory(const Scene& scene, const RenderSettings& settings);

// Throws gis::Error naming the estimate, its largest parts and the budget when it does not fit.
void checkMemoryBudget(const Scene& scene, const RenderSettings& settings);

}  // namespace gis
