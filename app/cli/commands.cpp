#include "cli/commands.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <chrono>
#include <regex>
#include <unistd.h>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "cli/flythrough.h"
#include "bvh.h"
#include "volume/volume_cascades.h"
#include "camera_path.h"
#include "cli/progress.h"
#include "gi/method.h"
#include "gl/shader.h"
#include "image.h"
#include "scene/atomic_file.h"
#include "cli/settings_io.h"
#include "cli/view_state.h"

namespace gis {

void parseRenderSize(const std::string& text, int& w, int& h) {
    static const std::regex re(R"(^(-?\d{1,12})x(-?\d{1,12})$)");
    std::smatch m;
    if (!std::regex_match(text, m, re)) throw Error("--size '" + text + "' is not WIDTHxHEIGHT (e.g. 256x256)");
    const long long lw = std::stoll(m[1]), lh = std::stoll(m[2]);
    if (lw < 1 || lh < 1 || lw > 16384 || lh > 16384)
        throw Error("--size " + text + " is out of range (1..16384 per side)");
    w = int(lw);
    h = int(lh);
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw Error("--size " + text + " is out of range (1..16384 per side)");
}

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {  // case-insensitive: x.PNG is a PNG
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
               return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
           });
}

// Fails before any rendering when `path` cannot be written: a directory, a missing or unwritable
// folder (with the OS's reason). Creates and removes a temporary file beside it.
void checkWritable(const std::string& path, const char* flag) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw Error(std::string(flag) + " '" + path + "' is a directory");
    const fs::path dir = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
    if (!fs::is_directory(dir, ec)) throw Error(std::string(flag) + ": directory '" + dir.string() + "' does not exist");
    // The probe is the atomic writer's own temporary (random name, O_EXCL): a fixed probe name
    // could be a planted symlink that fopen would follow and truncate.
    try {
        checkCanCreateBeside(path);
    } catch (const Error& e) {
        throw Error(std::string(flag) + " '" + path + "' cannot be written: " + e.what());
    }
}

// --frames N when given; otherwise the method's frames to converge, so a temporal method writes its
// accumulated image (as bench scores it), and with --timings at least --frames' default.
int framesToRender(const RenderOptions& o, const RenderSettings& s) {
    if (o.given && o.given("--frames")) return o.frames;
    const GiMethod& method = giMethod(s.gi);
    const int converge = method.framesToConverge ? std::max(1, method.framesToConverge(s)) : 1;
    return o.timings ? std::max(o.frames, converge) : converge;
}

void printWarnings(const Scene& scene) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "gisandbox: warning: %s\n", w.c_str());
}

std::unique_ptr<GlContext> headlessContext(const std::string& backend, bool debug, bool verbose) {
    ContextOptions co;
    co.backend = parseBackend(backend);
    co.debug = debug;
    auto ctx = createContext(co);
    if (verbose)
        std::fprintf(stderr, "backend: %s (%s)\nGL_RENDERER: %s\nGL_VERSION: %s\n", backendName(ctx->backend()),
                     ctx->detail.c_str(), ctx->renderer.c_str(), ctx->version.c_str());
    return ctx;
}

double mib(int64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

// GPU milliseconds per pass and its steps: the median over the frames after warm-up in which it
// worked, the first frame apart (it builds what later frames reuse); "total" sums the passes'
// medians, a frame's cost. A progressive pass (the path tracer, a bake) adds the total it spent on
// the samples this run made and its time per sample; "cached" only when no measured frame worked.
void printTimings(const Renderer& renderer, int frames, int warmup) {
    const auto& owners = renderer.memory().bytesByOwner;
    std::printf("%-22s %10s %10s %9s\n", "pass", "median ms", "first ms", "MiB");
    double total = 0.0;
    for (const PassTiming& t : renderer.timings(warmup)) {
        const std::string name = t.step ? "  " + t.pass.substr(t.pass.find('/') + 1) : t.pass;
        std::printf("%-22s %10.3f %10.3f %9.2f%s", name.c_str(), t.medianMs, t.firstMs, t.step ? 0.0 : mib(t.bytes),
                    t.cached ? "  (cached: nothing it depends on changed)" : "");
        if (t.samples > 0)
            std::printf("  total %.1f ms for %d samples: %.3f ms/sample", t.totalMs, t.samples, t.totalMs / t.samples);
        std::printf("\n");
        if (t.samples > 0 && t.rays)
            std::printf("%-22s %.3g Mrays/s: %.3g M rays (primary %.3g M, bounce %.3g M, shadow %.3g M) in %.1f ms\n",
                        "  rays", t.megaRaysPerSecond(), t.rays->total() * 1e-6, t.rays->primary * 1e-6,
                        t.rays->bounce * 1e-6, t.rays->shadow * 1e-6, t.totalMs);
        if (!t.step) total += t.medianMs;
    }
    for (const auto& [owner, bytes] : owners)
        if (owner.rfind("scene", 0) == 0) std::printf("%-22s %10s %10s %9.2f\n", owner.c_str(), "", "", mib(bytes));
    std::printf("%-22s %10.3f %10s %9.2f  (%dx%d, %d frames, median of the last %d)\n", "total", total, "",
                mib(renderer.memory().total()), renderer.settings().width, renderer.settings().height, frames,
                frames - warmup);
    for (const auto& pass : renderer.passes())
        for (const std::string& line : pass->stats()) std::printf("%-22s %s\n", pass->name(), line.c_str());
}

std::string builtinSceneList() {
    std::string list;
    for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
    return list;
}

// A documented alias (--spp, --ao-radius) sets the rendered method's row when it declares one, so
// it never warns there; otherwise every row that declares it, and the check below says it is unused.
void setAlias(RenderSettings& s, const std::string& flag, const std::string& value) {
    for (const ParamDesc& d : giMethod(s.gi).params)
        if (d.alias == flag) {
            s.params[s.gi + "." + d.key] = parseParamValue(s.gi, d, value);
            return;
        }
    setParam(s, flag, value);
}

// `--preset NAME`, or without it the viewer's default pane preset, so one method gives one image
// in render and in the viewer (ssao: GTAO, the fast kernel; pathtrace: the same spp). A method
// without that preset keeps its parameter defaults.
void applyRenderPreset(RenderSettings& s, const std::string& given) {
    const std::string preset = given.empty() ? view::PaneState{}.preset : given;
    const GiMethod& method = giMethod(s.gi);
    const bool has = std::any_of(method.presets.begin(), method.presets.end(),
                                 [&](const GiPreset& p) { return p.name == preset; });
    if (has || !given.empty()) applyPreset(s, s.gi, preset);
}

// The frame as --out asks (.exr: linear HDR, else PNG), box-filtered down by --supersample: the
// EXR's pixel is then the mean radiance over its square, as the Cycles references' is, the PNG's
// the mean of the display values. With GIS_CHECK_FINITE=1 an image whose shaders replaced a NaN or
// Inf is a bug's image: not written.
void writeRenderedImage(const Renderer& renderer, const RenderOptions& o) {
    const std::string report = renderer.nonFiniteReport();
    if (!report.empty()) throw Error("GIS_CHECK_FINITE: " + report + "; the image is not written");
    if (endsWith(o.out, ".exr")) writeExr(o.out, downsample(renderer.readHdr(), o.supersample));
    else writePng(o.out, downsample(renderer.readLdr(), o.supersample));
}

// `render --flythrough`: the scripted path's frames (renderer/camera_path.h), the last one written;
// with --timings each frame's GPU and wall ms and the cascades it rebuilt, then the passes' medians
// over the path (the warm-up frame left out).
int renderFlythrough(Renderer& renderer, const Scene& scene, const RenderOptions& o) {
    const std::vector<FlythroughFrame> frames = flyThrough(renderer, scene.bounds, o.flythrough);
    writeRenderedImage(renderer, o);
    if (o.timings) {
        printFlythrough(frames);
        printTimings(renderer, o.flythrough + 1, 1);
    }
    std::printf("wrote %s (frame %d of the fly-through)\n", o.out.c_str(), o.flythrough - 1);
    return 0;
}

// Older flags stay as aliases of their parameter rows (one flag may set the same key of
// several methods, e.g. --spp for pathtrace and ao-reference).
void addParameterAliasOptions(CLI::App& cmd, RenderOptions& o) {
    for (const GiMethod& m : giMethods())
        for (const ParamDesc& d : m.params) {
            if (d.alias.empty() || o.aliases.count(d.alias) || o.aliasFlags.count(d.alias)) continue;
            std::string keys;  // every method's row the flag stands for: it sets the rendered method's
            for (const GiMethod& other : giMethods())
                for (const ParamDesc& od : other.params)
                    if (od.alias == d.alias) keys += (keys.empty() ? "" : " or ") + other.name + "." + od.key;
            const std::string help = "Alias of --set " + keys + " (the rendered method's): " + d.help;
            if (d.type == ParamType::Bool) {
                o.aliasFlags[d.alias] = false;
                cmd.add_flag(d.alias, o.aliasFlags[d.alias], help);
            } else {
                o.aliases[d.alias] = "";
                cmd.add_option(d.alias, o.aliases[d.alias], help);
            }
        }
}

}  // namespace

void addEnvironmentOptions(CLI::App& cmd, std::string& path, float& rotationDegrees) {
    cmd.add_option("--environment", path,
                   "Equirectangular Radiance .hdr lighting the scene from afar (every method; not with --background); "
                   "mapped as Blender maps it: the centre column looks down +X, the top row is the zenith")
        ->check([](const std::string& v) {
            return v.empty() ? std::string("an empty name is no file (leave --environment out for no map)") : std::string();
        });
    cmd.add_option("--environment-rotation", rotationDegrees,
                   "Degrees the --environment map is turned about +Y (90: its centre column looks down -Z)")
        ->capture_default_str();
}

void addRenderOptions(CLI::App& cmd, RenderOptions& o) {
    cmd.add_option("--scene", o.scene,
                   "glTF file (.gltf/.glb) or builtin:NAME (" + builtinSceneList() + "); required unless "
                   "--settings names one");
    cmd.add_option("--out", o.out, "Output image: .png (tonemapped sRGB 8-bit) or .exr (linear float radiance)");
    cmd.add_option("--size", o.size, "Image size WIDTHxHEIGHT")->capture_default_str();
    cmd.add_option("--supersample", o.supersample,
                   "Render N x N pixels for each written one and average them (1-4): edges as the Cycles "
                   "references' box-filtered pixels have them; --timings then times the larger frame")
        ->capture_default_str();
    cmd.add_option("--backend", o.backend, "OpenGL context: auto (EGL, else OSMesa), egl, osmesa, glfw (hidden window)")
        ->capture_default_str();
    addSceneSetupOptions(cmd, o.setup);
    cmd.add_option("--gi", o.gi, "Global illumination method: " + giMethodNames())->capture_default_str();
    cmd.add_option("--diffuse", o.diffuse, "Diffuse BRDF: lambert, wrap (roughness-driven wrap), toon, burley")
        ->capture_default_str();
    cmd.add_option("--specular", o.specular,
                   "Specular BRDF: ggx (Schlick-GGX), blinn (normalised Blinn-Phong), toon, none")
        ->capture_default_str();
    cmd.add_option("--tonemap", o.tonemap, "Tone mapper for PNG output: aces (fitted), linear (clamp)")
        ->capture_default_str();
    cmd.add_option("--exposure", o.exposure, "Exposure in EV (scale 2^EV) before tone mapping")->capture_default_str();
    cmd.add_option("--ambient", o.ambient, "Constant ambient radiance for --gi none: one value or R,G,B")
        ->delimiter(',')
        ->expected(1, 3)
        ->capture_default_str();
    cmd.add_option("--shadow-size", o.shadowSize, "Shadow map resolution for directional and spot lights")
        ->capture_default_str();
    cmd.add_option("--shadow-cube-size", o.shadowCubeSize, "Shadow cube map resolution for point lights")
        ->capture_default_str();
    cmd.add_option("--background", o.background, "Environment radiance R,G,B (or one value), overriding the scene's")
        ->delimiter(',')
        ->expected(1, 3);
    addEnvironmentOptions(cmd, o.environment, o.environmentRotation);
    cmd.add_option("--preset", o.preset, "Quality preset of the --gi method: low, medium, high (see `gisandbox methods`); without it "
                   "medium, the viewer's default, where the method has one");
    cmd.add_option("--set", o.sets,
                   "A method parameter, METHOD.KEY=VALUE (repeatable; e.g. --set ssao.samples=32). "
                   "`gisandbox methods NAME` lists them")
        ->take_all()
        ->allow_extra_args(false);
    addParameterAliasOptions(cmd, o);
    cmd.add_option("--view", o.view,
                   "What to output: final, or a debug view the method's passes offer (gbuffer.normal, ao, ...); "
                   "`--view list` lists them")
        ->capture_default_str();
    cmd.add_flag("--no-shadows", o.noShadows, "Disable shadow maps");
    cmd.add_flag("--hdr32", o.hdr32, "Light into RGBA32F instead of RGBA16F");
    cmd.add_flag("--timings", o.timings,
                 "Print GPU ms per pass (median after warm-up) over the frames rendered, every pass executed each "
                 "frame as bench measures (without --timings a still view re-runs nothing once settled)");
    cmd.add_option("--frames", o.frames,
                   "Frames to render; without it the method's frames to converge (temporal methods), with "
                   "--timings at least 30. Progressive methods (pathtrace) still render all their samples");
    cmd.add_flag("--rerun-settled", o.rerunSettled,
                 "Execute every pass every frame, also those whose outputs would not change (frame-cost "
                 "comparisons with engines that re-render a static view)");
    cmd.add_option("--warmup", o.warmup, "Frames left out of the --timings median")->capture_default_str();
    cmd.add_flag("--flythrough{" + std::to_string(kFlythroughFrames) + "}", o.flythrough,
                 "Fly the scripted camera path through the scene (--flythrough=N: N frames, default " +
                     std::to_string(kFlythroughFrames) + "); writes the last frame, --timings prints every frame");
    cmd.add_flag("--gl-debug", o.glDebug, "Debug context; print KHR_debug messages (always on in Debug builds)");
    cmd.add_flag("-v,--verbose", o.verbose, "Print the backend, GL_RENDERER and GL_VERSION");
    cmd.add_option("--settings", o.settings,
                   "A `gisandbox view` settings file (or screenshot sidecar): render its pane as the view does; "
                   "flags given here override it");
    cmd.add_option("--pane", o.pane, "With --settings: which pane (0 = single/left/top-left)")->capture_default_str();
    o.given = [&cmd](const std::string& flag) { return cmd.count(flag) > 0; };
}

namespace {

// What `render` renders: the settings its flags give, or a --settings file's pane with only the
// flags given explicitly over it.
struct RenderJob {
    const RenderOptions& o;
    RenderSettings s;
    std::optional<view::ViewState> viewSettings;  // --settings
    std::string sceneSpec;

    bool given(const char* flag) const { return o.given && o.given(flag); }
    // Whether `flag` sets its setting: always, but over a settings file only when given.
    bool use(const char* flag) const { return !viewSettings || given(flag); }
    // The settings file's free camera, unless the command line places the camera.
    bool fileCamera() const { return viewSettings && viewSettings->camera.free && !use("--camera") && !use("--camera-pos"); }
};

void readRenderSettingsFile(RenderJob& job) {
    const RenderOptions& o = job.o;
    if (o.settings.empty()) {
        if (job.given("--pane")) throw Error("--pane needs --settings");
        return;
    }
    job.viewSettings = view::loadViewSettings(o.settings);
    const view::ViewState& file = *job.viewSettings;
    const int panes = view::paneCount(file.mode);
    if (o.pane < 0 || o.pane >= panes)
        throw Error("--pane " + std::to_string(o.pane) + ": the settings' " + view::viewModeName(file.mode) +
                    " view has " + std::to_string(panes) + " pane(s)");
    const glm::ivec2 size = view::paneRenderSize(file, file.viewWidth, file.viewHeight);
    job.s = view::paneSettings(file, o.pane, size);
    if (!job.use("--scene")) job.sceneSpec = file.scene;
    if (file.panes[o.pane].display == view::PaneDisplay::Heatmap && !job.use("--view"))
        throw Error("--pane " + std::to_string(o.pane) + " displays the error heatmap, which render does not draw: "
                    "add --view final and compare with `gisandbox diff`");
}

void checkRenderCounts(const RenderOptions& o) {
    if (o.frames < 1 || o.frames > 100000) throw Error("--frames must be in [1, 100000]");
    if (o.supersample < 1 || o.supersample > 4) throw Error("--supersample must be in [1, 4]");
    if (o.timings && (o.warmup < 0 || o.warmup >= o.frames)) throw Error("--warmup must be in [0, --frames)");
    if (o.flythrough < 0 || o.flythrough > 100000)
        throw Error("--flythrough=N must be in [0, 100000] (0: a still camera)");
    if (o.ambient.size() != 1 && o.ambient.size() != 3) throw Error("--ambient takes one value or R,G,B");
}

void checkRenderOut(const RenderOptions& o, bool listViews) {
    if (o.out.empty() && !listViews) throw Error("--out is required");
    if (!listViews && std::filesystem::is_directory(o.out)) throw Error("--out '" + o.out + "' is a directory");
    if (!listViews && !endsWith(o.out, ".exr") && !endsWith(o.out, ".png"))
        throw Error("--out '" + o.out + "' must end in .png or .exr");
}

glm::vec3 oneOrThree(const std::vector<float>& v) { return v.size() == 3 ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(v[0]); }

// The method, BRDFs, image and lighting flags.
void applyLookFlags(RenderJob& job) {
    const RenderOptions& o = job.o;
    RenderSettings& s = job.s;
    if (job.use("--gi")) s.gi = o.gi;
    giMethod(s.gi);  // throws for an unknown method
    if (job.use("--diffuse")) s.diffuse = parseDiffuse(o.diffuse);
    if (job.use("--specular")) s.specular = parseSpecular(o.specular);
    if (job.use("--tonemap")) s.tonemap = parseTonemapper(o.tonemap);
    if (job.use("--exposure")) s.exposureEV = o.exposure;
    if (job.use("--ambient")) s.ambient = oneOrThree(o.ambient);
    if (job.use("--shadow-size")) s.shadowMapSize = o.shadowSize;
    if (job.use("--shadow-cube-size")) s.shadowCubeSize = o.shadowCubeSize;
    if (job.use("--no-shadows")) s.shadows = !o.noShadows;
    if (job.use("--hdr32")) s.hdr32 = o.hdr32;
    if (!o.background.empty()) {
        if (o.background.size() != 1 && o.background.size() != 3) throw Error("--background takes one value or R,G,B");
        s.background = oneOrThree(o.background);
        // The constant ambient stands for the environment's radiance (the default sky sets both),
        // so --background without --ambient reaches none's and ssao's ambient term too.
        if (!job.viewSettings && !job.given("--ambient")) s.ambient = *s.background;
    }
    if (job.use("--environment")) s.environment = o.environment;
    if (job.use("--environment-rotation")) s.environmentRotation = o.environmentRotation;
    checkEnvironmentChoice(false, s.environment, job.given("--ambient"));
    checkEnvironmentRotation(s.environmentRotation, s.environment);
}

// The preset and the method parameters (--set and the older alias flags), then the view.
void applyParameterFlags(RenderJob& job) {
    const RenderOptions& o = job.o;
    RenderSettings& s = job.s;
    if (job.use("--preset")) applyRenderPreset(s, o.preset);
    // A shadow-map size given on the command line wins over the preset's.
    if (job.given("--shadow-size")) s.shadowMapSize = o.shadowSize;
    if (job.given("--shadow-cube-size")) s.shadowCubeSize = o.shadowCubeSize;
    for (const auto& [flag, value] : o.aliases)
        if (o.given && o.given(flag)) setAlias(s, flag, value);
    for (const auto& [flag, on] : o.aliasFlags)
        if (o.given && o.given(flag)) setAlias(s, flag, on ? "true" : "false");
    for (const std::string& kv : o.sets) {
        const size_t eq = kv.find('=');
        if (eq == std::string::npos) throw Error("--set '" + kv + "' is not METHOD.KEY=VALUE");
        setParam(s, kv.substr(0, eq), kv.substr(eq + 1));
    }
    if (job.use("--view")) s.view = o.view;
    // Progressive methods add a few samples per frame so progress can be shown between frames.
    s.samplesPerFrame = 4;
}

// A parameter of another method than the one rendered does nothing: say so.
void warnOtherMethodsParams(const RenderJob& job) {
    const RenderSettings& s = job.s;
    for (const auto& [key, value] : s.params)
        if (key.rfind(s.gi + ".", 0) != 0 && !isGroupParam(key) &&
            !(job.viewSettings && key == roleParamKey(MethodRole::Reference, "bounces")))
            std::fprintf(stderr, "gisandbox: warning: %s is a parameter of another method than --gi %s: ignored\n",
                         key.c_str(), s.gi.c_str());
}

// Lighting, camera and the settings file's light edits, as the view set them up.
void setUpRenderScene(RenderJob& job, Scene& scene) {
    const RenderOptions& o = job.o;
    SceneSetupOptions setup = o.setup;
    if (job.viewSettings && !job.use("--lighting")) setup.lighting = job.viewSettings->lighting;
    // With --settings the file's ambient stands: the view applied the same rule when it opened the scene.
    const bool ambientFixed = job.viewSettings.has_value() || job.given("--ambient") || job.given("--background");
    const int camera = prepareScene(scene, setup, float(job.s.width) / float(job.s.height), &job.s, ambientFixed);
    if (job.viewSettings) scene.lights = view::effectiveLights(*job.viewSettings, scene.lights);  // the panel's edits
    // The glTF loader's depth-range check, for the settings file's own camera.
    if (job.fileCamera()) {
        const std::string warning = checkCameraDepth(scene.bounds, job.viewSettings->camera.position,
                                                     job.viewSettings->camera.znear, o.settings + ": camera");
        if (!warning.empty()) std::fprintf(stderr, "gisandbox: warning: %s\n", warning.c_str());
    }
    if (!job.viewSettings || job.use("--camera") || job.use("--camera-pos")) job.s.camera = camera;
}

std::unique_ptr<GlContext> renderContext(const RenderOptions& o) {
    if (parseBackend(o.backend) != Backend::Glfw) return headlessContext(o.backend, o.glDebug, o.verbose);
    ContextOptions co;
    co.backend = Backend::Glfw;
    co.debug = o.glDebug;
    std::unique_ptr<GlContext> ctx = createContext(co);
    if (o.verbose)
        std::fprintf(stderr, "backend: glfw (%s)\nGL_RENDERER: %s\nGL_VERSION: %s\n", ctx->detail.c_str(),
                     ctx->renderer.c_str(), ctx->version.c_str());
    return ctx;
}

// `frames` frames; the wall clock of each with the GPU finished, comparable with other engines'
// wall-clock figures (Godot's frame time) where GPU timer queries are not.
std::vector<double> renderFrames(Renderer& renderer, int frames, bool timings) {
    std::vector<double> wallMs;
    std::optional<ProgressBar> frameProgress;
    if (frames > 1) frameProgress.emplace(frames, "", "frames");
    for (int i = 0; i < frames; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        renderer.renderFrame();
        if (timings || frameProgress) glFinish();
        wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        if (frameProgress) frameProgress->update(i + 1);
    }
    if (frameProgress) frameProgress->finish();
    return wallMs;
}

// The references count their samples with --spp, so they render them all whatever --frames
// says; other progressive methods (probe updates) stop at --frames when it is given.
void renderRestToConvergence(Renderer& renderer, const RenderJob& job) {
    if (renderer.converged() || (job.given("--frames") && giMethod(job.s.gi).role == MethodRole::Method)) return;
    Pass::Progress longest;
    for (const auto& pass : renderer.passes())
        if (pass->progress().target > longest.target) longest = pass->progress();
    ProgressBar progress(longest.target, "", longest.unit);
    renderToConvergence(renderer, progress);
}

}  // namespace

int runRender(const RenderOptions& o) {
    RenderJob job{o, {}, std::nullopt, o.scene};
    readRenderSettingsFile(job);
    if (job.sceneSpec.empty()) throw Error("--scene is required (or --settings FILE)");
    RenderSettings& s = job.s;
    if (job.use("--size")) parseRenderSize(o.size, s.width, s.height);
    checkRenderCounts(o);
    s.width *= o.supersample, s.height *= o.supersample;  // the renderer's own size limits apply to these
    const bool listViews = job.given("--view") && o.view == "list";
    checkRenderOut(o, listViews);
    applyLookFlags(job);
    applyParameterFlags(job);
    if (!listViews) checkWritable(o.out, "--out");
    warnOtherMethodsParams(job);

    Scene scene = loadScene(job.sceneSpec);
    printWarnings(scene);
    setUpRenderScene(job, scene);
    const std::unique_ptr<GlContext> ctx = renderContext(o);
    if (s.view == "list") {  // what this method's passes can show
        s.view = "final";
        Renderer lister(scene, s);
        for (const DebugViewDesc& v : lister.views()) std::printf("%-20s %s\n", v.name.c_str(), v.help.c_str());
        return 0;
    }
    Renderer renderer(scene, s);
    if (job.fileCamera()) renderer.setCamera(view::viewCameraMatrices(*job.viewSettings, scene, float(s.width) / float(s.height)));
    renderer.setSkipSettled(!o.rerunSettled);
    if (o.flythrough > 0) return renderFlythrough(renderer, scene, o);
    // A still camera settles every pass after a frame or a few, and a settled pass's timer reads 0:
    // --timings measures the frames as they cost when they run, as bench does.
    if (o.timings) renderer.setSkipSettled(false);
    const int frames = framesToRender(o, s);
    const std::vector<double> wallMs = renderFrames(renderer, frames, o.timings);
    renderRestToConvergence(renderer, job);
    writeRenderedImage(renderer, o);
    if (o.timings) {
        printTimings(renderer, frames, o.warmup);
        std::printf("%-22s %10.3f %10.3f %9s  (wall clock per frame with glFinish, median after warm-up)\n", "wall",
                    medianAfter(wallMs, o.warmup), wallMs.front(), "");
    }
    std::printf("wrote %s\n", o.out.c_str());
    return 0;
}

void addInfoOptions(CLI::App& cmd, InfoOptions& o) {
    cmd.add_option("--scene", o.scene, "glTF file (.gltf/.glb) or builtin:NAME (" + builtinSceneList() + ")")->required();
    cmd.add_option("--size", o.size, "Image size the GPU memory figures assume")->capture_default_str();
    cmd.add_option("--backend", o.backend, "OpenGL context for the GPU memory figures: auto, egl, osmesa")
        ->capture_default_str();
    cmd.add_flag("--json", o.json, "Print JSON instead of text");
    cmd.add_flag("--no-gpu", o.noGpu, "Skip the GPU memory figures (no OpenGL context needed)");
    cmd.add_option("--gi", o.gi, "The GI method whose passes, memory and volumes (voxel size, probe count) to report")
        ->capture_default_str();
    cmd.add_option("--preset", o.preset, "Its preset: low, medium, high");
    cmd.add_option("--camera", o.camera, "The scene camera the view depth and the methods' cascades follow")
        ->capture_default_str();
}

int runInfo(const InfoOptions& o) {
    int w = 0, h = 0;
    parseRenderSize(o.size, w, h);
    Scene scene = loadScene(o.scene);
    nlohmann::ordered_json j;
    j["scene"] = scene.name;
    j["meshes"] = scene.primitives.size();
    j["draws"] = scene.draws.size();
    j["triangles"] = scene.triangleCount();
    j["materials"] = scene.materials.size();
    j["textures"] = scene.images.size();
    j["lights"] = scene.lights.size();
    j["cameras"] = scene.cameras.size();
    if (scene.bounds.empty())
        j["bounds"] = nullptr;
    else
        j["bounds"] = {{"min", {scene.bounds.min.x, scene.bounds.min.y, scene.bounds.min.z}},
                       {"max", {scene.bounds.max.x, scene.bounds.max.y, scene.bounds.max.z}}};
    static const char* lightTypes[] = {"directional", "point", "spot"};
    for (const Light& l : scene.lights)
        j["light_list"].push_back({{"name", l.name}, {"type", lightTypes[int(l.type)]}, {"intensity", l.intensity},
                                   {"color", {l.color.r, l.color.g, l.color.b}},
                                   {"position", {l.position.x, l.position.y, l.position.z}}});
    j["warnings"] = scene.warnings;
    if (scene.triangleCount() > 0) {
        const Bvh bvh = buildBvh(scene);  // what --gi pathtrace builds
        j["bvh"] = {{"builder", "Embree rtcBuildBVH, SAH, binary, <= 4 triangles per leaf"},
                    {"nodes", bvh.nodes.size()}, {"leaves", bvh.leafCount}, {"depth", bvh.depth},
                    {"sah_cost", bvh.sahCost}, {"build_ms", bvh.buildMs}};
        // What the cascades' count follows (METHOD.cascade-extent 0): the render camera's view depth.
        const float depth = nearViewDepth(bvh, cameraMatrices(scene, o.camera, float(w) / float(h)));
        j["view_depth"] = std::isfinite(depth) ? nlohmann::ordered_json(depth) : nlohmann::ordered_json(nullptr);
    }
    if (!o.noGpu) {
        auto ctx = headlessContext(o.backend, false, false);
        RenderSettings s;
        s.width = w;
        s.height = h;
        s.gi = o.gi;
        s.camera = o.camera;
        if (!o.preset.empty()) applyPreset(s, o.gi, o.preset);
        Renderer renderer(scene, s);
        renderer.renderFrame();  // what methods build on their first frame (volumes, probes) exists then
        j["gpu"] = {{"renderer", ctx->renderer}, {"size", o.size}, {"gi", s.gi}};
        for (const auto& pass : renderer.passes())
            for (const std::string& line : pass->stats()) j["gpu"]["stats"][pass->name()].push_back(line);
        for (const auto& [owner, bytes] : renderer.memory().bytesByOwner) j["gpu"]["bytes"][owner] = bytes;
        j["gpu"]["total_bytes"] = renderer.memory().total();
    }
    if (o.json) {
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    std::printf("scene      %s\n", scene.name.c_str());
    std::printf("meshes     %zu primitives, %zu draws, %zu triangles\n", scene.primitives.size(), scene.draws.size(),
                scene.triangleCount());
    std::printf("materials  %zu (%zu textures)\n", scene.materials.size(), scene.images.size());
    std::printf("lights     %zu\n", scene.lights.size());
    for (const Light& l : scene.lights)
        std::printf("  %-11s %-16s intensity %g colour (%g, %g, %g)\n", lightTypes[int(l.type)], l.name.c_str(),
                    l.intensity, l.color.r, l.color.g, l.color.b);
    std::printf("cameras    %zu\n", scene.cameras.size());
    if (scene.bounds.empty())
        std::printf("bounds     empty (no geometry)\n");
    else
        std::printf("bounds     (%g, %g, %g) .. (%g, %g, %g)\n", scene.bounds.min.x, scene.bounds.min.y,
                    scene.bounds.min.z, scene.bounds.max.x, scene.bounds.max.y, scene.bounds.max.z);
    if (j.contains("bvh"))
        std::printf("BVH        %zu nodes, %d leaves, depth %d, SAH cost %.2f, built in %.2f ms (Embree SAH)\n",
                    j["bvh"]["nodes"].get<size_t>(), j["bvh"]["leaves"].get<int>(), j["bvh"]["depth"].get<int>(),
                    j["bvh"]["sah_cost"].get<double>(), j["bvh"]["build_ms"].get<double>());
    if (j.contains("view_depth"))
        std::printf("view depth %s (the distance to the nearest tenth of the camera's view: cascades follow it)\n",
                    j["view_depth"].is_null() ? "infinite" : std::to_string(j["view_depth"].get<double>()).c_str());
    for (const std::string& warning : scene.warnings) std::printf("warning    %s\n", warning.c_str());
    if (!o.noGpu) {
        std::printf("GPU memory at %s on %s:\n", o.size.c_str(), j["gpu"]["renderer"].get<std::string>().c_str());
        for (const auto& [owner, bytes] : j["gpu"]["bytes"].items())
            std::printf("  %-10s %8.2f MiB\n", owner.c_str(), mib(bytes.get<int64_t>()));
        std::printf("  %-10s %8.2f MiB\n", "total", mib(j["gpu"]["total_bytes"].get<int64_t>()));
        if (j["gpu"].contains("stats"))
            for (const auto& [pass, lines] : j["gpu"]["stats"].items())
                for (const auto& line : lines) std::printf("%-10s %s\n", pass.c_str(), line.get<std::string>().c_str());
    }
    return 0;
}

void addMethodsOptions(CLI::App& cmd, MethodsOptions& o) {
    cmd.add_option("method", o.method, "A method: list its parameters (type, range, default, live/rebuild, help)");
    cmd.add_flag("--json", o.json, "Print JSON instead of text");
}

namespace {

// One method's presets and parameters as aligned columns, each as wide as its longest entry.
void printMethodTable(const GiMethod& m) {
    size_t presetWidth = 0;
    for (const GiPreset& p : m.presets) presetWidth = std::max(presetWidth, p.name.size());
    for (const GiPreset& p : m.presets) std::printf("  preset %-*s  %s\n", int(presetWidth), p.name.c_str(), p.description.c_str());
    if (m.params.empty()) std::printf("  (no parameters)\n");
    std::vector<std::array<std::string, 5>> rows;
    for (const ParamDesc& d : m.params)
        rows.push_back({m.name + "." + d.key, paramTypeName(d.type), describeParamRange(d),
                        "default " + formatParamValue(d, d.defaultValue), d.update == ParamUpdate::Live ? "live" : "rebuild"});
    std::array<size_t, 5> width{};
    for (const auto& r : rows)
        for (size_t c = 0; c < r.size(); ++c) width[c] = std::max(width[c], r[c].size());
    for (size_t i = 0; i < rows.size(); ++i) {
        std::printf(" ");
        for (size_t c = 0; c < rows[i].size(); ++c) std::printf(" %-*s", int(width[c]), rows[i][c].c_str());
        const ParamDesc& d = m.params[i];
        std::printf("  %s%s\n", d.help.c_str(), d.alias.empty() ? "" : (" (alias " + d.alias + ")").c_str());
    }
}

}  // namespace

int runMethods(const MethodsOptions& o) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    std::vector<const GiMethod*> list;
    if (o.method.empty())
        for (const GiMethod& m : giMethods()) list.push_back(&m);
    else if (!findGiMethod(o.method) && isGroupParam(o.method + "."))
        ;  // a shared table's name: only its rows below
    else
        list.push_back(&giMethod(o.method));
    for (const GiMethod* m : list) {
        nlohmann::ordered_json e{{"name", m->name}, {"summary", m->summary},
                                 {"pipeline", m->pipeline == MethodPipeline::Deferred ? "deferred" : "standalone"},
                                 {"environment_light_by_default", m->environmentLightByDefault}};
        for (const GiPreset& p : m->presets) e["presets"][p.name] = p.description;
        for (const ParamDesc& d : m->params)
            e["params"].push_back({{"key", m->name + "." + d.key}, {"type", paramTypeName(d.type)},
                                   {"range", describeParamRange(d)}, {"default", formatParamValue(d, d.defaultValue)},
                                   {"update", d.update == ParamUpdate::Live ? "live" : "rebuild"},
                                   {"alias", d.alias}, {"label", d.label}, {"help", d.help}});
        j.push_back(e);
    }
    // The shared tables (the emitter lights): listed with every method, or by their own name.
    std::vector<const ParamGroup*> groups;
    for (const ParamGroup& g : paramGroups())
        if (o.method.empty() || o.method == g.name) groups.push_back(&g);
    for (const ParamGroup* g : groups) {
        nlohmann::ordered_json e{{"name", g->name}, {"summary", g->summary}, {"pipeline", "shared"}};
        for (const ParamDesc& d : g->params)
            e["params"].push_back({{"key", g->name + "." + d.key}, {"type", paramTypeName(d.type)},
                                   {"range", describeParamRange(d)}, {"default", formatParamValue(d, d.defaultValue)},
                                   {"update", d.update == ParamUpdate::Live ? "live" : "rebuild"},
                                   {"alias", d.alias}, {"label", d.label}, {"help", d.help}});
        j.push_back(e);
    }
    if (o.json) {
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    size_t nameWidth = 0;
    for (const GiMethod* m : list) nameWidth = std::max(nameWidth, m->name.size());
    for (const GiMethod* m : list) {
        std::printf("%-*s  %s\n", int(nameWidth), m->name.c_str(), m->summary.c_str());
        if (o.method.empty()) continue;
        printMethodTable(*m);
        std::printf("emitters.environment=auto: the environment is %sa light of the direct pass under %s\n",
                    m->environmentLightByDefault ? "" : "not ", m->name.c_str());
    }
    for (const ParamGroup* g : groups) {
        std::printf("%-13s %s (shared by every method)\n", g->name.c_str(), g->summary.c_str());
        for (const ParamDesc& d : g->params)
            std::printf("  %-26s %-6s %-24s default %-10s %-7s %s\n", (g->name + "." + d.key).c_str(),
                        paramTypeName(d.type), describeParamRange(d).c_str(), formatParamValue(d, d.defaultValue).c_str(),
                        d.update == ParamUpdate::Live ? "live" : "rebuild", d.help.c_str());
    }
    if (o.method.empty()) std::printf("\n`gisandbox methods NAME` lists a method's parameters and presets.\n");
    return 0;
}

void addExportOptions(CLI::App& cmd, ExportOptions& o) {
    cmd.add_option("--scene", o.scene, "builtin:NAME[?options] (or a glTF file) to write")->required();
    cmd.add_option("--out", o.out, "Output .gltf (its .bin is written beside it)")->required();
}

int runExport(const ExportOptions& o) {
    if (!endsWith(o.out, ".gltf")) throw Error("--out '" + o.out + "' must end in .gltf");
    checkWritable(o.out, "--out");
    const Scene scene = loadScene(o.scene);
    writeGltf(scene, o.out);
    auto count = [](size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
    std::printf("wrote %s (%s, %s, %s)\n", o.out.c_str(), count(scene.triangleCount(), "triangle", "triangles").c_str(),
                count(scene.lights.size(), "light", "lights").c_str(), count(scene.cameras.size(), "camera", "cameras").c_str());
    if (scene.background != glm::vec3(0.0f))
        std::fprintf(stderr,
                     "gisandbox: warning: glTF has no environment colour: render it under a sky of radiance "
                     "(%g, %g, %g) to match\n",
                     scene.background.r, scene.background.g, scene.background.b);
    return 0;
}

void addShaderDumpOptions(CLI::App& cmd, ShaderDumpOptions& o) {
    cmd.add_option("--dump", o.dir, "Directory to write PROGRAM.STAGEFILE files into (for glslangValidator)")
        ->required();
}

int runShaderDump(const ShaderDumpOptions& o) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(o.dir, ec);
    if (!fs::is_directory(o.dir)) throw Error("--dump: cannot create directory '" + o.dir + "'");
    int count = 0;
    for (const ProgramDesc& p : allPrograms()) {
        for (const std::string& stage : p.stages) {
            const PreprocessedShader pre = preprocessShader(stage, p.defines);
            // A stage in a subfolder (gi/ssao/ssao.frag) is dumped flat: its file name is enough.
            const std::string path = o.dir + "/" + p.name + "." + fs::path(stage).filename().string();
            writeFileAtomically(path, pre.source);
            ++count;
        }
    }
    std::printf("wrote %d shader stages to %s\n", count, o.dir.c_str());
    return 0;
}

}  // namespace gis
