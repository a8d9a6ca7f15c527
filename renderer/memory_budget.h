// Refusing renders that cannot fit before anything is allocated. The estimate follows the formats
// the passes allocate (what the MemoryLedger reports once they exist: `--timings`, `info`); the
// budget is the GPU's available memory where the driver reports it, else a stated share of the
// machine's memory. Exceeding it is an error whose message carries the estimate.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gis {

struct Scene;
struct RenderSettings;

struct MemoryEstimate {
    std::vector<std::pair<std::string, uint64_t>> parts;  // (what, bytes), largest first
    uint64_t total() const;
};

// Bytes of GPU memory a Renderer with these settings will hold for this scene.
MemoryEstimate estimateGpuMemory(const Scene& scene, const RenderSettings& settings);

struct MemoryBudget {
    uint64_t bytes = 0;
    std::string source;  // where the number comes from, for the message
    bool hostMemory = false;  // no GPU query: the budget is the machine's memory (software GL)
};

// GIS_MEMORY_BUDGET_MB if set; else GL_NVX_gpu_memory_info's currently available memory, or
// GL_ATI_meminfo's free texture memory; else half of the machine's physical memory (software
// GL such as llvmpipe allocates there, and the read-back and encoding need the rest).
// Needs a current GL context for the driver queries.
MemoryBudget gpuMemoryBudget();

// Throws gis::Error naming the estimate, its largest parts and the budget when it does not fit.
void checkMemoryBudget(const Scene& scene, const RenderSettings& settings);
// The same for a width x height environment map's textures alone, once the map is loaded: the file
// may have changed since checkMemoryBudget read its header. Needs a current GL context.
void checkEnvironmentMapBudget(const std::string& name, int width, int height);

}  // namespace gis
