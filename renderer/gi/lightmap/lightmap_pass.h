// `--gi lightmap`: baked light (issue #41), the static end of the trade. The scene's surfaces get a
// lightmap atlas (renderer/lightmap/), its texels are baked by the path tracer's paths on the GPU
// (lightmap_bake.h), progressively over frames, and each frame draws the surfaces again at their
// lightmap UVs into indirect.diffuse. A finished bake is cached on disk by the scene's content id.
// What changes the light (a light, an object, a material) makes the bake stale: the last lightmap
// stays on show, marked stale (progress()), while the next bake runs; it replaces it when done.
#pragma once

#include <chrono>
#include <memory>

#include "frame.h"
#include "gi/lightmap/lightmap_bake.h"
#include "gi/lightmap/lightmap_settings.h"
#include "ray_scene.h"

namespace gis {

class LightmapPass final : public Pass {
public:
    static constexpr const char* kName = "lightmap";
    LightmapPass(const Scene& scene, RayScene& rays, const RenderSettings& settings, gl::MemoryLedger& ledger);
    const char* name() const override { return kName; }
    std::vector<std::string> inputs() const override { return {resource::kGbufferDepth, resource::kGbufferNormal}; }
    std::vector<std::string> outputs() const override { return {resource::kIndirectDiffuse}; }
    void execute(Frame& frame) override;
    void invalidate(Changes c) override;
    bool settled() const override { return (done_ >= params_.samples || held()) && !changed_; }
    bool writesImagesOrBuffers() const override { return true; }
    Progress progress() const override { return {done_, params_.samples, "spp", stale_, held(), read_}; }
    std::vector<std::string> stats() const override;
    std::optional<RayCounts> raysTraced() const override;
    std::optional<int64_t> atlasTexels() const override;
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;

    static std::vector<ProgramDesc> programs();
    // GPU bytes, by part, before anything is built (the atlas is built on the CPU to know them).
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const Scene& scene, const RenderSettings& s);

private:
    bool held() const { return stale_ && params_.rebake == kRebakeHold; }
    void bake(Frame& frame);
    void draw(const Frame& frame, GLuint target, int mode);
    void drawAtlas(const Frame& frame, GLuint target);
    std::string cacheKey(const Frame& frame) const;
    void readCache(const Frame& frame);
    void writeCache();

    const Scene& scene_;
    RayScene& rays_;
    LightmapSettings params_;
    lightmap::Atlas atlas_;
    std::unique_ptr<LightmapBake> bake_;
    gl::Texture indirect_, depth_;
    gl::Object fbo_, gbufferFbo_, atlasProgram_, atlasVao_;
    std::vector<gl::Object> applyPrograms_;  // kApplyPrograms's, the cut-outs' only where the scene has some
    gl::Buffer rayCounts_;
    int done_ = 0;
    int read_ = 0;  // of done_, read from the cache
    bool changed_ = true;           // something since the last execute() asks for a redraw
    bool resolved_ = false;         // the lightmap holds the mean of done_ samples
    bool shown_ = false;            // a complete lightmap has been resolved (and drawn)
    bool stale_ = false;            // the one drawn predates an edit: kept until the next bake is done
    bool cacheTried_ = false;
    std::string cacheState_ = "off";  // what the cache did: off, read <path>, written <path>, ...
    std::string cachePath_;
    std::chrono::steady_clock::time_point bakeStarted_;
    double bakeSeconds_ = 0.0;      // wall time from the first batch to the last's end
};

}  // namespace gis
