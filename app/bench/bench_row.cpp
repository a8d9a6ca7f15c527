#include "bench/bench_row.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace gis {

namespace {

using CsvWriter = std::function<void(std::ostream&, const BenchRow&)>;

struct CsvColumn {
    const char* name;
    bool timing;
    CsvWriter write;
};

// An error column: empty for a fly-through, which is scored against nothing.
CsvWriter scored(CsvWriter write) {
    return [write](std::ostream& f, const BenchRow& r) {
        if (!r.flythrough) write(f, r);
    };
}

// A fly-through column: empty for a still camera.
CsvWriter flown(std::function<void(std::ostream&, const FlythroughStats&)> write) {
    return [write](std::ostream& f, const BenchRow& r) {
        if (r.flythrough) write(f, *r.flythrough);
    };
}

void optionalMs(std::ostream& f, double ms) {  // -1: no such frame
    if (ms >= 0.0) f << ms;
}

// A column of the convergence after a cut: empty for a fly-through.
CsvWriter cut(std::function<void(std::ostream&, const BenchRow::Convergence&)> write) {
    return [write](std::ostream& f, const BenchRow& r) {
        if (!r.flythrough && r.cut.frames > 0) write(f, r.cut);
    };
}

// A column of the convergence after a light edit: empty where no light was edited.
CsvWriter edited(std::function<void(std::ostream&, const BenchRow::Convergence&)> write) {
    return [write](std::ostream& f, const BenchRow& r) {
        if (r.edit) write(f, *r.edit);
    };
}

// A column of the first frame's error after the cut.
CsvWriter first(std::function<void(std::ostream&, const ImageMetrics&)> write) {
    return [write](std::ostream& f, const BenchRow& r) {
        if (!r.quality.empty()) write(f, r.quality.front().error);
    };
}

// bench.csv, left to right. Numbers print with the stream's default precision (as they always
// have); PSNR through formatMetric so +inf (identical images) reads "inf".
const std::vector<CsvColumn>& csvColumns() {
    static const std::vector<CsvColumn> columns{
        {"scene", false, [](std::ostream& f, const BenchRow& r) { f << r.scene; }},
        {"method", false, [](std::ostream& f, const BenchRow& r) { f << r.method; }},
        {"preset", false, [](std::ostream& f, const BenchRow& r) { f << r.preset; }},
        {"emitters", false, [](std::ostream& f, const BenchRow& r) { f << r.emitters; }},
        {"gpu_ms", true, [](std::ostream& f, const BenchRow& r) { f << r.ms; }},
        {"wall_ms", true, [](std::ostream& f, const BenchRow& r) { f << r.wallMs; }},
        {"converge_frames", false, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.frames; })},
        {"converge_gpu_ms", true, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.gpuMs; })},
        {"converge_wall_ms", true, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.wallMs; })},
        {"converge_frame_gpu_ms", true, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.frameMs; })},
        {"converge_settled_frames", false, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.settledFrames; })},
        {"converge_settled_gpu_ms", true, cut([](std::ostream& f, const BenchRow::Convergence& c) { f << c.settledGpuMs; })},
        {"edit_frames", false, edited([](std::ostream& f, const BenchRow::Convergence& c) { f << c.frames; })},
        {"edit_gpu_ms", true, edited([](std::ostream& f, const BenchRow::Convergence& c) { f << c.gpuMs; })},
        {"edit_settled_frames", false, edited([](std::ostream& f, const BenchRow::Convergence& c) { f << c.settledFrames; })},
        {"edit_settled_gpu_ms", true, edited([](std::ostream& f, const BenchRow::Convergence& c) { f << c.settledGpuMs; })},
        {"gpu_bytes", false, [](std::ostream& f, const BenchRow& r) { f << r.bytes; }},
        {"atlas_texels", false, [](std::ostream& f, const BenchRow& r) {
             if (r.atlasTexels >= 0) f << r.atlasTexels;
         }},
        {"rmse", false, scored([](std::ostream& f, const BenchRow& r) { f << r.error.rmse; })},
        {"relmse", false, scored([](std::ostream& f, const BenchRow& r) { f << r.error.relMse; })},
        {"psnr_linear", false, scored([](std::ostream& f, const BenchRow& r) { f << formatMetric(r.error.psnrLinear); })},
        {"psnr_srgb", false, scored([](std::ostream& f, const BenchRow& r) { f << formatMetric(r.error.psnrSrgb); })},
        {"ssim", false, scored([](std::ostream& f, const BenchRow& r) { f << r.error.ssim; })},
        {"flip", false, scored([](std::ostream& f, const BenchRow& r) { f << r.error.flip; })},
        {"first_rmse", false, first([](std::ostream& f, const ImageMetrics& m) { f << m.rmse; })},
        {"first_flip", false, first([](std::ostream& f, const ImageMetrics& m) { f << m.flip; })},
        {"mean_ratio", false, scored([](std::ostream& f, const BenchRow& r) {
             if (r.error.meanReference > 0.0) f << r.error.meanTest / r.error.meanReference;
         })},
        {"leak", false, [](std::ostream& f, const BenchRow& r) {
             if (r.leak >= 0.0) f << r.leak;
         }},
        {"ao_rmse", false,
         [](std::ostream& f, const BenchRow& r) { f << (r.aoRmse >= 0.0 ? std::to_string(r.aoRmse) : std::string()); }},
        {"mrays_per_s", true,
         [](std::ostream& f, const BenchRow& r) {
             if (r.megaRaysPerSecond >= 0.0) f << r.megaRaysPerSecond;
         }},
        {"fly_frames", false, flown([](std::ostream& f, const FlythroughStats& s) { f << s.frames; })},
        {"fly_worst_ms", true, flown([](std::ostream& f, const FlythroughStats& s) { f << s.worstMs; })},
        {"fly_move_frames", false, flown([](std::ostream& f, const FlythroughStats& s) { f << s.moveFrames; })},
        {"fly_move_ms", true, flown([](std::ostream& f, const FlythroughStats& s) { optionalMs(f, s.moveMedianMs); })},
        {"fly_still_ms", true, flown([](std::ostream& f, const FlythroughStats& s) { optionalMs(f, s.stillMedianMs); })},
    };
    return columns;
}

// JSON has no infinity (nlohmann writes null): PSNR of identical images comes back as +inf.
double psnrFromJson(const nlohmann::ordered_json& v) {
    return v.is_null() ? std::numeric_limits<double>::infinity() : v.get<double>();
}

nlohmann::ordered_json errorToJson(const ImageMetrics& m) {
    return {{"rmse", m.rmse}, {"relmse", m.relMse}, {"psnr_linear", m.psnrLinear},
            {"psnr_srgb", m.psnrSrgb}, {"ssim", m.ssim}, {"flip", m.flip},
            {"mean", m.meanTest}, {"mean_reference", m.meanReference}};
}

ImageMetrics errorFromJson(const nlohmann::ordered_json& j) {
    ImageMetrics m;
    m.rmse = j.at("rmse").get<double>();
    m.relMse = j.at("relmse").get<double>();
    m.psnrLinear = psnrFromJson(j.at("psnr_linear"));
    m.psnrSrgb = psnrFromJson(j.at("psnr_srgb"));
    m.ssim = j.at("ssim").get<double>();
    m.flip = j.at("flip").get<double>();
    m.meanTest = j.value("mean", 0.0);  // absent in results recorded before the means were
    m.meanReference = j.value("mean_reference", 0.0);
    return m;
}

// JSON has no -1 convention: a median over no frame is null.
nlohmann::ordered_json optionalMsJson(double ms) { return ms >= 0.0 ? nlohmann::ordered_json(ms) : nullptr; }
double optionalMsFromJson(const nlohmann::ordered_json& v) { return v.is_null() ? -1.0 : v.get<double>(); }

nlohmann::ordered_json flythroughToJson(const FlythroughStats& s) {
    return {{"frames", s.frames},           {"gpu_ms_median", s.medianMs},
            {"gpu_ms_worst", s.worstMs},    {"wall_ms_median", s.medianWallMs},
            {"move_frames", s.moveFrames},  {"move_gpu_ms_median", optionalMsJson(s.moveMedianMs)},
            {"still_gpu_ms_median", optionalMsJson(s.stillMedianMs)}};
}

FlythroughStats flythroughFromJson(const nlohmann::ordered_json& j) {
    FlythroughStats s;
    s.frames = j.at("frames").get<int>();
    s.medianMs = j.at("gpu_ms_median").get<double>();
    s.worstMs = j.at("gpu_ms_worst").get<double>();
    s.medianWallMs = j.at("wall_ms_median").get<double>();
    s.moveFrames = j.at("move_frames").get<int>();
    s.moveMedianMs = optionalMsFromJson(j.at("move_gpu_ms_median"));
    s.stillMedianMs = optionalMsFromJson(j.at("still_gpu_ms_median"));
    return s;
}

nlohmann::ordered_json convergenceToJson(const BenchRow::Convergence& c) {
    return {{"frames", c.frames},        {"gpu_ms", c.gpuMs},
            {"wall_ms", c.wallMs},       {"frame_gpu_ms", c.frameMs},
            {"settled_frames", c.settledFrames}, {"settled_gpu_ms", c.settledGpuMs}};
}

BenchRow::Convergence convergenceFromJson(const nlohmann::ordered_json& j) {
    return {j.at("frames").get<int>(),        j.at("gpu_ms").get<double>(),
            j.at("wall_ms").get<double>(),     j.at("frame_gpu_ms").get<double>(),
            j.at("settled_frames").get<int>(), j.at("settled_gpu_ms").get<double>()};
}

nlohmann::ordered_json qualityToJson(const std::vector<BenchRow::QualityPoint>& points) {
    nlohmann::ordered_json a = nlohmann::ordered_json::array();
    for (const BenchRow::QualityPoint& p : points) {
        nlohmann::ordered_json e{{"frames", p.frames}, {"gpu_ms", p.gpuMs}};
        const nlohmann::ordered_json error = errorToJson(p.error);  // items() of a temporary would dangle
        for (const auto& [key, value] : error.items()) e[key] = value;
        a.push_back(e);
    }
    return a;
}

std::vector<BenchRow::QualityPoint> qualityFromJson(const nlohmann::ordered_json& a) {
    std::vector<BenchRow::QualityPoint> points;
    for (const auto& e : a) points.push_back({e.at("frames").get<int>(), e.at("gpu_ms").get<double>(), errorFromJson(e)});
    return points;
}

}  // namespace

double frameCostMs(const BenchRow& row) { return std::max(row.ms, row.cut.frameMs); }

nlohmann::ordered_json rowToJson(const BenchRow& r) {
    nlohmann::ordered_json e{{"scene", r.scene}, {"method", r.method}, {"preset", r.preset},
                             {"description", r.description}, {"gpu_ms", r.ms}, {"wall_ms", r.wallMs}, {"gpu_bytes", r.bytes}};
    if (!r.emitters.empty()) e["emitters"] = r.emitters;
    if (r.flythrough) {
        e["flythrough"] = flythroughToJson(*r.flythrough);
    } else {
        const nlohmann::ordered_json error = errorToJson(r.error);
        for (const auto& [key, value] : error.items()) e[key] = value;
    }
    for (const auto& [pass, ms] : r.passMs) e["pass_ms"][pass] = ms;
    for (const BenchRow::StepTime& t : r.steps) e["step_ms"][t.step] = {{"frame", t.ms}, {"first", t.firstMs}};
    if (r.aoRmse >= 0.0) e["ao_rmse_vs_raytraced"] = r.aoRmse;
    if (r.leak >= 0.0) e["leak"] = r.leak;
    if (r.megaRaysPerSecond >= 0.0) e["mrays_per_s"] = r.megaRaysPerSecond;
    if (r.atlasTexels >= 0) e["atlas_texels"] = r.atlasTexels;
    if (r.cut.frames > 0) e["converge"] = convergenceToJson(r.cut);
    if (r.edit) e["light_edit"] = convergenceToJson(*r.edit);
    if (!r.quality.empty()) e["quality"] = qualityToJson(r.quality);
    return e;
}

BenchRow rowFromJson(const nlohmann::ordered_json& j) {
    BenchRow r;
    r.scene = j.at("scene").get<std::string>();
    r.method = j.at("method").get<std::string>();
    r.preset = j.at("preset").get<std::string>();
    r.description = j.at("description").get<std::string>();
    r.emitters = j.value("emitters", std::string());  // absent: the default mode
    r.ms = j.at("gpu_ms").get<double>();
    r.wallMs = j.at("wall_ms").get<double>();
    r.bytes = j.at("gpu_bytes").get<int64_t>();
    if (j.contains("flythrough"))
        r.flythrough = flythroughFromJson(j.at("flythrough"));
    else
        r.error = errorFromJson(j);
    // Absent in fly-throughs and in results recorded before they were measured.
    if (j.contains("converge")) r.cut = convergenceFromJson(j.at("converge"));
    if (j.contains("light_edit")) r.edit = convergenceFromJson(j.at("light_edit"));
    if (j.contains("quality")) r.quality = qualityFromJson(j.at("quality"));
    if (j.contains("pass_ms"))
        for (const auto& [pass, ms] : j.at("pass_ms").items()) r.passMs.emplace_back(pass, ms.get<double>());
    if (j.contains("step_ms"))
        for (const auto& [step, t] : j.at("step_ms").items())
            r.steps.push_back({step, t.at("frame").get<double>(), t.at("first").get<double>()});
    if (j.contains("ao_rmse_vs_raytraced")) r.aoRmse = j.at("ao_rmse_vs_raytraced").get<double>();
    if (j.contains("leak")) r.leak = j.at("leak").get<double>();
    if (j.contains("mrays_per_s")) r.megaRaysPerSecond = j.at("mrays_per_s").get<double>();
    if (j.contains("atlas_texels")) r.atlasTexels = j.at("atlas_texels").get<int64_t>();
    return r;
}

void writeCsvHeader(std::ostream& out) {
    const char* sep = "";
    for (const CsvColumn& c : csvColumns()) {
        out << sep << c.name;
        sep = ",";
    }
    out << "\n";
}

void writeCsvRow(std::ostream& out, const BenchRow& row) {
    const char* sep = "";
    for (const CsvColumn& c : csvColumns()) {
        out << sep;
        c.write(out, row);
        sep = ",";
    }
    out << "\n";
}

bool isTimingColumn(const std::string& name) {
    for (const CsvColumn& c : csvColumns())
        if (name == c.name) return c.timing;
    return false;
}

}  // namespace gis
