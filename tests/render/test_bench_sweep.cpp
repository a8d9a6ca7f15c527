// A bench sweep spread over processes: --plan, --cell under GNU parallel, --merge, against the
// in-process `bench` of the same selection; idempotent cells; damaged results caught by id; content
// ids that follow the scene's bytes and the settings, and nothing else.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "bench/bench_row.h"
#include "cli_util.h"

namespace gis::test {
namespace {

namespace fs = std::filesystem;

const std::string kFlags = "--size 24x24 --frames 3 --warmup 1 --reference-spp 8 ";
const std::string kSelection = "--scenes builtin:cornell " + kFlags;

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void spit(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

std::string bin() { return std::string("'") + GIS_BINARY + "'"; }

// Runs `command` under sh; returns its exit status (stdout and stderr go to the test's log).
int shell(const std::string& command) {
    const int raw = std::system(command.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) out.push_back(line);
    return out;
}

// Writes the plan of `selection` to DIR/sweep.jsonl; returns its lines parsed.
std::vector<nlohmann::json> plan(const std::string& dir, const std::string& selection) {
    const CliResult r = runCli("bench --plan " + selection);
    EXPECT_EQ(r.status, 0) << r.err;
    spit(dir + "/sweep.jsonl", r.out);
    std::vector<nlohmann::json> jobs;
    for (const std::string& line : lines(r.out)) jobs.push_back(nlohmann::json::parse(line));
    return jobs;
}

std::vector<std::string> idsOf(const std::vector<nlohmann::json>& jobs, const std::string& kind) {
    std::vector<std::string> ids;
    for (const auto& j : jobs)
        if (j["kind"] == kind) ids.push_back(j["id"]);
    return ids;
}

// CSV rows without the timing columns (they differ between any two runs).
std::vector<std::string> csvWithoutTimings(const std::string& path) {
    std::vector<std::string> rows;
    std::vector<bool> keep;
    for (const std::string& line : lines(slurp(path))) {
        std::vector<std::string> fields;
        std::stringstream s(line);
        for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
        if (line.back() == ',') fields.push_back("");
        if (keep.empty())
            for (const std::string& name : fields) keep.push_back(!isTimingColumn(name));
        std::string row;
        for (size_t i = 0; i < fields.size() && i < keep.size(); ++i)
            if (keep[i]) row += fields[i] + ",";
        rows.push_back(row);
    }
    return rows;
}

// Plans `selection` into DIR and runs every job with `parallel -j2`: references, then cells.
std::vector<nlohmann::json> runSweepInParallel(const std::string& dir, const std::string& selection) {
    const std::vector<nlohmann::json> jobs = plan(dir, selection);
    for (const char* kind : {"references", "cells"}) {
        const std::string cmd = bin() + " bench --ids " + kind + " --manifest '" + dir + "/sweep.jsonl' | parallel --will-cite -j2 " +
                                bin() + " bench --manifest '" + dir + "/sweep.jsonl' --out-dir '" + dir + "' --cell {} 2>>'" +
                                dir + "/parallel.log'";
        EXPECT_EQ(shell(cmd), 0) << kind << ": " << slurp(dir + "/parallel.log");
    }
    return jobs;
}

TEST(BenchSweep, ParallelCellsMergeToTheInProcessRows) {
    const std::string selection = kSelection + "--methods none,ssao --presets low,high";
    const std::string dir = tempDir("sweep_parallel"), inProcess = tempDir("sweep_inprocess");
    const std::vector<nlohmann::json> jobs = runSweepInParallel(dir, selection);
    EXPECT_EQ(idsOf(jobs, "reference").size(), 2u);  // path traced, and AO for SSAO
    EXPECT_EQ(idsOf(jobs, "cell").size(), 4u);
    const CliResult merged = runCli("bench --merge '" + dir + "' --manifest '" + dir + "/sweep.jsonl'");
    ASSERT_EQ(merged.status, 0) << merged.err;

    const CliResult r = runCli("bench " + selection + " --out-dir '" + inProcess + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> distributed = csvWithoutTimings(dir + "/bench.csv");
    EXPECT_EQ(distributed.size(), 5u);  // header + 4 rows
    EXPECT_EQ(distributed, csvWithoutTimings(inProcess + "/bench.csv"));
    const nlohmann::json j = nlohmann::json::parse(slurp(dir + "/bench.json"));
    EXPECT_EQ(j["results"].size(), 4u);
    EXPECT_GT(j["results"][2]["ao_rmse_vs_raytraced"].get<double>(), 0.0) << j["results"][2].dump();
    EXPECT_TRUE(fileExists(dir + "/cornell_chart.png"));
    EXPECT_TRUE(fileExists(dir + "/cornell_grid.png"));
    // The in-process run is the same plan: its manifest is the one --plan prints.
    EXPECT_EQ(slurp(inProcess + "/manifest.jsonl"), slurp(dir + "/sweep.jsonl"));
}

struct stat statOf(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st;
}

TEST(BenchSweep, RerunningACellIsANoOpAndForceRunsItAgain) {
    const std::string dir = tempDir("sweep_rerun");
    const std::vector<nlohmann::json> jobs = plan(dir, kSelection + "--methods none --presets low");
    const std::string ref = idsOf(jobs, "reference").at(0), cell = idsOf(jobs, "cell").at(0);
    const std::string run = "bench --manifest '" + dir + "/sweep.jsonl' --out-dir '" + dir + "' --cell ";
    ASSERT_EQ(runCli(run + ref).status, 0);
    CliResult r = runCli(run + cell);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string result = dir + "/cells/" + cell + ".json";
    const std::string before = slurp(result);
    const struct stat st = statOf(result);

    r = runCli(run + cell);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("done already"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(result), before);
    EXPECT_EQ(statOf(result).st_ino, st.st_ino);
    EXPECT_EQ(statOf(result).st_mtim.tv_nsec, st.st_mtim.tv_nsec);
    r = runCli(run + ref);  // a cached reference is not rendered again either
    EXPECT_NE(r.err.find("reference from cache"), std::string::npos) << r.err;

    r = runCli(run + cell + " --force");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("done already"), std::string::npos) << r.err;
    EXPECT_NE(statOf(result).st_ino, st.st_ino);  // written anew (atomically: a new file renamed over)
}

TEST(BenchSweep, MergeReportsDamagedTruncatedAndMissingResultsById) {
    const std::string dir = tempDir("sweep_damaged");
    const std::vector<nlohmann::json> jobs = runSweepInParallel(dir, kSelection + "--methods none --presets low,medium,high");
    const std::vector<std::string> cells = idsOf(jobs, "cell");
    ASSERT_EQ(cells.size(), 3u);
    const std::string manifest = " --manifest '" + dir + "/sweep.jsonl'";
    ASSERT_EQ(runCli("bench --merge '" + dir + "'" + manifest).status, 0);
    fs::remove(dir + "/bench.csv");

    // One digit changed (still valid JSON), one file cut in half, one cell's image altered.
    const std::string altered = dir + "/cells/" + cells[0] + ".json", cut = dir + "/cells/" + cells[1] + ".json";
    std::string text = slurp(altered);
    const size_t at = text.find("\"flip\":") + 7;
    text[at + 2] = text[at + 2] == '1' ? '2' : '1';
    spit(altered, text);
    text = slurp(cut);
    spit(cut, text.substr(0, text.size() / 2));
    std::ofstream(dir + "/cells/" + cells[2] + ".png", std::ios::app) << "x";

    const CliResult r = runCli("bench --merge '" + dir + "'" + manifest);
    EXPECT_NE(r.status, 0);
    const std::vector<std::string> errors = lines(r.err);
    ASSERT_EQ(errors.size(), 4u) << r.err;  // one line per damaged cell, then the summary
    EXPECT_NE(errors[0].find(cells[0]), std::string::npos) << r.err;
    EXPECT_NE(errors[0].find("checksum mismatch"), std::string::npos) << r.err;
    EXPECT_NE(errors[1].find(cells[1]), std::string::npos) << r.err;
    EXPECT_NE(errors[1].find("truncated"), std::string::npos) << r.err;
    EXPECT_NE(errors[2].find(cells[2]), std::string::npos) << r.err;
    EXPECT_NE(errors[2].find(".png does not match"), std::string::npos) << r.err;
    EXPECT_FALSE(fileExists(dir + "/bench.csv"));  // nothing written from a partial sweep

    // Re-running the damaged cells (not a no-op: their results are not valid) repairs the sweep.
    for (const std::string& id : cells)
        ASSERT_EQ(runCli("bench --out-dir '" + dir + "' --cell " + id + manifest).status, 0) << id;
    EXPECT_EQ(runCli("bench --merge '" + dir + "'" + manifest).status, 0);
}

TEST(BenchSweep, ACellWithoutItsReferenceSaysSoAndMergeReportsIt) {
    const std::string dir = tempDir("sweep_noref");
    const std::vector<nlohmann::json> jobs = plan(dir, kSelection + "--methods none --presets low");
    const std::string ref = idsOf(jobs, "reference").at(0), cell = idsOf(jobs, "cell").at(0);
    const std::string manifest = " --manifest '" + dir + "/sweep.jsonl'";
    CliResult r = runCli("bench --out-dir '" + dir + "' --cell " + cell + manifest);
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("needs reference " + ref), std::string::npos) << r.err;
    EXPECT_FALSE(fileExists(dir + "/cells/" + cell + ".json"));

    r = runCli("bench --merge '" + dir + "'" + manifest);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find(cell + " (cornell none/low): failed: cell " + cell + " needs reference"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(ref + " (cornell reference): missing"), std::string::npos) << r.err;

    r = runCli("bench --out-dir '" + dir + "' --cell 0123456789abcdef" + manifest);
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("no such id"), std::string::npos) << r.err;
}

TEST(BenchSweep, AJobWhoseSceneChangedSinceThePlanIsRefused) {
    const std::string dir = tempDir("sweep_changed");
    ASSERT_EQ(runCli("export --scene builtin:cornell --out '" + dir + "/box.gltf'").status, 0);
    const std::vector<nlohmann::json> jobs = plan(dir, "--scenes '" + dir + "/box.gltf' " + kFlags + "--methods none --presets low");
    std::string bytes = slurp(dir + "/box.bin");
    bytes[bytes.size() / 2] ^= 1;
    spit(dir + "/box.bin", bytes);
    const std::string ref = idsOf(jobs, "reference").at(0);
    const CliResult r = runCli("bench --out-dir '" + dir + "' --cell " + ref + " --manifest '" + dir + "/sweep.jsonl'");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("box.gltf changed since --plan"), std::string::npos) << r.err;
    EXPECT_FALSE(fileExists(dir + "/cache/" + ref + ".exr"));
}

// The Slurm array script picks its job by SLURM_ARRAY_TASK_ID; run here as Slurm would run a task.
TEST(BenchSweep, SlurmScriptRunsTheJobItsTaskIdPicks) {
    const std::string dir = tempDir("sweep_slurm");
    const std::vector<nlohmann::json> jobs = plan(dir, kSelection + "--methods none --presets low,high");
    const std::string script = std::string(GIS_SOURCE_DIR) + "/scripts/bench-sweep.sbatch";
    const std::string env = "GISANDBOX=" + bin() + " ";
    EXPECT_EQ(shell(env + "SLURM_ARRAY_TASK_ID=0 '" + script + "' references '" + dir + "/sweep.jsonl' '" + dir + "'"), 0);
    EXPECT_EQ(shell(env + "SLURM_ARRAY_TASK_ID=1 '" + script + "' cells '" + dir + "/sweep.jsonl' '" + dir + "'"), 0);
    const std::vector<std::string> cells = idsOf(jobs, "cell");
    EXPECT_FALSE(fileExists(dir + "/cells/" + cells[0] + ".json"));
    EXPECT_TRUE(fileExists(dir + "/cells/" + cells[1] + ".json"));
    EXPECT_NE(shell(env + "SLURM_ARRAY_TASK_ID=2 '" + script + "' cells '" + dir + "/sweep.jsonl' '" + dir + "' 2>/dev/null"), 0);
}

TEST(BenchSweep, IdsFollowTheSceneBytesAndTheSettingsOnly) {
    const std::string dir = tempDir("sweep_ids");
    fs::create_directories(dir + "/a");
    ASSERT_EQ(runCli("export --scene builtin:cornell --out '" + dir + "/a/box.gltf'").status, 0);
    fs::create_directories(dir + "/b");
    fs::copy(dir + "/a", dir + "/b", fs::copy_options::recursive);
    fs::rename(dir + "/b/box.gltf", dir + "/b/renamed.gltf");  // its .bin keeps the name the .gltf gives it
    // The ids of a one-method plan of `scene`: --frames, --reference-spp, --size and --presets as
    // given (else 3, 8, 24x24, low), plus `extra` flags.
    struct Flags {
        Flags(std::string s) : scene(std::move(s)) {}  // NOLINT: a scene alone is a plan's flags
        std::string scene, frames = "3", spp = "8", size = "24x24", presets = "low", extra;
    };
    auto ids = [&](const Flags& f) {
        std::vector<std::string> out;
        const std::string flags = "--scenes '" + f.scene + "' --frames " + f.frames + " --warmup 1 --reference-spp " + f.spp +
                                  " --size " + f.size + " --presets " + f.presets + " --methods none " + f.extra;
        for (const auto& j : plan(dir, flags)) out.push_back(j["id"]);
        return out;
    };
    auto common = [](const std::vector<std::string>& a, const std::vector<std::string>& b) {
        size_t n = 0;
        for (const std::string& id : a) n += std::count(b.begin(), b.end(), id);
        return n;
    };
    const std::string a = dir + "/a/box.gltf", b = dir + "/b/renamed.gltf";
    auto with = [&](std::string Flags::*field, const std::string& value) {  // scene a, one flag changed
        Flags f{a};
        f.*field = value;
        return f;
    };
    const std::vector<std::string> base = ids({a});
    ASSERT_EQ(base.size(), 2u);  // reference, cell
    EXPECT_EQ(ids({a}), base);                                    // stable
    EXPECT_EQ(ids({b}), base);                                    // path and name are not content
    EXPECT_EQ(ids(with(&Flags::extra, "--metric rmse")), base);          // the chart's axis is not a cell's

    std::string bytes = slurp(dir + "/b/box.bin");  // one byte of the geometry buffer
    bytes[bytes.size() / 2] ^= 1;
    spit(dir + "/b/box.bin", bytes);
    EXPECT_EQ(common(ids({b}), base), 0u);

    std::vector<std::string> changed = ids(with(&Flags::frames, "4"));  // a cell setting: the cell only
    EXPECT_EQ(changed[0], base[0]);
    EXPECT_NE(changed[1], base[1]);
    for (const Flags& f : {with(&Flags::spp, "9"), with(&Flags::size, "24x16"), with(&Flags::extra, "--ambient 0.1"),
                           with(&Flags::extra, "--lighting default"),
                           with(&Flags::extra, "--camera-pos 0,1,3 --look-at 0,1,0")})
        EXPECT_EQ(common(ids(f), base), 0u) << f.spp << " " << f.size << " " << f.extra;  // references and cells alike
    changed = ids(with(&Flags::presets, "low,high"));  // one more cell; the others keep their ids
    EXPECT_EQ(changed.size(), 3u);
    EXPECT_EQ(common(changed, base), 2u);
    EXPECT_EQ(common(ids({"builtin:cornell"}), ids({"builtin:cornell-area"})), 0u);
}

}  // namespace
}  // namespace gis::test
