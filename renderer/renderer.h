// The renderer: a plain, linear list of passes (renderer/frame.h) over one uploaded scene. A GI
// method (renderer/gi/<method>/) adds its passes through the registry; the lighting pass consumes
// what they output (the lighting contract).
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "frame.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "image.h"
#include "nonfinite_counter.h"
#include "render_settings.h"
#include "scene/scene.h"

namespace gis {

class ChannelDisplay;
class GpuEnvironment;

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
    // GPU ms of each frame rendered so far: the passes' work that frame (a cached pass adds none).
    std::vector<double> frameGpuMs() const;
    const gl::MemoryLedger& memory() const { return ledger_; }
    const RenderSettings& settings() const { return settings_; }
    const std::vector<std::unique_ptr<Pass>>& passes() const { return passes_; }
    int samplesDone() const;     // progressive methods: samples accumulated so far
    bool converged() const;
    // True when renderFrame() would execute no pass: every pass is settled (Pass::settled), so the
    // last frame's image is the one a new frame would give.
    bool settled() const;
    // Whether renderFrame() skips settled passes (the default: a static view costs nothing once
    // converged). Frame-cost measurements (bench, `render --rerun-settled`) turn it off, so every
    // pass executes every frame as a real-time engine re-renders a static view.
    void setSkipSettled(bool skip) { skipSettled_ = skip; }
    // Per pass, in passes() order: true when the last frame skipped it as settled.
    const std::vector<bool>& skippedLastFrame() const { return skipped_; }
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
    // With GIS_CHECK_FINITE=1 (nonfinite_counter.h): per pass, in passes() order, then the debug
    // view, the NaN and Inf values its shaders replaced by 0 so far; empty when not counting.
    std::vector<uint64_t> nonFiniteCounts() const;
    // "" or one line naming each pass that replaced NaN or Inf, and how many.
    std::string nonFiniteReport() const;

private:
    void drawDebugView(Frame& frame);
    void checkViewOffered(const std::string& view) const;  // throws naming the views there are
    void ensureDebugTarget();
    bool canSkip(const Pass& pass, const std::set<std::string>& reproduced) const;
    void keepOutputs(Pass& pass, Frame& frame) const;
    RenderSettings settings_;
    gl::MemoryLedger ledger_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<SceneServices> services_;
    std::unique_ptr<GpuEnvironment> environment_;      // the radiance of rays that leave the scene
    std::unique_ptr<ChannelDisplay> channelDisplay_;   // built for the first debug view
    std::vector<std::unique_ptr<Pass>> passes_;
    CameraMatrices camera_;
    GLuint hdr_ = 0, ldr_ = 0;
    gl::Texture debugTarget_;          // RGBA16F, when settings.view is not "final"
    uint64_t frameIndex_ = 0;
    std::map<std::string, FrameResource> frameResources_;  // the last frame's named resources
    std::map<std::string, FrameResource> passResources_;   // the same as the passes wrote them: what a skipped pass keeps
    bool skipSettled_ = true;
    bool redrawPending_ = false;  // the debug view changed: the next frame draws it, settled or not
    std::vector<bool> skipped_;
    std::unique_ptr<NonFiniteCounter> nonFinite_;  // with GIS_CHECK_FINITE=1 only
};

// True when going from `built` to `wanted` needs a new Renderer: anything baked into GPU
// resources differs (size, method, a rebuild parameter, shadows ...), or the environment map or its
// rotation (what every method has accumulated of the sky: probes, voxel light, the path tracer's
// samples). Camera, BRDFs, tone mapping, exposure, ambient, live parameters and a deferred
// method's debug view never do.
bool requiresRebuild(const RenderSettings& built, const RenderSettings& wanted);

// shaders/brdf_probe.comp: evaluates brdf.glsl at a list of points (the BRDF tests use it).
ProgramDesc brdfProbeProgram();

// Level 0 of an RGBA texture as an image, rows top to bottom.
ImageF readTextureFloat(GLuint texture, int width, int height);
ImageU8 readTextureBytes(GLuint texture, int width, int height);

// Every program (with its permutations) any pass can request: the shader test compiles them all.
std::vector<ProgramDesc> allPrograms();

}  // namespace gis
