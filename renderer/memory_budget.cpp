#include "memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "emitters/emitter_lights.h"
#include "environment.h"
#include "environment_gpu.h"
#include "gi/method.h"
#include "passes/gbuffer_pass.h"
#include "gl/gl.h"
#include "renderer.h"
#include "scene/scene.h"

namespace gis {

namespace {

// Not in every glad build: the enums of the two vendor extensions.
constexpr GLenum kGpuMemoryCurrentAvailableNvx = 0x9049;  // KiB
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;          // 4 values, [0] = free KiB

// The estimate's part for an environment map: a refusal it leads advises a smaller map.
const std::string kEnvironmentMapPart = "environment map textures (radiance, specular chain, sampling CDFs)";

bool hasGlExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

std::string gib(uint64_t bytes) {
    char text[32];
    if (bytes >= (uint64_t(1) << 30))
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
    else
        std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(1 << 20));
    return text;
}

}  // namespace

uint64_t MemoryEstimate::total() const {
    uint64_t sum = 0;
    for (const auto& p : parts) sum += p.second;
    return sum;
}

MemoryEstimate estimateGpuMemory(const Scene& scene, const RenderSettings& s) {
    const uint64_t pixels = uint64_t(std::max(s.width, 0)) * uint64_t(std::max(s.height, 0));
    MemoryEstimate e;
    // Per-pixel bytes of each pass's targets (the formats in passes/*.cpp, as the ledger counts).
    const GiMethod& method = giMethod(s.gi);
    if (method.estimateMemory)  // the method's own passes and volumes
        for (const auto& part : method.estimateMemory(scene, s)) e.parts.push_back(part);
    const bool deferred = method.pipeline == MethodPipeline::Deferred;
    // A G-buffer view of a standalone method adds the G-buffer; any debug view its RGBA16F target.
    if (deferred || s.view.rfind("gbuffer.", 0) == 0) {
        e.parts.push_back({"G-buffer (28 bytes/pixel)", pixels * 28});
        if (const int64_t aa = emissionAntialiasingBytes(scene, s.width, s.height))
            e.parts.push_back({"G-buffer emission antialiasing (multisampled)", uint64_t(aa)});
    }
    if (s.view != "final") e.parts.push_back({"debug view (RGBA16F)", pixels * 8});
    if (deferred) {
        e.parts.push_back({s.hdr32 ? "lighting (RGBA32F)" : "lighting (RGBA16F)", pixels * (s.hdr32 ? 16 : 8)});
        if (emittersAreLights(scene, s))
            e.parts.push_back({"emitter lights (ReSTIR reservoirs)", EmitterLightPass::targetBytes(s.width, s.height)});
        if (s.shadows && !scene.draws.empty()) {
            uint64_t points = 0, flat = 0;
            for (const Light& l : scene.lights) (l.type == LightType::Point ? points : flat) += 1;
            const uint64_t map = uint64_t(s.shadowMapSize) * uint64_t(s.shadowMapSize) * 4;
            const uint64_t cube = uint64_t(s.shadowCubeSize) * uint64_t(s.shadowCubeSize) * 4 * 6;
            e.parts.push_back({"shadow maps", flat * map + points * cube});
        }
    }
    e.parts.push_back({"tonemap (RGBA8)", pixels * 4});
    e.parts.push_back({"environment (split-sum table)", uint64_t(GpuEnvironment::tableBytes())});
    if (!s.environment.empty())
        if (const std::optional<glm::ivec2> size = environmentMapSize(s.environment))
            e.parts.push_back({kEnvironmentMapPart,
                               uint64_t(GpuEnvironment::mapBytes(size->x, size->y))});
    uint64_t vertices = 0, indices = 0, texels = 0;
    for (const Primitive& p : scene.primitives) {
        vertices += p.vertices.size();
        indices += p.indices.size();
    }
    for (const Image& img : scene.images) texels += uint64_t(img.width) * uint64_t(img.height);
    e.parts.push_back({"scene (geometry, textures with mips)", vertices * sizeof(Vertex) + indices * 4 + texels * 4 * 4 / 3});
    std::sort(e.parts.begin(), e.parts.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    return e;
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

void checkMemoryBudget(const Scene& scene, const RenderSettings& settings) {
    MemoryEstimate e = estimateGpuMemory(scene, settings);
    const MemoryBudget b = gpuMemoryBudget();
    // Software GL allocates "GPU" memory in the same RAM as the image read back (RGBA32F for EXR,
    // RGBA8 for PNG) and its encoding: 16384x16384 took 12.8 GB on a 23 GB machine.
    if (b.hostMemory) {
        const uint64_t pixels = uint64_t(settings.width) * uint64_t(settings.height);
        e.parts.push_back({"read-back and encoding (host)", pixels * 20});
    }
    if (e.total() <= b.bytes) return;
    std::sort(e.parts.begin(), e.parts.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
    // The advice follows the largest part: a method's volume does not shrink with --size.
    const uint64_t perPixel = uint64_t(settings.width) * uint64_t(settings.height) * 64;  // G-buffer, HDR, read-back
    const bool sizeBound = e.parts.empty() || e.parts.front().second <= perPixel;
    const std::string advice = sizeBound                                      ? "use a smaller --size"
                               : e.parts.front().first == kEnvironmentMapPart ? "use a smaller environment map, or raise the budget"
                                                                              : "lower the settings that size " + e.parts.front().first +
                                                                                    " (e.g. the method's resolution), or raise the budget";
    std::string parts;
    for (size_t i = 0; i < e.parts.size() && i < 2; ++i) parts += (i ? ", " : "") + e.parts[i].first + " " + gib(e.parts[i].second);
    throw Error(std::to_string(settings.width) + "x" + std::to_string(settings.height) + " needs about " +
                gib(e.total()) + (b.hostMemory ? " of memory (" : " of GPU memory (") + parts + "), more than the " + gib(b.bytes) + " budget: " +
                b.source + "; " + advice);
}

void checkEnvironmentMapBudget(const std::string& name, int width, int height) {
    const uint64_t need = uint64_t(GpuEnvironment::mapBytes(width, height));
    const MemoryBudget b = gpuMemoryBudget();
    if (need > b.bytes)
        throw Error("environment map '" + name + "' is " + std::to_string(width) + "x" + std::to_string(height) + ": its " +
                    kEnvironmentMapPart + " need about " + gib(need) + ", more than the " + gib(b.bytes) + " budget: " +
                    b.source + "; use a smaller environment map");
}

}  // namespace gis
