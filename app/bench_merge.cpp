#include "bench_merge.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>

#include "bench_record.h"
#include "bench_row.h"
#include "gi/method.h"
#include "image.h"
#include "metrics.h"
#include "plot.h"
#include "tonemap.h"

namespace gis {

std::string timeAxisLabel(const std::string& glRenderer, const std::vector<std::string>& totals) {
    std::string label = "GPU ms on " + glRenderer.substr(0, glRenderer.find(" (")) + " (per frame";
    if (!totals.empty()) {
        label += "; until converged: ";
        for (size_t i = 0; i < totals.size(); ++i) label += (i ? ", " : "") + totals[i];
    }
    return label + ")";
}

namespace {

using ojson = nlohmann::ordered_json;

struct MergedCell {
    const BenchJob* job = nullptr;
    BenchRow row;
};

// Every cell's verified result; problems (by id) are collected, not thrown, so all are reported.
std::vector<MergedCell> gatherCells(const std::vector<BenchJob>& jobs, const SweepDirs& dirs, ojson& machine,
                                    std::vector<std::string>& problems) {
    std::vector<MergedCell> cells;
    for (const BenchJob& job : jobs) {
        if (job.kind != JobKind::Cell) continue;
        const std::string path = recordPath(dirs, job);
        const RecordCheck check = readRecord(path, job.id);
        const std::string what = job.sceneName + " " + job.method + "/" + job.preset;
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
        // The manifest names the row: results are shared by content, names belong to the sweep.
        cell.row.scene = job.sceneName;
        cell.row.method = job.method;
        cell.row.preset = job.preset;
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

double chartError(const BenchRow& row, ErrorMetric metric) {
    return metric == ErrorMetric::Flip     ? row.error.flip
           : metric == ErrorMetric::Rmse   ? row.error.rmse
           : metric == ErrorMetric::RelMse ? row.error.relMse
                                           : 1.0 - row.error.ssim;
}

// One scene's grid (reference first, then every cell labelled with ms and error) and chart.
void writeSceneImages(const std::string& sceneName, const BenchJob& referenceJob, const std::vector<MergedCell>& cells,
                      const SweepDirs& dirs, const std::string& metricName, const std::string& glRenderer) {
    const ErrorMetric metric = parseErrorMetric(metricName);
    std::vector<std::pair<std::string, ImageU8>> tiles;
    tiles.emplace_back("reference  path traced, " + std::to_string(referenceJob.referenceSpp) + " spp",
                       toLdrImage(readExr(imagePath(dirs, referenceJob)), DisplaySettings{}));
    std::vector<ChartPoint> points;
    std::vector<std::string> methods;  // chart colour: the method's place in the selection
    for (const MergedCell& c : cells) {
        if (c.job->sceneName != sceneName) continue;
        if (std::find(methods.begin(), methods.end(), c.row.method) == methods.end()) methods.push_back(c.row.method);
        const int methodIndex = int(std::find(methods.begin(), methods.end(), c.row.method) - methods.begin());
        const double y = chartError(c.row, metric);
        const std::string label = c.row.method + "/" + c.row.preset;
        points.push_back({label, c.row.ms, y, methodIndex});
        char caption[200];
        std::snprintf(caption, sizeof caption, "%s  %.1f ms, %s %.4f", label.c_str(), c.row.ms, metricName.c_str(), y);
        tiles.emplace_back(caption, readPng(imagePath(dirs, *c.job)));
    }
    const std::string stem = dirs.outDir + "/" + fileSafeName(sceneName);
    writePng(stem + "_grid.png", composeGrid(tiles, std::min<int>(4, int(tiles.size()))));
    const std::string yLabel = metricName == "ssim" ? "1 - SSIM vs reference" : metricName + " vs reference";
    std::vector<std::string> totals;
    for (const MergedCell& c : cells)
        if (c.job->sceneName == sceneName && c.row.msToConverge &&
            std::find(totals.begin(), totals.end(), c.row.method) == totals.end())
            totals.push_back(c.row.method);
    writePng(stem + "_chart.png", drawTradeoffChart(points, sceneName + ": error vs GPU time, " + referenceJob.size,
                                                    timeAxisLabel(glRenderer, totals), yLabel));
}

void writeTables(const std::vector<MergedCell>& cells, const ojson& machine, const SweepDirs& dirs) {
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
    writeAtomically(json, [&](const std::string& tmp) {
        std::ofstream f(tmp);
        f << j.dump(2) << "\n";
        if (!f) throw Error(json + ": cannot write");
    });
    writeAtomically(csv, [&](const std::string& tmp) {
        std::ofstream f(tmp);
        writeCsvHeader(f);
        for (const MergedCell& c : cells) writeCsvRow(f, c.row);
        if (!f) throw Error(csv + ": cannot write");
    });
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
    for (const std::string& scene : scenes)
        writeSceneImages(scene, *references.at(scene), cells, dirs, metric, glRenderer);
    writeTables(cells, machine, dirs);
    std::printf("wrote %s/bench.json, %s/bench.csv and a grid and chart per scene (%zu cells)\n", dirs.outDir.c_str(),
                dirs.outDir.c_str(), cells.size());
    return 0;
}

}  // namespace gis
