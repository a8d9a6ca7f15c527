// What a frame is made of: passes, each declaring the named textures and buffers it reads and
// writes (renderer/frame_resources.h), owning its GL resources (charged to its name in the memory
// ledger) and timed with GPU timer queries; the Frame they share while they run; what changed
// since they last ran; and how their timings are summarised.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frame_resources.h"
#include "gl/gl.h"
#include "gpu_scene.h"
#include "ray_counts.h"
#include "render_settings.h"

namespace gis {

// What changed since a pass last ran, so it throws away only what depends on it: moving the
// camera keeps shadow maps, voxels, distance fields and probes.
enum Change : uint32_t {
    ChangeCamera = 1u << 0,
    ChangeLights = 1u << 1,
    ChangeGeometry = 1u << 2,
    ChangeMaterials = 1u << 3,
    ChangeBrdfModels = 1u << 4,
    ChangeLiveParams = 1u << 5,   // a live parameter, exposure, tone mapper, ambient
};
using Changes = uint32_t;

// What passes exchange: a GL object with its shape, so consumers and debug views need no side
// channel to know a texture's size, format or dimensionality.
enum class ResourceKind { Texture2D, Texture2DArray, TextureCubeArray, Texture3D, Buffer };
struct FrameResource {
    GLuint id = 0;
    ResourceKind kind = ResourceKind::Texture2D;
    GLenum format = 0;                  // textures
    int width = 0, height = 0, depth = 1, levels = 1;
    int64_t bytes = 0;                  // buffers
};

// A pass's timers for its own steps ("voxelize", "inject" ...), nested under the pass's timer.
class StepTimers {
public:
    struct Scope {
        gl::GpuTimer* timer = nullptr;
        Scope(gl::GpuTimer* t) : timer(t) { timer->begin(); }
        Scope(Scope&& o) noexcept : timer(o.timer) { o.timer = nullptr; }
        Scope(const Scope&) = delete;
        ~Scope() {
            if (timer) timer->end();
        }
    };
    Scope scope(const std::string& step);
    std::vector<std::pair<std::string, std::unique_ptr<gl::GpuTimer>>> steps;  // first use order
};

class ChannelDisplay;
class GpuEnvironment;
class Pass;
struct SceneServices;

// What the passes share during one frame: settings, the scene, the camera and named resources
// (renderer/frame_resources.h). The executing pass may read only what its inputs() or outputs()
// declare and write only its outputs(): any other access throws, naming the pass and the name.
struct Frame {
    const RenderSettings& settings;
    const GpuScene& scene;
    SceneServices& services;
    CameraMatrices camera;
    std::map<std::string, FrameResource> resources;
    uint64_t index = 0;                 // frames rendered before this one
    StepTimers* steps = nullptr;        // the executing pass's step timers
    GpuEnvironment* environment = nullptr;  // bindEnvironment()'s; the renderer owns it
    ChannelDisplay* channelDisplay = nullptr;  // debug views draw channels with it (renderer/debug_view.h)
    const Pass* pass = nullptr;         // the executing pass (none: the renderer itself)
    void put(const std::string& name, const gl::Texture& texture);
    void put(const std::string& name, const gl::Buffer& buffer);
    bool has(const std::string& name) const { return resources.count(name) > 0; }
    const FrameResource& resource(const std::string& name) const;
    GLuint texture(const std::string& name) const;
    GLuint buffer(const std::string& name) const;
    StepTimers::Scope step(const std::string& name) { return steps->scope(name); }
    // The radiance of rays that leave the scene when it is a constant: --background when given,
    // else the scene's own.
    glm::vec3 background() const { return settings.background.value_or(scene.cpu.background); }
    // Binds the environment (shaders/environment.glsl) for the programs the pass runs next: the
    // map of --environment, else background() as a constant map. Defined in environment_gpu.cpp.
    void bindEnvironment() const;

private:
    void checkDeclared(const std::string& name, bool write) const;
};

// A named picture a pass can draw for inspection ("ao", "gbuffer.normal", "vct.slice").
struct DebugViewDesc {
    std::string name, help;
};

// The memory-barrier rule between passes: after each pass that declares writesImagesOrBuffers(),
// the renderer makes its writes visible to every way a later pass may read the kinds of resource
// the pass outputs (barrierBitsFor); within a pass, the pass orders its own steps.
class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    virtual std::vector<std::string> inputs() const { return {}; }
    virtual std::vector<std::string> outputs() const { return {}; }
    virtual void execute(Frame& frame) = 0;
    // True when the last execute() reused cached results (e.g. static shadow maps).
    virtual bool reusedLastFrame() const { return false; }
    // True when executing again would reproduce the outputs the pass put last time: nothing it
    // depends on changed since (no invalidate() since its last execute()) and its temporal or
    // progressive work has converged. The renderer then skips execute() and keeps those outputs,
    // so a static view costs no GI step.
    virtual bool settled() const { return false; }
    // Something changed: drop what depends on it. Progressive passes start over.
    virtual void invalidate(Changes) {}
    // Image load/store or SSBO writes that later passes read.
    virtual bool writesImagesOrBuffers() const { return false; }
    // Progressive passes accumulate samples over frames: how many are in and how many are wanted
    // ({0, 0} for the others).
    struct Progress {
        int done = 0, target = 0;
        const char* unit = "spp";  // what is counted: samples per pixel, probe updates ...
        bool stale = false;        // what is shown predates an edit: it is redone in the background
        bool held = false;         // stale, and the redo waits for the user: rendering adds nothing
        int read = 0;              // of `done`, those read from a cache rather than made by this run
    };
    virtual Progress progress() const { return {}; }
    // Debug views: names offered, and drawing one of them (display values, linear, [0, 1] for
    // data such as AO and normals) into `target`, an RGBA16F texture of the frame's size, after the
    // frame's passes ran.
    virtual std::vector<DebugViewDesc> debugViews() const { return {}; }
    virtual void drawDebugView(const std::string& /*view*/, const Frame& /*frame*/, GLuint /*target*/) {}
    // Facts about what the pass built, one line each ("voxels 64^3, 3.4 cm each"): --timings, `info
    // --gi METHOD` and the sandbox's timing table print them.
    virtual std::vector<std::string> stats() const { return {}; }
    // Passes that count the rays they trace: the count over every frame the pass worked in (the
    // frames PassTiming::totalMs covers), so rays / totalMs is its throughput. nullopt: not counted.
    virtual std::optional<RayCounts> raysTraced() const { return std::nullopt; }
    // A pass that bakes its light into a texture atlas (the lightmap): the atlas's texels, for the
    // bench's columns beside the bake's time and memory. nullopt: no atlas.
    virtual std::optional<int64_t> atlasTexels() const { return std::nullopt; }
    gl::GpuTimer timer;
    StepTimers steps;
};

// The median of `values` (the upper one of an even count; 0 for none): how every timing here is summarised.
double median(std::vector<double> values);
// The median of the values after the first `skip` (warm-up frames).
double medianAfter(const std::vector<double>& values, int skip);

struct PassTiming {
    std::string pass;                // "vct" or, for a step, "vct/inject"
    double medianMs = 0.0;   // over frames after warm-up in which the pass worked
    double firstMs = 0.0;    // the first frame, which builds caches
    double totalMs = 0.0;    // every frame in which it worked, warm-up included
    int workedFrames = 0;    // frames in which it did work (progressive: batches of samples)
    int samples = 0;         // progressive passes: samples this run made (0 for the others)
    int64_t bytes = 0;       // GPU memory the pass holds
    std::optional<RayCounts> rays;  // rays traced in those frames, for passes that count them
    // Millions of rays per second of the pass's GPU time (0 when not counted or no time).
    double megaRaysPerSecond() const { return rays && totalMs > 0.0 ? double(rays->total()) / (totalMs * 1e3) : 0.0; }
    bool cached = false;     // no measured frame did work: every one reused the pass's results
    bool step = false;       // a sub-step of the pass before it
};

}  // namespace gis
