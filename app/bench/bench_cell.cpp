#include "bench/bench_cell.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "cli/flythrough.h"
#include "bench/bench_record.h"
#include "bench/bench_row.h"
#include "gi/method.h"
#include "image.h"
#include "metrics.h"
#include "cli/progress.h"

namespace gis {

namespace {

namespace fs = std::filesystem;

// Renders until the image is final; returns the GPU ms and per-pass figures. Progressive methods
// (the path tracer): every frame's work summed, until converged. Methods that accumulate over
// frames (framesToConverge, from the registry): the median per frame of `frames` frames after
// warm-up, measured once converged, and the image scored is the converged one.
void measure(Renderer& renderer, const GiMethod& method, int frames, int warmup, BenchRow& row) {
    renderer.setSkipSettled(false);  // the cost of a frame that runs, as the peers' frames do
    const bool progressive = !renderer.converged();
    row.msToConverge = progressive;
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
        const double ms = progressive ? t.totalMs : t.medianMs;
        if (t.step) {  // listed apart: the pass's own figure already holds its steps
            row.steps.push_back({t.pass, ms, t.firstMs});
            continue;
        }
        row.passMs.emplace_back(t.pass, ms);
        row.ms += ms;
        if (t.rays) row.megaRaysPerSecond = t.megaRaysPerSecond();
    }
    row.bytes = renderer.memory().total();
}

// A fly-through cell: the path's frames (after the warm-up frame), summarised; the passes' and
// steps' figures are their medians over the path.
void measureFlythrough(Renderer& renderer, const Aabb& bounds, int frames, BenchRow& row) {
    const FlythroughStats stats = summarizeFlythrough(flyThrough(renderer, bounds, frames));
    row.ms = stats.medianMs;
    row.wallMs = stats.medianWallMs;
    row.flythrough = stats;
    for (const PassTiming& t : renderer.timings(1)) {
        if (t.step)
            row.steps.push_back({t.pass, t.medianMs, t.firstMs});
        else
            row.passMs.emplace_back(t.pass, t.medianMs);
    }
    row.bytes = renderer.memory().total();
}

// The mean radiance of the view through the scene's camera `camera`, rendered as the cell's image
// is: until progressive passes converge, and for the frames a method needs to converge.
double convergedMean(const Scene& scene, RenderSettings settings, const GiMethod& method, int camera) {
    settings.camera = camera;
    Renderer renderer(scene, settings);
    const int frames = method.framesToConverge ? std::max(1, method.framesToConverge(settings)) : 1;
    for (int f = 0; f < frames || !renderer.converged(); ++f) renderer.renderFrame();
    return meanRadiance(renderer.readHdr());
}

// Scene::leakCameras' leak number: the dark room's mean radiance over the lit room's; -1 for a
// scene without leak cameras or a lit room that renders black (no number to divide by).
double leakNumber(const Scene& scene, const RenderSettings& settings, const GiMethod& method) {
    const Scene::LeakCameras& c = scene.leakCameras;
    if (c.dark < 0 || c.lit < 0) return -1.0;
    const double lit = convergedMean(scene, settings, method, c.lit);
    return lit > 0.0 ? convergedMean(scene, settings, method, c.dark) / lit : -1.0;
}

// The job as the manifest describes it, made concrete; refuses one whose inputs changed since the
// plan (its id would be another).
RenderSettings resolveChecked(const BenchJob& job, PreparedScene& prepared) {
    prepared = prepareBenchScene(job);
    BenchJob now = job;
    now.sceneSha256 = prepared.sha256;
    const RenderSettings settings = jobSettings(job, prepared.base);
    const std::string id = contentId(now, settings);
    if (id == job.id) return settings;
    const std::string why =
        prepared.sha256 != job.sceneSha256 ? "the scene file " + job.scene + " changed"
        : !job.environment.empty() && environmentSha256(job.environment) != job.environmentSha256
            ? "the environment map " + job.environment + " changed"
            : "its settings resolve differently in this build";
    throw Error("job " + job.id + " is now " + id + ": " + why + " since --plan; plan again");
}

void runReference(const BenchJob& job, const SweepDirs& dirs, const GlOpener& openGl) {
    PreparedScene prepared;
    const RenderSettings settings = resolveChecked(job, prepared);
    const nlohmann::ordered_json machine = openGl();
    const bool ao = giMethod(job.method).role == MethodRole::AoReference;
    std::fprintf(stderr, "%s: rendering the %sreference (%d spp)...\n", job.sceneName.c_str(), ao ? "AO " : "",
                 job.referenceSpp);
    Renderer renderer(prepared.scene, settings);
    ProgressBar progress(job.referenceSpp, job.sceneName + (ao ? " AO reference" : " reference"));
    renderToConvergence(renderer, progress);
    const std::string exr = imagePath(dirs, job);
    writeExr(exr, renderer.readHdr());
    nlohmann::ordered_json body{{"id", job.id},          {"kind", "reference"},      {"method", job.method},
                                {"scene", job.sceneName}, {"spp", job.referenceSpp}, {"machine", machine}};
    writeRecord(recordPath(dirs, job), body, {fs::path(exr).filename().string()});
}

// A cell's reference image, verified against its record; throws naming the id when it is absent.
ImageF loadReference(const BenchJob& cell, const std::string& refId, const SweepDirs& dirs) {
    const std::string path = dirs.cacheDir + "/" + refId + ".json";
    const RecordCheck check = readRecord(path, refId);
    if (!check.ok)
        throw Error("cell " + cell.id + " needs reference " + refId + ", which is " + check.problem + " in " +
                    dirs.cacheDir + " (run bench --cell " + refId + " first)");
    return readExr(dirs.cacheDir + "/" + refId + ".exr");
}

void runFlythroughCell(const BenchJob& job, const SweepDirs& dirs, const GlOpener& openGl) {
    PreparedScene prepared;
    const RenderSettings settings = resolveChecked(job, prepared);
    const nlohmann::ordered_json machine = openGl();
    BenchRow row;
    row.scene = job.sceneName;
    row.method = job.method;
    row.preset = job.preset;
    row.emitters = job.setup.emitters;
    row.description = giMethod(job.method).preset(job.preset).description;
    Renderer renderer(prepared.scene, settings);
    measureFlythrough(renderer, prepared.scene.bounds, job.frames, row);
    const std::string png = imagePath(dirs, job);
    writePng(png, renderer.readLdr());
    const FlythroughStats& f = *row.flythrough;
    std::fprintf(stderr, "%-14s %-10s %-8s flythrough %d frames: GPU ms median %.2f, worst %.2f; %d moved a cascade\n",
                 row.scene.c_str(), row.method.c_str(), row.preset.c_str(), f.frames, f.medianMs, f.worstMs,
                 f.moveFrames);
    nlohmann::ordered_json body{{"id", job.id}, {"kind", "cell"}, {"machine", machine}, {"row", rowToJson(row)}};
    writeRecord(recordPath(dirs, job), body, {fs::path(png).filename().string()});
}

void runCell(const BenchJob& job, const SweepDirs& dirs, const GlOpener& openGl) {
    const ImageF reference = loadReference(job, job.reference, dirs);
    const ImageF aoReference = job.aoReference.empty() ? ImageF{} : loadReference(job, job.aoReference, dirs);
    PreparedScene prepared;
    const RenderSettings settings = resolveChecked(job, prepared);
    const nlohmann::ordered_json machine = openGl();
    const GiMethod& method = giMethod(job.method);
    BenchRow row;
    row.scene = job.sceneName;
    row.method = job.method;
    row.preset = job.preset;
    row.emitters = job.setup.emitters;
    row.description = method.preset(job.preset).description;
    Renderer renderer(prepared.scene, settings);
    measure(renderer, method, job.frames, job.warmup, row);
    row.error = compareImages(renderer.readHdr(), reference);
    row.leak = leakNumber(prepared.scene, settings, method);
    if (!aoReference.rgba.empty()) {
        RenderSettings aoView = settings;
        aoView.view = "ao";
        Renderer aoRenderer(prepared.scene, aoView);
        aoRenderer.renderFrame();
        row.aoRmse = rmse(aoRenderer.readHdr(), aoReference);
    }
    const std::string png = imagePath(dirs, job);
    writePng(png, renderer.readLdr());
    std::fprintf(stderr, "%-14s %-10s %-8s %10.2f ms GPU %10.2f ms wall %8.2f MiB  FLIP %.4f  RMSE %.5f  SSIM %.4f%s\n",
                 row.scene.c_str(), row.method.c_str(), row.preset.c_str(), row.ms, row.wallMs,
                 double(row.bytes) / (1 << 20), row.error.flip, row.error.rmse, row.error.ssim,
                 row.aoRmse >= 0.0 ? ("  AO RMSE " + std::to_string(row.aoRmse)).c_str() : "");
    if (row.leak >= 0.0) std::fprintf(stderr, "%-14s %-10s %-8s leak number %.4f\n", row.scene.c_str(), row.method.c_str(), row.preset.c_str(), row.leak);
    nlohmann::ordered_json body{{"id", job.id}, {"kind", "cell"}, {"machine", machine}, {"row", rowToJson(row)}};
    writeRecord(recordPath(dirs, job), body, {fs::path(png).filename().string()});
}

}  // namespace

SweepDirs sweepDirs(const std::string& outDir, const std::string& cacheDir) {
    return {outDir, cacheDir.empty() ? outDir + "/cache" : cacheDir};
}

void createSweepDirs(const SweepDirs& dirs) {
    std::error_code ec;
    for (const std::string& dir : {dirs.outDir + "/cells", dirs.cacheDir}) {
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir)) throw Error("cannot create directory '" + dir + "' (--out-dir, --cache-dir)");
    }
}

std::string recordPath(const SweepDirs& dirs, const BenchJob& job) {
    return (job.kind == JobKind::Cell ? dirs.outDir + "/cells/" : dirs.cacheDir + "/") + job.id + ".json";
}

std::string imagePath(const SweepDirs& dirs, const BenchJob& job) {
    return job.kind == JobKind::Cell ? dirs.outDir + "/cells/" + job.id + ".png" : dirs.cacheDir + "/" + job.id + ".exr";
}

nlohmann::ordered_json currentMachine(const std::string& backend) {
    return {{"gl_renderer", reinterpret_cast<const char*>(glGetString(GL_RENDERER))},
            {"gl_version", reinterpret_cast<const char*>(glGetString(GL_VERSION))},
            {"backend", backend}};
}

JobOutcome runJob(const BenchJob& job, const SweepDirs& dirs, bool force, const GlOpener& openGl) {
    const std::string record = recordPath(dirs, job);
    if (!force && readRecord(record, job.id).ok) {
        if (job.kind == JobKind::Reference)
            std::fprintf(stderr, "%s: %sreference from cache %s\n", job.sceneName.c_str(),
                         giMethod(job.method).role == MethodRole::AoReference ? "AO " : "", imagePath(dirs, job).c_str());
        else
            std::fprintf(stderr, "%s: done already (%s); --force runs it again\n", job.id.c_str(), record.c_str());
        return JobOutcome::AlreadyDone;
    }
    try {
        if (job.kind == JobKind::Reference)
            runReference(job, dirs, openGl);
        else if (job.flythrough)
            runFlythroughCell(job, dirs, openGl);
        else
            runCell(job, dirs, openGl);
    } catch (const std::exception& e) {
        writeFailure(record, e.what());
        throw;
    }
    clearFailure(record);
    return JobOutcome::Ran;
}

}  // namespace gis
