// One row of `gisandbox bench`: a method at a preset on a scene. bench.json holds rowToJson of
// each, bench.csv one line per row through the column table in bench_row.cpp; a cell's result file
// carries the same JSON, so a new figure is one field here and one column there.
#pragma once

#include <cstdint>
#include <ostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/flythrough.h"
#include "metrics.h"

namespace gis {

struct BenchRow {
    std::string scene, method, preset, description;
    std::string emitters;                     // --emitters the cell ran with; "" = the default
    // A static view's steady cost per frame once the image is final, every pass executed as an
    // engine re-renders it (render --rerun-settled): medians after warm-up.
    double ms = 0.0;
    double wallMs = 0.0;                      // wall clock with glFinish, the same way
    // From a camera cut (a renderer with nothing accumulated) or a light edit until the image is
    // final: frames, their GPU and wall ms together, and the median GPU ms of those after the first
    // (a frame while the method still works; after a cut final in one frame, the steady frame);
    // and, measured on the images, the frame from which the image stopped changing and the GPU ms
    // until then.
    struct Convergence {
        int frames = 0;
        double gpuMs = 0.0, wallMs = 0.0, frameMs = 0.0;
        int settledFrames = 0;
        double settledGpuMs = 0.0;
    };
    Convergence cut;
    std::optional<Convergence> edit;          // scenes with a punctual light to edit
    // Time to quality after the cut: the error at 1, 2, 4, ... frames and at the last, with the GPU
    // ms spent until then. The first point is the first frame's error.
    struct QualityPoint {
        int frames = 0;
        double gpuMs = 0.0;
        ImageMetrics error;
    };
    std::vector<QualityPoint> quality;
    std::vector<std::pair<std::string, double>> passMs;  // steady, as ms
    // A pass's steps ("sdf/c0.jfa.1.16"), within passMs: per measured frame (0 when cached then) and
    // in the first frame, which builds what later frames reuse.
    struct StepTime {
        std::string step;
        double ms = 0.0, firstMs = 0.0;
    };
    std::vector<StepTime> steps;
    int64_t bytes = 0;
    ImageMetrics error;                       // not measured for a fly-through (no reference for its views)
    double aoRmse = -1.0;                     // SSAO only: its AO term against ray-traced AO
    double leak = -1.0;                       // scenes with leak cameras (Scene::leakCameras); -1: none
    double megaRaysPerSecond = -1.0;          // passes that count their rays (the path tracer); -1: none
    int64_t atlasTexels = -1;                 // a method that bakes into an atlas (Pass::atlasTexels); -1: none
    // A fly-through (bench --flythrough): ms and wallMs are its medians, passMs and steps too.
    std::optional<FlythroughStats> flythrough;
};

// What a frame costs a real-time user: the dearer of a frame while the method converges and a
// static view's steady frame (a converged path tracer re-shows its image for nothing, but every
// frame of a moving camera pays for samples). The trade-off chart's first panel.
double frameCostMs(const BenchRow& row);

nlohmann::ordered_json rowToJson(const BenchRow& row);
// Throws gis::Error (via nlohmann) when a field is missing or of the wrong type.
BenchRow rowFromJson(const nlohmann::ordered_json& json);  // ordered: pass_ms keeps pass order

void writeCsvHeader(std::ostream& out);
void writeCsvRow(std::ostream& out, const BenchRow& row);

// The CSV columns that measure time (they differ between runs of the same cell).
bool isTimingColumn(const std::string& name);

}  // namespace gis
