#include "gi/memory_budget.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "emitters/emitter_lights.h"
#include "environment.h"
#include "environment_gpu.h"
#include "lights.h"
#include "gi/method.h"
#include "passes/gbuffer_pass.h"
#include "gl/gpu_budget.h"
#include "scene/scene.h"

namespace gis {

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
        if (directPassHasLights(scene, s))
            e.parts.push_back({"emitter lights (ReSTIR reservoirs)", EmitterLightPass::targetBytes(s.width, s.height, environmentIsLight(scene, s))});
        if (s.shadows && !scene.draws.empty()) {
            const uint64_t points = uint64_t(shadowCubes(scene.lights)), flat = uint64_t(shadowMapLayers(scene.lights));
            const uint64_t map = uint64_t(s.shadowMapSize) * uint64_t(s.shadowMapSize) * 4;
            const uint64_t cube = uint64_t(s.shadowCubeSize) * uint64_t(s.shadowCubeSize) * 4 * 6;
            e.parts.push_back({"shadow maps", flat * map + points * cube});
        }
    }
    e.parts.push_back({"tonemap (RGBA8)", pixels * 4});
    e.parts.push_back({"environment (split-sum table)", uint64_t(GpuEnvironment::tableBytes())});
    if (!s.environment.empty())
        if (const std::optional<glm::ivec2> size = environmentMapSize(s.environment))
            e.parts.push_back({GpuEnvironment::kMemoryPart,
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
                               : e.parts.front().first == GpuEnvironment::kMemoryPart ? "use a smaller environment map, or raise the budget"
                                                                              : "lower the settings that size " + e.parts.front().first +
                                                                                    " (e.g. the method's resolution), or raise the budget";
    std::string parts;
    for (size_t i = 0; i < e.parts.size() && i < 2; ++i) parts += (i ? ", " : "") + e.parts[i].first + " " + bytesText(e.parts[i].second);
    throw Error(std::to_string(settings.width) + "x" + std::to_string(settings.height) + " needs about " +
                bytesText(e.total()) + (b.hostMemory ? " of memory (" : " of GPU memory (") + parts + "), more than the " + bytesText(b.bytes) + " budget: " +
                b.source + "; " + advice);
}

}  // namespace gis
