#include "bench/bench_cell.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

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

// Frames a static view needs after a cut or an edit, as the registry declares them (progressive
// passes report their own progress besides).
int declaredFrames(const GiMethod& method, const RenderSettings& settings) {
    return method.framesToConverge ? std::max(1, method.framesToConverge(settings)) : 1;
}

// One frame, waited for: its wall-clock ms.
double timedFrame(Renderer& renderer) {
    const auto t0 = std::chrono::steady_clock::now();
    renderer.renderFrame();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A frame's image stops changing, for the bench, once it and every later frame stay within this
// fraction of the final image's mean radiance in RMS: about the smallest change of brightness a
// viewer notices (Weber's fraction for luminance is one to two percent).
constexpr double kSettledFraction = 0.01;
// Images are compared box-filtered by this factor: what a viewer sees change, less the per-pixel
// sample noise of a single frame.
constexpr int kSettledShrink = 4;

ImageF boxShrink(const ImageF& image, int factor) {
    ImageF out;
    out.width = std::max(1, image.width / factor);
    out.height = std::max(1, image.height / factor);
    out.rgba.assign(size_t(out.width) * out.height * 4, 0.0f);
    for (int y = 0; y < out.height * factor && y < image.height; ++y)
        for (int x = 0; x < out.width * factor && x < image.width; ++x)
            for (int c = 0; c < 4; ++c) out.at(x / factor, y / factor)[c] += image.at(x, y)[c];
    const float n = float(factor * factor);
    for (float& v : out.rgba) v /= n;
    return out;
}

// The first frame from which every frame's image stays within kSettledFraction of the last one's.
int firstSettledFrame(const std::vector<ImageF>& frames) {
    const ImageF& last = frames.back();
    const double tolerance = kSettledFraction * meanRadiance(last);
    size_t settled = frames.size();
    while (settled > 1 && rmse(frames[settled - 2], last) <= tolerance) --settled;
    return int(settled);
}

// Renders from now until the image is final: at least `declared` frames and until every
// progressive pass has converged, and measures when the image actually stopped changing.
// `onFrame(n, gpuMsSoFar, last, image)` runs after the n-th frame, with its HDR image.
BenchRow::Convergence renderUntilFinal(Renderer& renderer, int declared,
                                       const std::function<void(int, double, bool, const ImageF&)>& onFrame) {
    const size_t before = renderer.frameGpuMs().size();
    BenchRow::Convergence c;
    std::vector<double> gpu;
    std::vector<ImageF> images;
    for (bool last = false; !last;) {
        c.wallMs += timedFrame(renderer);
        ++c.frames;
        last = c.frames >= declared && renderer.converged();
        const std::vector<double> all = renderer.frameGpuMs();
        gpu.assign(all.begin() + std::ptrdiff_t(before), all.end());
        c.gpuMs = 0.0;
        for (double ms : gpu) c.gpuMs += ms;
        const ImageF image = renderer.readHdr();
        images.push_back(boxShrink(image, kSettledShrink));
        if (onFrame) onFrame(c.frames, c.gpuMs, last, image);
    }
    c.frameMs = c.frames > 1 ? medianAfter(gpu, 1) : gpu.front();
    c.settledFrames = firstSettledFrame(images);
    for (size_t i = 0; i < std::min(gpu.size(), size_t(c.settledFrames)); ++i) c.settledGpuMs += gpu[i];
    return c;
}

// A cell's measurements on a still camera, in the order a user meets them:
// - the cut: a renderer with nothing accumulated rendered until its image is final, scored against
//   the reference at 1, 2, 4, ... frames and at the last (the time-to-quality curve);
// - the steady frame: `frames` more, every pass executed (render --rerun-settled), medians after
//   `warmup`; the image scored is this final one.
// Every pass executes every frame throughout, as the peers' frames do.
void measure(Renderer& renderer, const GiMethod& method, const ImageF& reference, int frames, int warmup,
             BenchRow& row) {
    renderer.setSkipSettled(false);
    row.cut = renderUntilFinal(renderer, declaredFrames(method, renderer.settings()),
                               [&](int n, double gpuMs, bool last, const ImageF& image) {
                                   if ((n & (n - 1)) == 0 || last) row.quality.push_back({n, gpuMs, compareImages(image, reference)});
                               });
    for (const PassTiming& t : renderer.timings(0))
        if (t.rays) row.megaRaysPerSecond = t.megaRaysPerSecond();  // over the samples the cut traced
    std::vector<double> wall;
    for (int i = 0; i < frames; ++i) wall.push_back(timedFrame(renderer));
    row.wallMs = medianAfter(wall, warmup);
    for (const PassTiming& t : renderer.timings(row.cut.frames + warmup)) {
        if (t.step) {  // listed apart: the pass's own figure already holds its steps
            row.steps.push_back({t.pass, t.medianMs, t.firstMs});
            continue;
        }
        row.passMs.emplace_back(t.pass, t.medianMs);
        row.ms += t.medianMs;
    }
    if (row.cut.frames == 1) row.cut.frameMs = row.ms;  // no frame after the first: the steady one is its frame
    row.bytes = renderer.memory().total();
    for (const auto& pass : renderer.passes())
        if (const std::optional<int64_t> texels = pass->atlasTexels()) row.atlasTexels = *texels;
}

// After the steady frames: the first punctual light's intensity halved (as a light edit in the
// viewer) and the frames until the image is final again. Restores the light; nothing for a scene
// without one.
void measureLightEdit(Renderer& renderer, Scene& scene, const GiMethod& method, BenchRow& row) {
    if (scene.lights.empty()) return;
    const float intensity = scene.lights.front().intensity;
    scene.lights.front().intensity = 0.5f * intensity;
    renderer.lightsChanged();
    row.edit = renderUntilFinal(renderer, declaredFrames(method, renderer.settings()), nullptr);
    scene.lights.front().intensity = intensity;
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
    const int frames = declaredFrames(method, settings);
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
    {  // compiles the cell's programs (a process-wide cache): the cut measures rendering, not the compiler
        Renderer warm(prepared.scene, settings);
        warm.renderFrame();
    }
    Renderer renderer(prepared.scene, settings);
    measure(renderer, method, reference, job.frames, job.warmup, row);
    row.error = compareImages(renderer.readHdr(), reference);
    const std::string png = imagePath(dirs, job);
    writePng(png, renderer.readLdr());
    measureLightEdit(renderer, prepared.scene, method, row);
    row.leak = leakNumber(prepared.scene, settings, method);
    if (!aoReference.rgba.empty()) {
        RenderSettings aoView = settings;
        aoView.view = "ao";
        Renderer aoRenderer(prepared.scene, aoView);
        aoRenderer.renderFrame();
        row.aoRmse = rmse(aoRenderer.readHdr(), aoReference);
    }
    std::fprintf(stderr, "%-14s %-10s %-8s %10.2f ms GPU %10.2f ms wall %8.2f MiB  FLIP %.4f  RMSE %.5f  SSIM %.4f%s\n",
                 row.scene.c_str(), row.method.c_str(), row.preset.c_str(), row.ms, row.wallMs,
                 double(row.bytes) / (1 << 20), row.error.flip, row.error.rmse, row.error.ssim,
                 row.aoRmse >= 0.0 ? ("  AO RMSE " + std::to_string(row.aoRmse)).c_str() : "");
    std::fprintf(stderr, "%-14s %-10s %-8s after a cut: final in %d frames (settled at %d), %.1f ms GPU (%.2f a frame), FLIP %.4f at the first\n",
                 row.scene.c_str(), row.method.c_str(), row.preset.c_str(), row.cut.frames, row.cut.settledFrames, row.cut.gpuMs,
                 row.cut.frameMs, row.quality.front().error.flip);
    if (row.edit)
        std::fprintf(stderr, "%-14s %-10s %-8s after a light edit: settled at frame %d of %d, %.1f ms GPU until then\n",
                     row.scene.c_str(), row.method.c_str(), row.preset.c_str(), row.edit->settledFrames,
                     row.edit->frames, row.edit->settledGpuMs);
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
