// gisandbox bench: for each scene, every GI method at each quality preset - GPU milliseconds per
// pass, GPU memory held, and error against a path-traced reference rendered once and cached.
// Writes bench.json, bench.csv, a labelled comparison grid and an error-versus-milliseconds chart
// (with the Pareto front) per scene.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "commands.h"
#include "metrics.h"
#include "plot.h"
#include "progress.h"
#include "gi/method.h"
#include "tonemap.h"

namespace gis {

namespace {

namespace fs = std::filesystem;

struct BenchRow {
    std::string scene, method, preset, description;
    double ms = 0.0;                          // per frame; for progressive methods, to converge
    double wallMs = 0.0;                      // wall clock with glFinish, the same way
    std::vector<std::pair<std::string, double>> passMs;
    int64_t bytes = 0;
    ImageMetrics error;
    double aoRmse = -1.0;                     // SSAO only: its AO term against ray-traced AO
};

// The reference depends on the scene (and the file's size and time for glTF files), camera,
// size, sample count, bounces and seed: all of them are in the cache key.
std::string referenceKey(const std::string& sceneSpec, const Scene& scene, const RenderSettings& s) {
    std::ostringstream key;
    // What --camera/--lighting/--background made of the scene: the camera used, lights, environment.
    const glm::mat4& cam = scene.cameras.at(size_t(s.camera)).cameraToWorld;
    for (int c = 0; c < 16; ++c) key << cam[c / 4][c % 4] << ",";
    for (const Light& l : scene.lights)
        key << "|L" << int(l.type) << l.intensity << l.color.r << l.color.g << l.color.b << l.position.x << l.position.y
            << l.position.z << l.direction.x << l.direction.y << l.direction.z;
    const glm::vec3 env = s.background.value_or(scene.background);
    key << "|env" << env.r << "," << env.g << "," << env.b << "|";
    key << sceneSpec << "|" << s.width << "x" << s.height << "|cam" << s.camera << "|" << s.gi << "|seed" << s.seed;
    for (const auto& [name, value] : s.params) key << "|" << name << "=" << formatParamValue(findParam(name), value);
    std::error_code ec;
    if (fs::is_regular_file(sceneSpec, ec))
        key << "|" << fs::file_size(sceneSpec, ec) << "|" << fs::last_write_time(sceneSpec, ec).time_since_epoch().count();
    char hex[20];
    std::snprintf(hex, sizeof hex, "%016zx", std::hash<std::string>{}(key.str()));
    return hex;
}

std::string fileSafe(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return s;
}

// Renders until the image is final; returns the GPU ms and per-pass figures. Progressive methods
// (the path tracer): every frame's work summed, until converged. Methods that accumulate over
// frames (framesToConverge, from the registry): the median per frame of `frames` frames after
// warm-up, measured once converged, and the image scored is the converged one.
void measure(Renderer& renderer, const GiMethod& method, int frames, int warmup, BenchRow& row) {
    const bool progressive = !renderer.converged();
    const int converge = method.framesToConverge ? std::max(1, method.framesToConverge(renderer.settings())) : 1;
    std::vector<double> wall;
    auto frame = [&] {
        const auto t0 = std::chrono::steady_clock::now();
        renderer.renderFrame();
        glFinish();
        wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    };
    if (progressive) {
        do frame();
        while (!renderer.converged());
        for (double w : wall) row.wallMs += w;
    } else {
        for (int i = 0; i < converge - 1 + frames; ++i) frame();
        row.wallMs = medianAfter(wall, converge - 1 + warmup);
    }
    for (const PassTiming& t : renderer.timings(progressive ? 0 : converge - 1 + warmup)) {
        if (t.step) continue;  // the pass's own figure already holds its steps
        const double ms = progressive ? t.totalMs : t.medianMs;
        row.passMs.emplace_back(t.pass, ms);
        row.ms += ms;
    }
    row.bytes = renderer.memory().total();
}

}  // namespace

void addBenchOptions(CLI::App& cmd, BenchOptions& o) {
    cmd.add_option("--scenes", o.scenes, "Scenes to measure (glTF paths or builtin:NAME), comma separated")
        ->delimiter(',')
        ->capture_default_str();
    cmd.add_option("--size", o.size, "Image size WIDTHxHEIGHT")->capture_default_str();
    cmd.add_option("--frames", o.frames, "Frames per measurement (rasterized methods)")->capture_default_str();
    cmd.add_option("--warmup", o.warmup, "Frames left out of the median")->capture_default_str();
    cmd.add_option("--methods", o.methods, "GI methods, comma separated (default: every method)")->delimiter(',');
    cmd.add_option("--presets", o.presets, "Quality presets, comma separated: low, medium, high")
        ->delimiter(',')
        ->capture_default_str();
    cmd.add_option("--reference-spp", o.referenceSpp, "Samples per pixel of the path-traced reference")
        ->capture_default_str();
    cmd.add_option("--metric", o.metric, "Error on the chart's y axis: flip, rmse, relmse, ssim")->capture_default_str();
    cmd.add_option("--out-dir", o.outDir, "Where bench.json, bench.csv and the PNGs go")->capture_default_str();
    cmd.add_option("--cache-dir", o.cacheDir, "Where references are cached (default: OUT_DIR/cache)");
    cmd.add_option("--backend", o.backend, "OpenGL context: auto, egl, osmesa")->capture_default_str();
    addSceneSetupOptions(cmd, o.setup);
    cmd.add_option("--ambient", o.ambient, "Constant ambient radiance: one value or R,G,B")->delimiter(',')->expected(1, 3);
    cmd.add_option("--background", o.background, "Environment radiance R,G,B (or one value), overriding the scene's")
        ->delimiter(',')
        ->expected(1, 3);
}

namespace {
glm::vec3 colourFlag(const std::vector<float>& v, const char* flag) {
    if (v.size() != 1 && v.size() != 3) throw Error(std::string(flag) + " takes one value or R,G,B");
    for (float x : v)
        if (!std::isfinite(x) || x < 0.0f) throw Error(std::string(flag) + " must be finite and non-negative");
    return v.size() == 3 ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(v[0]);
}

// Results are named by the scene's file stem (or builtin name), made unique within the run: two
// files whose glTF scene is called "Scene" no longer overwrite each other's chart and rows.
std::vector<std::string> uniqueSceneNames(const std::vector<std::string>& specs) {
    std::vector<std::string> names;
    for (const std::string& spec : specs) {
        std::string base = spec.rfind("builtin:", 0) == 0 ? spec.substr(8) : fs::path(spec).stem().string();
        if (base.empty()) base = "scene";
        std::string name = base;
        for (int k = 2; std::find(names.begin(), names.end(), name) != names.end(); ++k) name = base + "-" + std::to_string(k);
        names.push_back(name);
    }
    return names;
}
}  // namespace

int runBench(const BenchOptions& o) {
    RenderSettings base;
    parseRenderSize(o.size, base.width, base.height);
    if (o.frames < 1 || o.frames > 100000) throw Error("--frames must be in [1, 100000]");
    if (o.warmup < 0 || o.warmup >= o.frames)
        throw Error("--warmup " + std::to_string(o.warmup) + " must be in [0, --frames " + std::to_string(o.frames) +
                    ") (the default warm-up is 5 frames: with fewer --frames, lower --warmup too)");
    if (!o.ambient.empty()) base.ambient = colourFlag(o.ambient, "--ambient");
    if (!o.background.empty()) base.background = colourFlag(o.background, "--background");
    cameraRequest(o.setup);            // validates the camera flags before any work
    parseLightingMode(o.setup.lighting);
    if (o.referenceSpp < 1 || o.referenceSpp > (1 << 20)) throw Error("--reference-spp must be in [1, 1048576]");
    const ErrorMetric metric = parseErrorMetric(o.metric);
    std::vector<std::string> methods = o.methods;
    if (methods.empty())
        for (const GiMethod& m : giMethods())
            if (m.benchmarked) methods.push_back(m.name);
    for (const std::string& m : methods) {
        const GiMethod& method = giMethod(m);
        if (method.image != MethodImage::Radiance)
            throw Error("--methods " + m + ": its image is not radiance, so it cannot be scored against the "
                        "path-traced reference (it is the AO reference itself)");
        for (const std::string& p : o.presets) method.preset(p);  // validates the name
    }
    if (o.scenes.empty()) throw Error("--scenes needs at least one scene");
    std::vector<Scene> scenes;
    std::vector<RenderSettings> sceneBases;  // per scene: its camera, and the sky as ambient where added
    const std::vector<std::string> sceneNames = uniqueSceneNames(o.scenes);
    for (const std::string& spec : o.scenes) {  // fail early on bad input
        scenes.push_back(loadScene(spec));
        sceneBases.push_back(base);
        sceneBases.back().camera = prepareScene(scenes.back(), o.setup, float(base.width) / float(base.height),
                                                &sceneBases.back(), !o.ambient.empty());
    }
    std::error_code ec;
    const std::string cacheDir = o.cacheDir.empty() ? o.outDir + "/cache" : o.cacheDir;
    fs::create_directories(cacheDir, ec);
    if (!fs::is_directory(o.outDir) || !fs::is_directory(cacheDir))
        throw Error("cannot create --out-dir '" + o.outDir + "' or --cache-dir '" + cacheDir + "'");

    ContextOptions co;
    co.backend = parseBackend(o.backend);
    // In-process callers (tests) that already hold a current context pass useCurrentContext: a
    // second EGL context on the same display would tear theirs down with it.
    std::unique_ptr<GlContext> ctx;
    if (!o.useCurrentContext) ctx = createContext(co);
    const std::string glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string glVersion = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const std::string backend = ctx ? backendName(ctx->backend()) : "caller's context";
    std::fprintf(stderr, "bench on %s (%s), %dx%d\n", glRenderer.c_str(), backend.c_str(), base.width,
                 base.height);

    std::vector<BenchRow> rows;
    for (size_t si = 0; si < scenes.size(); ++si) {
        const Scene& scene = scenes[si];
        const std::string& sceneName = sceneNames[si];
        const RenderSettings& sceneBase = sceneBases[si];
        RenderSettings refSettings = sceneBase;
        refSettings.gi = "pathtrace";
        setParam(refSettings, "pathtrace.spp", std::to_string(o.referenceSpp));
        setParam(refSettings, "pathtrace.bounces", "64");
        refSettings.samplesPerFrame = 16;
        const std::string refPath = cacheDir + "/reference_" + fileSafe(sceneName) + "_" +
                                    referenceKey(o.scenes[si], scene, refSettings) + ".exr";
        ImageF reference;
        ImageU8 referenceLdr;
        {
            Renderer refRenderer(scene, refSettings);
            if (fs::exists(refPath)) {
                reference = readExr(refPath);
                std::fprintf(stderr, "%s: reference from cache %s\n", sceneName.c_str(), refPath.c_str());
                // (the cached image is what is compared)
            } else {
                std::fprintf(stderr, "%s: rendering the reference (%d spp)...\n", sceneName.c_str(), o.referenceSpp);
                ProgressBar progress(o.referenceSpp, sceneName + " reference");
                do {
                    refRenderer.renderFrame();
                    glFinish();
                    progress.update(refRenderer.samplesDone());
                } while (!refRenderer.converged());
                progress.finish();
                reference = refRenderer.readHdr();
                writeExr(refPath, reference);
            }
        }
        // Ray-traced AO, SSAO's own ground truth, cached the same way (only when SSAO is measured).
        ImageF aoReference;
        if (std::find(methods.begin(), methods.end(), "ssao") != methods.end()) {
            RenderSettings aoSettings = sceneBase;
            aoSettings.gi = "ao-reference";
            setParam(aoSettings, "ao-reference.spp", std::to_string(o.referenceSpp));
            aoSettings.samplesPerFrame = 64;
            const std::string aoPath = cacheDir + "/ao_reference_" + fileSafe(sceneName) + "_" +
                                       referenceKey(o.scenes[si], scene, aoSettings) + ".exr";
            if (fs::exists(aoPath)) {
                aoReference = readExr(aoPath);
            } else {
                Renderer aoRenderer(scene, aoSettings);
                do aoRenderer.renderFrame();
                while (!aoRenderer.converged());
                aoReference = aoRenderer.readHdr();
                writeExr(aoPath, aoReference);
            }
        }
        std::vector<std::pair<std::string, ImageU8>> tiles;
        tiles.emplace_back("reference  path traced, " + std::to_string(o.referenceSpp) + " spp", toLdrImage(reference, DisplaySettings{}));

        std::vector<ChartPoint> points;
        for (size_t mi = 0; mi < methods.size(); ++mi)
            for (const std::string& preset : o.presets) {
                BenchRow row;
                row.scene = sceneName;
                row.method = methods[mi];
                row.preset = preset;
                const GiMethod& method = giMethod(methods[mi]);
                row.description = method.preset(preset).description;
                RenderSettings s = sceneBase;
                applyPreset(s, methods[mi], preset);
                Renderer renderer(scene, s);
                measure(renderer, method, o.frames, o.warmup, row);
                const ImageF image = renderer.readHdr();
                row.error = compareImages(image, reference);
                if (methods[mi] == "ssao" && !aoReference.rgba.empty()) {
                    RenderSettings aoView = s;
                    aoView.view = "ao";
                    Renderer aoRenderer(scene, aoView);
                    aoRenderer.renderFrame();
                    row.aoRmse = rmse(aoRenderer.readHdr(), aoReference);
                }
                const double y = metric == ErrorMetric::Flip     ? row.error.flip
                                 : metric == ErrorMetric::Rmse   ? row.error.rmse
                                 : metric == ErrorMetric::RelMse ? row.error.relMse
                                                                 : 1.0 - row.error.ssim;
                char label[160];
                std::snprintf(label, sizeof label, "%s/%s", row.method.c_str(), row.preset.c_str());
                points.push_back({label, row.ms, y, int(mi)});
                char caption[200];
                std::snprintf(caption, sizeof caption, "%s  %.1f ms, %s %.4f", label, row.ms, o.metric.c_str(), y);
                tiles.emplace_back(caption, renderer.readLdr());
                std::fprintf(stderr, "%-14s %-10s %-8s %10.2f ms GPU %10.2f ms wall %8.2f MiB  FLIP %.4f  RMSE %.5f  SSIM %.4f%s\n",
                             sceneName.c_str(), row.method.c_str(), row.preset.c_str(), row.ms, row.wallMs,
                             double(row.bytes) / (1 << 20), row.error.flip, row.error.rmse, row.error.ssim,
                             row.aoRmse >= 0.0 ? ("  AO RMSE " + std::to_string(row.aoRmse)).c_str() : "");
                rows.push_back(row);
            }
        const std::string stem = o.outDir + "/" + fileSafe(sceneName);
        writePng(stem + "_grid.png", composeGrid(tiles, std::min<int>(4, int(tiles.size()))));
        const std::string yLabel = o.metric == "ssim" ? "1 - SSIM vs reference" : o.metric + " vs reference";
        writePng(stem + "_chart.png",
                 drawTradeoffChart(points, sceneName + ": error vs GPU time, " + o.size,
                                   "GPU ms on " + glRenderer.substr(0, glRenderer.find(" (")) +
                                       " (per frame; path tracer: all samples)",
                                   yLabel));
    }

    nlohmann::ordered_json j;
    j["machine"] = {{"gl_renderer", glRenderer}, {"gl_version", glVersion}, {"backend", backend}};
    j["size"] = o.size;
    j["frames"] = o.frames;
    j["warmup"] = o.warmup;
    j["reference_spp"] = o.referenceSpp;
    for (const BenchRow& r : rows) {
        nlohmann::ordered_json e{{"scene", r.scene}, {"method", r.method}, {"preset", r.preset},
                                 {"description", r.description}, {"gpu_ms", r.ms}, {"wall_ms", r.wallMs}, {"gpu_bytes", r.bytes},
                                 {"rmse", r.error.rmse}, {"relmse", r.error.relMse}, {"psnr_linear", r.error.psnrLinear},
                                 {"psnr_srgb", r.error.psnrSrgb}, {"ssim", r.error.ssim}, {"flip", r.error.flip}};
        for (const auto& [pass, ms] : r.passMs) e["pass_ms"][pass] = ms;
        if (r.aoRmse >= 0.0) e["ao_rmse_vs_raytraced"] = r.aoRmse;
        j["results"].push_back(e);
    }
    writeAtomically(o.outDir + "/bench.json", [&](const std::string& tmp) {
        std::ofstream f(tmp);
        f << j.dump(2) << "\n";
        if (!f) throw Error(o.outDir + "/bench.json: cannot write");
    });
    writeAtomically(o.outDir + "/bench.csv", [&](const std::string& tmp) {
        std::ofstream f(tmp);
        f << "scene,method,preset,gpu_ms,wall_ms,gpu_bytes,rmse,relmse,psnr_linear,psnr_srgb,ssim,flip,ao_rmse\n";
        for (const BenchRow& r : rows)
            f << r.scene << "," << r.method << "," << r.preset << "," << r.ms << "," << r.wallMs << "," << r.bytes << ","
              << r.error.rmse
              << "," << r.error.relMse << "," << formatMetric(r.error.psnrLinear) << ","
              << formatMetric(r.error.psnrSrgb) << "," << r.error.ssim << "," << r.error.flip << ","
              << (r.aoRmse >= 0.0 ? std::to_string(r.aoRmse) : std::string()) << "\n";
        if (!f) throw Error(o.outDir + "/bench.csv: cannot write");
    });
    std::printf("wrote %s/bench.json, %s/bench.csv and a grid and chart per scene\n", o.outDir.c_str(), o.outDir.c_str());
    return 0;
}

}  // namespace gis
