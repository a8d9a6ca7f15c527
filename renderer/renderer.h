// The frame: a plain, linear list of passes over one uploaded scene. Each pass declares the named
// textures/buffers it reads and writes, owns its GL resources (charged to its name in the memory
// ledger) and is timed with GPU timer queries. Adding a GI method = adding a pass.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "gl/shader.h"
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
enum class DebugView { Final, AmbientOcclusion };

DiffuseModel parseDiffuse(const std::string& s);    // lambert, wrap, toon, burley
SpecularModel parseSpecular(const std::string& s);  // ggx, blinn, toon, none
Tonemapper parseTonemapper(const std::string& s);
std::string giMethodNames();          // "none" (others as they land)
void checkGiMethod(const std::string& s);

struct RenderSettings {
    int width = 256, height = 256;
    int camera = 0;                    // index into Scene::cameras; a default camera when there are none
    std::string gi = "none";
    DiffuseModel diffuse = DiffuseModel::Lambert;
    SpecularModel specular = SpecularModel::Ggx;
    Tonemapper tonemap = Tonemapper::Aces;
    float exposureEV = 0.0f;
    glm::vec3 ambient{0.03f};          // constant ambient radiance: the `--gi none` baseline
    int shadowMapSize = 1024;          // directional and spot lights
    int shadowCubeSize = 512;          // point lights
    bool shadows = true;
    bool hdr32 = false;                // RGBA32F lighting buffer instead of RGBA16F
    std::optional<glm::vec3> background;  // overrides the scene's environment radiance
    // --gi pathtrace
    int spp = 64;                      // samples per pixel to accumulate
    int samplesPerFrame = 1;           // samples added by each renderFrame()
    int maxBounces = 16;               // indirect bounces; 0 = direct lighting only
    int russianRouletteStart = 3;      // bounce from which Russian roulette may end a path
    uint32_t seed = 0;                 // fixed: the same settings give the same image
    // --gi ssao (and --gi ao-reference, which uses aoRadius)
    int aoSamples = 16;                // directions in the hemisphere kernel
    int aoSteps = 4;                   // points tested along each direction
    float aoRadius = 0.0f;             // world units; 0 = 15% of the scene's bounding-box diagonal
    float aoBias = 0.03f;              // depth bias as a fraction of the radius
    float aoPower = 1.0f;              // AO^power (contrast)
    bool aoBlur = true;                // bilateral 4x4 blur
    bool aoHalfResolution = false;
    bool aoTemporal = false;           // reprojected accumulation with per-frame noise rotation
    DebugView view = DebugView::Final;
};

DebugView parseDebugView(const std::string& s);  // final, ao

struct CameraMatrices {
    glm::mat4 view{1.0f}, proj{1.0f}, viewProj{1.0f}, invViewProj{1.0f};
    glm::vec3 position{0.0f};
    float znear = 0.01f, zfar = 100.0f;
};
CameraMatrices cameraMatrices(const Scene& scene, int cameraIndex, float aspect);

// What the passes share during one frame: settings, the scene, the camera and named resources.
struct Frame {
    const RenderSettings& settings;
    const GpuScene& scene;
    CameraMatrices camera;
    std::map<std::string, GLuint> textures;
    std::map<std::string, GLuint> buffers;
    uint64_t index = 0;                 // frames rendered before this one
    GLuint texture(const std::string& name) const;
    GLuint buffer(const std::string& name) const;
};

class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    virtual std::vector<std::string> inputs() const { return {}; }
    virtual std::vector<std::string> outputs() const { return {}; }
    virtual void execute(Frame& frame) = 0;
    // True when the last execute() reused cached results (e.g. static shadow maps).
    virtual bool reusedLastFrame() const { return false; }
    // Progressive passes accumulate samples over frames: how many are in and how many are wanted
    // ({0, 0} for the others), and a restart when what they accumulate changed.
    struct Progress {
        int done = 0, target = 0;
    };
    virtual Progress progress() const { return {}; }
    virtual void restart() {}
    gl::GpuTimer timer;
};

struct PassTiming {
    std::string pass;
    double medianMs = 0.0;   // over frames after warm-up (0 when every frame reused a cache)
    double firstMs = 0.0;    // the first frame, which builds caches
    int64_t bytes = 0;       // GPU memory the pass holds
    bool cached = false;     // the last frame reused this pass's results instead of recomputing
};

class Renderer {
public:
    // Needs a current GL 4.5 context. Throws gis::Error on bad settings or GL failure.
    Renderer(const Scene& scene, const RenderSettings& settings);
    ~Renderer();
    void renderFrame();
    ImageF readHdr() const;      // linear radiance, rows top to bottom
    ImageU8 readLdr() const;     // tonemapped sRGB RGBA8, rows top to bottom
    // Per pass, in execution order; `warmup` first frames are left out of the median.
    std::vector<PassTiming> timings(int warmup) const;
    const gl::MemoryLedger& memory() const { return ledger_; }
    const RenderSettings& settings() const { return settings_; }
    const std::vector<std::unique_ptr<Pass>>& passes() const { return passes_; }
    // Progressive methods (the path tracer): samples accumulated so far, and the target.
    int samplesDone() const;
    bool converged() const;

    // Interactive use (`gisandbox view`), additive to the batch interface above.
    // Replaces the camera (settings.camera's until now); progressive passes start over.
    void setCamera(const CameraMatrices& camera);
    const CameraMatrices& camera() const { return camera_; }
    // Changes the settings that passes read only in execute(), never when they are built: the BRDF
    // models, tone mapper and exposure. Progressive passes start over when the BRDFs change.
    // (A pass that bakes any of these into its resources must not: the view relies on it.)
    void setLiveSettings(DiffuseModel diffuse, SpecularModel specular, Tonemapper tonemap, float exposureEV);
    // Progressive passes (the path tracer) discard their samples and start again.
    void restartAccumulation();
    // A named texture the last frame produced ("gbuffer.normal", "radiance", "display", ...); 0 if none.
    GLuint frameTexture(const std::string& name) const;

private:
    RenderSettings settings_;
    gl::MemoryLedger ledger_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::vector<std::unique_ptr<Pass>> passes_;
    CameraMatrices camera_;
    GLuint hdr_ = 0, ldr_ = 0;
    uint64_t frameIndex_ = 0;
    std::map<std::string, GLuint> frameTextures_;  // the last frame's named textures
};

// shaders/brdf_probe.comp: evaluates brdf.glsl at a list of points (the BRDF tests use it).
ProgramDesc brdfProbeProgram();

// Level 0 of an RGBA texture as an image, rows top to bottom.
ImageF readTextureFloat(GLuint texture, int width, int height);
ImageU8 readTextureBytes(GLuint texture, int width, int height);

// Every program (with its permutations) any pass can request: the shader test compiles them all.
std::vector<ProgramDesc> allPrograms();

}  // namespace gis
