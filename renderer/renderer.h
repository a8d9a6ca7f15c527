// The frame: a plain, linear list of passes over one uploaded scene. Each pass declares the named
// textures/buffers it reads and writes, owns its GL resources (charged to its name in the memory
// ledger) and is timed with GPU timer queries. A GI method (renderer/gi/<method>/) adds its passes
// through the registry; the lighting pass consumes what they output (the lighting contract).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/shader.h"
#include "gi/params.h"
#include "gpu_scene.h"
#include "image.h"
#include "scene/scene.h"

namespace gis {

// BRDF models (shaders/brdf.glsl): the values are the GLSL DIFFUSE_* / SPECULAR_* ids.
enum class DiffuseModel { Lambert = 0, LambertWrap = 1, Toon = 2, Burley = 3 };
enum class SpecularModel { Ggx = 0, BlinnPhong = 1, Toon = 2, None = 3 };
constexpr int kDiffuseModelCount = 4;
constexpr int kSpecularModelCount = 4;
enum class Tonemapper { Aces, Linear };

DiffuseModel parseDiffuse(const std::string& s);    // lambert, wrap, toon, burley
SpecularModel parseSpecular(const std::string& s);  // ggx, blinn, toon, none
Tonemapper parseTonemapper(const std::string& s);
// Lambert or Burley diffuse with GGX or no specular: what the path tracer (the reference) renders.
bool physicallyBased(DiffuseModel diffuse, SpecularModel specular);

struct RenderSettings {
    int width = 256, height = 256;
    int camera = 0;                    // index into Scene::cameras; a default camera when there are none
    std::string gi = "none";           // a method in the registry (renderer/gi/methods.cpp)
    ParamValues params;                // "method.key" -> value, where not the row's default
    DiffuseModel diffuse = DiffuseModel::Lambert;
    SpecularModel specular = SpecularModel::Ggx;
    Tonemapper tonemap = Tonemapper::Aces;
    float exposureEV = 0.0f;
    glm::vec3 ambient{0.03f};          // constant ambient radiance, used where no method gives indirect light
    int shadowMapSize = 1024;          // directional and spot lights
    int shadowCubeSize = 512;          // point lights
    bool shadows = true;
    bool hdr32 = false;                // RGBA32F lighting buffer instead of RGBA16F
    std::optional<glm::vec3> background;  // overrides the scene's environment radiance
    int samplesPerFrame = 1;           // progressive methods: samples added by each renderFrame()
    uint32_t seed = 0;                 // fixed: the same settings give the same image
    std::string view = "final";        // "final" or a debug view some pass offers (Renderer::views)
};

// Parses and validates "method.key" = text against the registry and stores it in s.params.
void setParam(RenderSettings& s, const std::string& fullKey, const std::string& text);
// The value of "method.key" in s: what s.params holds, else the row's default.
ParamValue getParam(const RenderSettings& s, const std::string& fullKey);

struct CameraMatrices {
    glm::mat4 view{1.0f}, proj{1.0f}, viewProj{1.0f}, invViewProj{1.0f};
    glm::vec3 position{0.0f};
    float znear = 0.01f, zfar = 100.0f;
};
CameraMatrices cameraMatrices(const Scene& scene, int cameraIndex, float aspect);

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

struct SceneServices;

// What the passes share during one frame: settings, the scene, the camera and named resources.
struct Frame {
    const RenderSettings& settings;
    const GpuScene& scene;
    SceneServices& services;
    CameraMatrices camera;
    std::map<std::string, FrameResource> resources;
    uint64_t index = 0;                 // frames rendered before this one
    StepTimers* steps = nullptr;        // the executing pass's step timers
    void put(const std::string& name, const gl::Texture& texture);
    void put(const std::string& name, const gl::Buffer& buffer);
    bool has(const std::string& name) const { return resources.count(name) > 0; }
    const FrameResource& resource(const std::string& name) const;
    GLuint texture(const std::string& name) const;
    GLuint buffer(const std::string& name) const;
    StepTimers::Scope step(const std::string& name) { return steps->scope(name); }
};

// A named picture a pass can draw for inspection ("ao", "gbuffer.normal", "vct.slice").
struct DebugViewDesc {
    std::string name, help;
};

// Rays a ray-tracing pass traced, by kind: primary (from the camera), bounce (path continuation),
// shadow (visibility towards a light or emitter).
struct RayCounts {
    uint64_t primary = 0, bounce = 0, shadow = 0;
    uint64_t total() const { return primary + bounce + shadow; }
};

// The memory-barrier rule between passes: the renderer issues one glMemoryBarrier with every bit
// after each pass that declares writesImagesOrBuffers(); within a pass, the pass orders its steps.
class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    virtual std::vector<std::string> inputs() const { return {}; }
    virtual std::vector<std::string> outputs() const { return {}; }
    virtual void execute(Frame& frame) = 0;
    // True when the last execute() reused cached results (e.g. static shadow maps).
    virtual bool reusedLastFrame() const { return false; }
    // Something changed: drop what depends on it. Progressive passes start over.
    virtual void invalidate(Changes) {}
    // Image load/store or SSBO writes that later passes read.
    virtual bool writesImagesOrBuffers() const { return false; }
    // Progressive passes accumulate samples over frames: how many are in and how many are wanted
    // ({0, 0} for the others).
    struct Progress {
        int done = 0, target = 0;
        const char* unit = "spp";  // what is counted: samples per pixel, probe updates ...
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
    int samples = 0;         // progressive passes: samples accumulated (0 for the others)
    int64_t bytes = 0;       // GPU memory the pass holds
    std::optional<RayCounts> rays;  // rays traced in those frames, for passes that count them
    // Millions of rays per second of the pass's GPU time (0 when not counted or no time).
    double megaRaysPerSecond() const { return rays && totalMs > 0.0 ? double(rays->total()) / (totalMs * 1e3) : 0.0; }
    bool cached = false;     // no measured frame did work: every one reused the pass's results
    bool step = false;       // a sub-step of the pass before it
};

class Renderer {
public:
    // Needs a current GL 4.5 context. Throws gis::Error on bad settings or GL failure.
    Renderer(const Scene& scene, const RenderSettings& settings);
    ~Renderer();
    void renderFrame();
    ImageF readHdr() const;      // linear radiance (or the debug view's values), rows top to bottom
    ImageU8 readLdr() const;     // tonemapped sRGB RGBA8 (debug views: their values), rows top to bottom
    // Per pass (and its steps), in execution order; `warmup` first frames are left out of the median.
    std::vector<PassTiming> timings(int warmup) const;
    const gl::MemoryLedger& memory() const { return ledger_; }
    const RenderSettings& settings() const { return settings_; }
    const std::vector<std::unique_ptr<Pass>>& passes() const { return passes_; }
    int samplesDone() const;     // progressive methods: samples accumulated so far
    bool converged() const;
    // Debug views the passes offer ("final" first).
    std::vector<DebugViewDesc> views() const;

    // Interactive use (`gisandbox view`), additive to the batch interface above.
    void setCamera(const CameraMatrices& camera);   // invalidate(ChangeCamera)
    const CameraMatrices& camera() const { return camera_; }
    // Changes what passes read only in execute(): BRDF models, tone mapper, exposure, ambient and
    // live parameters. Throws gis::Error for a rebuild parameter (see requiresRebuild).
    void setLiveSettings(const RenderSettings& live);
    // The scene's lights changed (the caller edited the Scene this renderer was built from).
    void lightsChanged();
    void invalidate(Changes changes);
    // A named texture the last frame produced ("gbuffer.normal", "radiance", "display", ...); 0 if none.
    GLuint frameTexture(const std::string& name) const;
    const std::map<std::string, FrameResource>& frameResources() const { return frameResources_; }
    SceneServices& services() { return *services_; }

private:
    void drawDebugView(Frame& frame);
    RenderSettings settings_;
    gl::MemoryLedger ledger_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<SceneServices> services_;
    std::vector<std::unique_ptr<Pass>> passes_;
    CameraMatrices camera_;
    GLuint hdr_ = 0, ldr_ = 0;
    gl::Texture debugTarget_;          // RGBA16F, when settings.view is not "final"
    uint64_t frameIndex_ = 0;
    std::map<std::string, FrameResource> frameResources_;  // the last frame's named resources
};

// True when going from `built` to `wanted` needs a new Renderer: anything baked into GPU
// resources differs (size, method, a rebuild parameter, shadows ...). Camera, BRDFs, tone mapping,
// exposure, ambient and live parameters never do.
bool requiresRebuild(const RenderSettings& built, const RenderSettings& wanted);

// shaders/brdf_probe.comp: evaluates brdf.glsl at a list of points (the BRDF tests use it).
ProgramDesc brdfProbeProgram();

// Level 0 of an RGBA texture as an image, rows top to bottom.
ImageF readTextureFloat(GLuint texture, int width, int height);
ImageU8 readTextureBytes(GLuint texture, int width, int height);

// Every program (with its permutations) any pass can request: the shader test compiles them all.
std::vector<ProgramDesc> allPrograms();

}  // namespace gis
