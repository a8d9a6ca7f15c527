// How much GPU memory a render may use: the GPU's available memory where the driver reports it,
// else a stated share of the machine's memory (software GL allocates there).
#pragma once

#include <cstdint>
#include <string>

namespace gis {

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

// "1.5 GiB" or "300 MiB": how budget messages print bytes.
std::string bytesText(uint64_t bytes);

}  // namespace gis
