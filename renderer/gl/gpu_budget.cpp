#include "gpu_budget.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gl.h"

namespace gis {

namespace {

// Not in every glad build: the enums of the two vendor extensions.
constexpr GLenum kGpuMemoryCurrentAvailableNvx = 0x9049;  // KiB
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;          // 4 values, [0] = free KiB

bool hasGlExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

}  // namespace

std::string bytesText(uint64_t bytes) {
    char text[32];
    if (bytes >= (uint64_t(1) << 30))
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
    else
        std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(1 << 20));
    return text;
}

MemoryBudget gpuMemoryBudget() {
    MemoryBudget b;
    if (const char* env = std::getenv("GIS_MEMORY_BUDGET_MB")) {
        char* end = nullptr;
        const unsigned long long mb = std::strtoull(env, &end, 10);
        if (end != env && *end == '\0' && mb > 0) {
            b.bytes = uint64_t(mb) << 20;
            b.source = "GIS_MEMORY_BUDGET_MB";
            return b;
        }
    }
    GLint kib[4] = {0, 0, 0, 0};
    if (hasGlExtension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(kGpuMemoryCurrentAvailableNvx, kib);
        if (kib[0] > 0) return {uint64_t(kib[0]) << 10, "available GPU memory (GL_NVX_gpu_memory_info)"};
    }
    if (hasGlExtension("GL_ATI_meminfo")) {
        glGetIntegerv(kTextureFreeMemoryAti, kib);
        if (kib[0] > 0) return {uint64_t(kib[0]) << 10, "free GPU memory (GL_ATI_meminfo)"};
    }
    glGetError();  // a query the driver did not take must not be reported by a later check
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    b.bytes = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) / 2 : (uint64_t(8) << 30);
    b.source = "half the physical memory (no GPU memory query; set GIS_MEMORY_BUDGET_MB to change)";
    b.hostMemory = true;
    return b;
}

}  // namespace gis
