#include "bench/bench_merge.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bench/bench_record.h"
#include "bench/bench_row.h"
#include "gi/method.h"
#include "image.h"
#include "metrics.h"
#include "plot.h"
#include "scene/atomic_file.h"
#include "tonemap.h"

namespace gis {

std::string rendererName(const std::string& glRenderer) { return glRenderer.substr(0, glRenderer.find(" (")); }

namespace {

using ojson = nlohmann::ordered_json;
using OutputSet = std::vector<std::pair<std::string, std::string>>;  // path, bytes: written as one

struct MergedCell {
    const BenchJob* job = nullptr;
    BenchRow row;
};

// Every cell's verified result; problems (by id) are collected, not thrown, so all are reported.
std::string describe(const BenchJob& job);

std::vector<MergedCell> gatherCells(const std::vector<BenchJob>& jobs, const SweepDirs& dirs, ojson& machine,
                                    std::vector<std::string>& problems) {
    std::vector<MergedCell> cells;
    for (const BenchJob& job : jobs) {
        if (job.kind != JobKind::Cell) continue;
        const std::string path = recordPath(dirs, job);
        const RecordCheck check = readRecord(path, job.id);
        const std::string what = describe(job);
        if (!check.ok) {
            const std::string failure = readFailure(path);
            problems.push_back(job.id + " (" + what + "): " +
                               (!check.exists && !failure.empty() ? "failed: " + failure : check.problem + ": " + path));
            continue;
        }
        MergedCell cell{&job, {}};
        try {
            cell.row = rowFromJson(check.body.at("row"));
        } catch (const std::exception& e) {
            problems.push_back(job.id + " (" + what + "): not a bench row: " + e.what());
            continue;
        }
        if (cell.row.method != job.method || cell.row.preset != job.preset) {
            problems.push_back(job.id + " (" + what + "): its record holds a " + cell.row.method + "/" +
                               cell.row.preset + " result: " + path);
            continue;
        }
        // The manifest names the row: results are shared by content, names belong to the sweep.
        cell.row.scene = job.sceneName;
        cell.row.method = job.method;
        cell.row.preset = job.preset;
        cell.row.emitters = job.setup.emitters;
        const ojson cellMachine = check.body.value("machine", ojson());
        if (machine.is_null()) machine = cellMachine;
        if (cellMachine != machine)
            std::fprintf(stderr, "gisandbox: warning: cell %s ran on %s, not %s like the first: its timings are not "
                                 "comparable with theirs\n",
                         job.id.c_str(), cellMachine.dump().c_str(), machine.dump().c_str());
        cells.push_back(cell);
    }
    return cells;
}

std::string describe(const BenchJob& job) {
    if (job.kind != JobKind::Cell) return job.sceneName + " " + job.method + " reference";
    return job.sceneName + " " + job.method + "/" + job.preset +
           (job.setup.emitters.empty() ? "" : " emitters=" + job.setup.emitters);
}

// What decides a job's scene and base settings (not its method, preset or counts): the key under
// which the scene is loaded once for all its lines.
std::string sceneKey(const BenchJob& job) {
    ojson j = jobToJson(job);
    for (const char* k : {"id", "kind", "method", "preset", "frames", "warmup", "reference", "ao_reference",
                          "reference_spp", "scene_name", "scene_sha256", "flythrough"})
        j.erase(k);
    return j.dump();
}

// The manifest itself, before any result is read: each line's id recomputed from the line (a
// method, preset or setting edited with the id kept is caught), no job listed twice, and every
// cell's references present, for its own scene.
void verifyManifest(const std::vector<BenchJob>& jobs, std::vector<std::string>& problems) {
    std::map<std::string, PreparedScene> prepared;
    // Two scenes with the same bytes share their references' ids: a reference is looked up by id
    // and scene name together.
    std::set<std::pair<std::string, std::string>> references;  // id, scene name
    std::set<std::string> referenceIds, seen;
    for (const BenchJob& job : jobs)
        if (job.kind == JobKind::Reference) {
            references.emplace(job.id, job.sceneName);
            referenceIds.insert(job.id);
        }
    for (const BenchJob& job : jobs) {
        const std::string what = job.id + " (" + describe(job) + ")";
        if (!seen.insert(describe(job)).second || !seen.insert("id " + job.id + " " + job.sceneName).second) {
            problems.push_back(what + ": listed twice in the manifest");
            continue;
        }
        try {
            auto it = prepared.find(sceneKey(job));
            if (it == prepared.end()) it = prepared.emplace(sceneKey(job), prepareBenchScene(job)).first;
            const std::string id = contentId(job, jobSettings(job, it->second.base));
            if (id != job.id)
                problems.push_back(what + ": the manifest line describes job " + id +
                                   ", not its id (edited after --plan?)");
        } catch (const Error& e) {
            problems.push_back(what + ": cannot recompute its id: " + e.what());
        }
        if (job.kind != JobKind::Cell) continue;
        for (const std::string& ref : {job.reference, job.aoReference}) {
            if (ref.empty()) continue;
            if (!referenceIds.count(ref))
                problems.push_back(what + ": its reference " + ref + " is not in the manifest");
            else if (!references.count({ref, job.sceneName}))
                problems.push_back(what + ": its reference " + ref + " is not listed for scene " + job.sceneName);
        }
    }
}

double chartError(const ImageMetrics& e, ErrorMetric metric) {
    return metric == ErrorMetric::Flip     ? e.flip
           : metric == ErrorMetric::Rmse   ? e.rmse
           : metric == ErrorMetric::RelMse ? e.relMse
                                           : 1.0 - e.ssim;
}

std::string cellLabel(const BenchRow& row) {
    return row.method + "/" + row.preset + (row.emitters.empty() ? "" : " emitters=" + row.emitters);
}

// The cell whose time-to-quality curve stands for its method (and emitter mode) on the scene:
// the medium preset where it was run, else the first one.
const MergedCell* curveCell(const std::vector<MergedCell>& cells, const MergedCell& of) {
    const MergedCell* first = nullptr;
    for (const MergedCell& c : cells) {
        if (c.job->sceneName != of.job->sceneName || c.row.method != of.row.method || c.row.emitters != of.row.emitters)
            continue;
        if (c.row.preset == "medium") return &c;
        if (!first) first = &c;
    }
    return first;
}

// One scene's grid (reference first, then every cell labelled with its costs and error), its
// trade-off chart (error against a frame's cost, and against the GPU time from a camera cut until
// the image stopped changing) and its time-to-quality chart (each method's error after 1, 2, 4, ... frames from a cut,
// at its medium preset).
void addSceneImages(OutputSet& out, const std::string& sceneName, const BenchJob& referenceJob,
                    const std::vector<MergedCell>& cells, const SweepDirs& dirs, const std::string& metricName,
                    const std::string& glRenderer) {
    const ErrorMetric metric = parseErrorMetric(metricName);
    std::vector<std::pair<std::string, ImageU8>> tiles;
    tiles.emplace_back("reference  path traced, " + std::to_string(referenceJob.referenceSpp) + " spp",
                       toLdrImage(readExr(imagePath(dirs, referenceJob)), DisplaySettings{}));
    std::vector<ChartPoint> perFrame, toSettled;
    std::vector<ChartCurve> curves;
    std::vector<std::string> methods;  // chart colour: the method's place in the selection
    for (const MergedCell& c : cells) {
        if (c.job->sceneName != sceneName) continue;
        if (std::find(methods.begin(), methods.end(), c.row.method) == methods.end()) methods.push_back(c.row.method);
        const int methodIndex = int(std::find(methods.begin(), methods.end(), c.row.method) - methods.begin());
        const double y = chartError(c.row.error, metric);
        const std::string label = cellLabel(c.row);
        perFrame.push_back({label, frameCostMs(c.row), y, methodIndex});
        toSettled.push_back({label, c.row.cut.settledGpuMs, y, methodIndex});
        if (&c == curveCell(cells, c)) {
            ChartCurve curve{label, {}, methodIndex};
            for (const BenchRow::QualityPoint& q : c.row.quality) curve.points.emplace_back(q.gpuMs, chartError(q.error, metric));
            curves.push_back(curve);
        }
        char caption[200];
        std::snprintf(caption, sizeof caption, "%s  %.1f ms/frame, %.0f ms to settle, %s %.4f", label.c_str(),
                      frameCostMs(c.row), c.row.cut.settledGpuMs, metricName.c_str(), y);
        tiles.emplace_back(caption, readPng(imagePath(dirs, *c.job)));
    }
    const std::string stem = dirs.outDir + "/" + fileSafeName(sceneName);
    out.emplace_back(stem + "_grid.png", encodePng(composeGrid(tiles, std::min<int>(4, int(tiles.size())))));
    const std::string yLabel = metricName == "ssim" ? "1 - SSIM vs reference" : metricName + " vs reference";
    const std::string gpu = rendererName(glRenderer);
    const std::string title = sceneName + ", " + referenceJob.size + ": ";
    const ImageU8 framePanel = drawTradeoffChart(
        perFrame, title + "error vs a frame's cost",
        "GPU ms per frame on " + gpu + " (converging or steady, the dearer)", yLabel);
    const ImageU8 settledPanel = drawTradeoffChart(
        toSettled, title + "error vs time to converge",
        "GPU ms on " + gpu + " from a camera cut until the image stops changing", yLabel);
    out.emplace_back(stem + "_chart.png", encodePng(stackImages({framePanel, settledPanel})));
    out.emplace_back(stem + "_quality.png",
                     encodePng(drawCurvesChart(curves, title + "time to quality after a cut (medium presets)",
                                               "GPU ms on " + gpu + " since the cut (points: 1, 2, 4, ... frames)",
                                               yLabel)));
}

// A fly-through scene's grid: every cell's last frame, labelled with its median and worst frame.
// No reference and no chart: a fly-through is scored against nothing.
void addFlythroughGrid(OutputSet& out, const std::string& sceneName, const std::vector<MergedCell>& cells,
                       const SweepDirs& dirs) {
    std::vector<std::pair<std::string, ImageU8>> tiles;
    for (const MergedCell& c : cells) {
        if (c.job->sceneName != sceneName || !c.row.flythrough) continue;
        char caption[200];
        std::snprintf(caption, sizeof caption, "%s/%s  median %.1f ms, worst %.1f", c.row.method.c_str(),
                      c.row.preset.c_str(), c.row.flythrough->medianMs, c.row.flythrough->worstMs);
        tiles.emplace_back(caption, readPng(imagePath(dirs, *c.job)));
    }
    out.emplace_back(dirs.outDir + "/" + fileSafeName(sceneName) + "_grid.png",
                     encodePng(composeGrid(tiles, std::min<int>(4, int(tiles.size())))));
}

void addTables(OutputSet& out, const std::vector<MergedCell>& cells, const ojson& machine, const SweepDirs& dirs) {
    const BenchJob& first = *cells.front().job;
    ojson j;
    j["machine"] = machine;
    j["size"] = first.size;
    j["frames"] = first.frames;
    j["warmup"] = first.warmup;
    j["reference_spp"] = first.referenceSpp;
    j["results"] = ojson::array();
    for (const MergedCell& c : cells) j["results"].push_back(rowToJson(c.row));
    const std::string json = dirs.outDir + "/bench.json", csv = dirs.outDir + "/bench.csv";
    out.emplace_back(json, j.dump(2) + "\n");
    std::ostringstream table;
    writeCsvHeader(table);
    for (const MergedCell& c : cells) writeCsvRow(table, c.row);
    out.emplace_back(csv, table.str());
}

}  // namespace

std::string fileSafeName(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return s;
}

int mergeBench(const std::vector<BenchJob>& jobs, const SweepDirs& dirs, const std::string& metric) {
    parseErrorMetric(metric);
    std::vector<std::string> problems;
    verifyManifest(jobs, problems);
    ojson machine;
    const std::vector<MergedCell> cells = gatherCells(jobs, dirs, machine, problems);
    std::map<std::string, const BenchJob*> references;  // scene name -> its path-traced reference
    for (const BenchJob& job : jobs) {
        if (job.kind != JobKind::Reference || giMethod(job.method).role != MethodRole::Reference) continue;
        const RecordCheck check = readRecord(recordPath(dirs, job), job.id);
        if (!check.ok) problems.push_back(job.id + " (" + job.sceneName + " reference): " + check.problem);
        references[job.sceneName] = &job;
    }
    size_t cellCount = 0;
    for (const BenchJob& job : jobs) cellCount += job.kind == JobKind::Cell;
    if (cellCount == 0) problems.push_back("the manifest has no cells");
    if (!problems.empty()) {
        for (const std::string& p : problems) std::fprintf(stderr, "gisandbox: bench --merge: %s\n", p.c_str());
        throw Error(std::to_string(problems.size()) + " of " + std::to_string(jobs.size()) +
                    " jobs missing, failed or damaged (listed above): nothing written; run them, then merge again");
    }
    const std::string glRenderer = machine.value("gl_renderer", std::string("unknown"));
    std::vector<std::string> scenes;
    for (const MergedCell& c : cells)
        if (std::find(scenes.begin(), scenes.end(), c.job->sceneName) == scenes.end()) scenes.push_back(c.job->sceneName);
    // Every output staged (written and synced under temporary names) before any replaces the
    // previous merge's: a failure half way (a full disk) leaves the old set whole.
    OutputSet out;
    for (const std::string& scene : scenes) {
        const bool flown = std::any_of(cells.begin(), cells.end(),
                                       [&](const MergedCell& c) { return c.job->sceneName == scene && c.job->flythrough; });
        if (flown) {
            addFlythroughGrid(out, scene, cells, dirs);
            continue;
        }
        const auto reference = references.find(scene);
        if (reference == references.end())
            throw Error("scene " + scene + " has cells but no path-traced reference line in the manifest");
        addSceneImages(out, scene, *reference->second, cells, dirs, metric, glRenderer);
    }
    addTables(out, cells, machine, dirs);
    writeFilesAtomically(out);
    std::printf("wrote %s/bench.json, %s/bench.csv and a grid%s per scene (%zu cells)\n", dirs.outDir.c_str(),
                dirs.outDir.c_str(), cells.front().job->flythrough ? "" : ", a chart and a quality chart", cells.size());
    return 0;
}

}  // namespace gis
