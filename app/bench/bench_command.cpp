// gisandbox bench: for each scene, every GI method at each quality preset - GPU milliseconds per
// pass, GPU memory held, and error against a path-traced reference rendered once and cached.
// Writes bench.json, bench.csv, a labelled comparison grid and an error-versus-milliseconds chart
// (with the Pareto front) per scene.
//
// One plan, run in one of two ways: here in-process (references, then cells, then the merge), or
// spread by a scheduler: --plan prints the jobs, --cell runs one, --merge gathers the results.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "bench/bench_cell.h"
#include "bench/bench_merge.h"
#include "bench/bench_plan.h"
#include "camera_path.h"
#include "cli/commands.h"
#include "scene/atomic_file.h"

namespace gis {

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
    cmd.add_option("--out-dir", o.outDir, "Where bench.json, bench.csv, the PNGs and cells/ go")->capture_default_str();
    cmd.add_option("--cache-dir", o.cacheDir, "Where references are cached by content id (default: OUT_DIR/cache)");
    cmd.add_option("--backend", o.backend, "OpenGL context: auto, egl, osmesa")->capture_default_str();
    addSceneSetupOptions(cmd, o.setup);
    cmd.add_option("--ambient", o.ambient, "Constant ambient radiance: one value or R,G,B")->delimiter(',')->expected(1, 3);
    addEnvironmentOptions(cmd, o.environment, o.environmentRotation);
    cmd.add_option("--background", o.background, "Environment radiance R,G,B (or one value), overriding the scene's")
        ->delimiter(',')
        ->expected(1, 3);
    cmd.add_flag("--flythrough{" + std::to_string(kFlythroughFrames) + "}", o.flythrough,
                 "Measure camera motion: each cell flies the scripted path (--flythrough=N: N frames, default " +
                     std::to_string(kFlythroughFrames) + "), median and worst frame, frames that moved a cascade; "
                     "no reference, no error");
    CLI::Option* plan = cmd.add_flag("--plan", o.plan, "Print the sweep's jobs (JSON Lines, references first) and exit");
    CLI::Option* cell = cmd.add_option("--cell", o.cell, "Run the one job ID of --manifest (a reference or a cell)");
    CLI::Option* merge = cmd.add_option("--merge", o.merge, "Gather the results in DIR into bench.json, bench.csv, charts, grids");
    CLI::Option* ids = cmd.add_option("--ids", o.ids, "Print the ids of --manifest's jobs of one kind: references, cells, all");
    cmd.add_option("--manifest", o.manifest, "The sweep's plan (bench --plan's output; default for --merge: DIR/manifest.jsonl)");
    cmd.add_flag("--force", o.force, "--cell: run the job even when its result is there already");
    plan->excludes(cell)->excludes(merge)->excludes(ids);
    cell->excludes(merge)->excludes(ids);
    merge->excludes(ids);
}

namespace {

// The GL context of this process, opened on first use. In-process callers (tests) that already
// hold a current context pass useCurrentContext: a second EGL context on the same display would
// tear theirs down with it.
class LazyContext {
public:
    explicit LazyContext(const BenchOptions& o) : o_(o) {}
    nlohmann::ordered_json operator()() {
        if (machine_.is_null()) {
            ContextOptions co;
            co.backend = parseBackend(o_.backend);
            if (!o_.useCurrentContext) ctx_ = createContext(co);
            machine_ = currentMachine(ctx_ ? backendName(ctx_->backend()) : "caller's context");
            std::fprintf(stderr, "bench on %s (%s)\n", machine_["gl_renderer"].get<std::string>().c_str(),
                         machine_["backend"].get<std::string>().c_str());
        }
        return machine_;
    }

private:
    const BenchOptions& o_;
    std::unique_ptr<GlContext> ctx_;
    nlohmann::ordered_json machine_;
};

int printIds(const BenchOptions& o) {
    if (o.ids != "references" && o.ids != "cells" && o.ids != "all")
        throw Error("--ids '" + o.ids + "' must be references, cells or all");
    std::set<std::string> printed;  // two scenes with the same bytes share their jobs: each runs once
    for (const BenchJob& job : readManifest(o.manifest))
        if ((o.ids == "all" || (o.ids == "cells") == (job.kind == JobKind::Cell)) && printed.insert(job.id).second)
            std::printf("%s\n", job.id.c_str());
    return 0;
}

int runOneJob(const BenchOptions& o) {
    const std::vector<BenchJob> jobs = readManifest(o.manifest);
    const BenchJob& job = findJob(jobs, o.cell, o.manifest);
    const SweepDirs dirs = sweepDirs(o.outDir, o.cacheDir);
    createSweepDirs(dirs);
    LazyContext context(o);
    runJob(job, dirs, o.force, std::ref(context));
    return 0;
}

int mergeResults(const BenchOptions& o) {
    // The merge reads DIR/cells and writes its tables and charts into DIR: an --out-dir elsewhere
    // would be silently ignored, so it is refused.
    const BenchOptions defaults;
    if (o.outDir != defaults.outDir && std::filesystem::weakly_canonical(o.outDir) != std::filesystem::weakly_canonical(o.merge))
        throw Error("bench --merge " + o.merge + " writes its results into " + o.merge + ": --out-dir " + o.outDir +
                    " does not apply (give --merge " + o.outDir + " to merge there)");
    if (o.manifest.empty() && !std::filesystem::exists(o.merge + "/manifest.jsonl"))
        throw Error("bench --merge " + o.merge + ": no manifest there (" + o.merge +
                    "/manifest.jsonl, which a plain bench run writes); give the plan with --manifest FILE");
    const std::string manifest = o.manifest.empty() ? o.merge + "/manifest.jsonl" : o.manifest;
    return mergeBench(readManifest(manifest), sweepDirs(o.merge, o.cacheDir), o.metric);
}

// The whole plan here: its manifest into OUT_DIR, references (from the cache where there), every
// cell measured afresh (timings are the point of a plain run), then the merge.
int runInProcess(const BenchOptions& o) {
    const std::vector<BenchJob> jobs = planBench(o);
    const SweepDirs dirs = sweepDirs(o.outDir, o.cacheDir);
    createSweepDirs(dirs);
    std::ostringstream manifest;
    writeManifest(manifest, jobs);
    writeFileAtomically(o.outDir + "/manifest.jsonl", manifest.str());
    LazyContext context(o);
    context();  // the machine line first, as before
    std::set<std::string> done;  // two scenes with the same bytes share their jobs: each runs once
    for (const BenchJob& job : jobs)
        if (done.insert(job.id).second) runJob(job, dirs, /*force=*/job.kind == JobKind::Cell, std::ref(context));
    return mergeBench(jobs, dirs, o.metric);
}

}  // namespace

int runBench(const BenchOptions& o) {
    if (o.plan) {
        writeManifest(std::cout, planBench(o));
        std::cout.flush();
        if (!std::cout) throw Error("--plan: cannot write the manifest to standard output");
        return 0;
    }
    if (!o.ids.empty()) return printIds(o);
    if (!o.cell.empty()) return runOneJob(o);
    if (!o.merge.empty()) return mergeResults(o);
    return runInProcess(o);
}

}  // namespace gis
