#include "bench_row.h"

#include <cmath>
#include <functional>
#include <limits>

namespace gis {

namespace {

struct CsvColumn {
    const char* name;
    bool timing;
    std::function<void(std::ostream&, const BenchRow&)> write;
};

// bench.csv, left to right. Numbers print with the stream's default precision (as they always
// have); PSNR through formatMetric so +inf (identical images) reads "inf".
const std::vector<CsvColumn>& csvColumns() {
    static const std::vector<CsvColumn> columns{
        {"scene", false, [](std::ostream& f, const BenchRow& r) { f << r.scene; }},
        {"method", false, [](std::ostream& f, const BenchRow& r) { f << r.method; }},
        {"preset", false, [](std::ostream& f, const BenchRow& r) { f << r.preset; }},
        {"gpu_ms", true, [](std::ostream& f, const BenchRow& r) { f << r.ms; }},
        {"wall_ms", true, [](std::ostream& f, const BenchRow& r) { f << r.wallMs; }},
        {"gpu_bytes", false, [](std::ostream& f, const BenchRow& r) { f << r.bytes; }},
        {"rmse", false, [](std::ostream& f, const BenchRow& r) { f << r.error.rmse; }},
        {"relmse", false, [](std::ostream& f, const BenchRow& r) { f << r.error.relMse; }},
        {"psnr_linear", false, [](std::ostream& f, const BenchRow& r) { f << formatMetric(r.error.psnrLinear); }},
        {"psnr_srgb", false, [](std::ostream& f, const BenchRow& r) { f << formatMetric(r.error.psnrSrgb); }},
        {"ssim", false, [](std::ostream& f, const BenchRow& r) { f << r.error.ssim; }},
        {"flip", false, [](std::ostream& f, const BenchRow& r) { f << r.error.flip; }},
        {"ao_rmse", false,
         [](std::ostream& f, const BenchRow& r) { f << (r.aoRmse >= 0.0 ? std::to_string(r.aoRmse) : std::string()); }},
        {"mrays_per_s", true,
         [](std::ostream& f, const BenchRow& r) {
             if (r.megaRaysPerSecond >= 0.0) f << r.megaRaysPerSecond;
         }},
    };
    return columns;
}

// JSON has no infinity (nlohmann writes null): PSNR of identical images comes back as +inf.
double psnrFromJson(const nlohmann::ordered_json& v) {
    return v.is_null() ? std::numeric_limits<double>::infinity() : v.get<double>();
}

}  // namespace

nlohmann::ordered_json rowToJson(const BenchRow& r) {
    nlohmann::ordered_json e{{"scene", r.scene}, {"method", r.method}, {"preset", r.preset},
                             {"description", r.description}, {"gpu_ms", r.ms}, {"wall_ms", r.wallMs}, {"gpu_bytes", r.bytes},
                             {"rmse", r.error.rmse}, {"relmse", r.error.relMse}, {"psnr_linear", r.error.psnrLinear},
                             {"psnr_srgb", r.error.psnrSrgb}, {"ssim", r.error.ssim}, {"flip", r.error.flip}};
    for (const auto& [pass, ms] : r.passMs) e["pass_ms"][pass] = ms;
    for (const BenchRow::StepTime& t : r.steps) e["step_ms"][t.step] = {{"frame", t.ms}, {"first", t.firstMs}};
    if (r.aoRmse >= 0.0) e["ao_rmse_vs_raytraced"] = r.aoRmse;
    if (r.megaRaysPerSecond >= 0.0) e["mrays_per_s"] = r.megaRaysPerSecond;
    if (r.msToConverge) e["gpu_ms_to_converge"] = true;
    return e;
}

BenchRow rowFromJson(const nlohmann::ordered_json& j) {
    BenchRow r;
    r.scene = j.at("scene").get<std::string>();
    r.method = j.at("method").get<std::string>();
    r.preset = j.at("preset").get<std::string>();
    r.description = j.at("description").get<std::string>();
    r.ms = j.at("gpu_ms").get<double>();
    r.wallMs = j.at("wall_ms").get<double>();
    r.bytes = j.at("gpu_bytes").get<int64_t>();
    r.error.rmse = j.at("rmse").get<double>();
    r.error.relMse = j.at("relmse").get<double>();
    r.error.psnrLinear = psnrFromJson(j.at("psnr_linear"));
    r.error.psnrSrgb = psnrFromJson(j.at("psnr_srgb"));
    r.error.ssim = j.at("ssim").get<double>();
    r.error.flip = j.at("flip").get<double>();
    r.msToConverge = j.value("gpu_ms_to_converge", false);  // absent in rows of per-frame methods
    if (j.contains("pass_ms"))
        for (const auto& [pass, ms] : j.at("pass_ms").items()) r.passMs.emplace_back(pass, ms.get<double>());
    if (j.contains("step_ms"))
        for (const auto& [step, t] : j.at("step_ms").items())
            r.steps.push_back({step, t.at("frame").get<double>(), t.at("first").get<double>()});
    if (j.contains("ao_rmse_vs_raytraced")) r.aoRmse = j.at("ao_rmse_vs_raytraced").get<double>();
    if (j.contains("mrays_per_s")) r.megaRaysPerSecond = j.at("mrays_per_s").get<double>();
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
