// `gisandbox bench` end to end at a tiny size: well-formed JSON/CSV, a grid and a chart per scene,
// the reference cached between runs, and clean failures on bad flags.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "bench/bench_plan.h"
#include "cli_util.h"
#include "gi/method.h"
#include "image.h"

namespace gis::test {
namespace {

TEST(Bench, RunsEndToEndAndCachesTheReference) {
    const std::string dir = tempDir("bench_tiny");
    const std::string args = "bench --scenes builtin:cornell --size 24x24 --frames 3 --warmup 1 --reference-spp 8 "
                             "--presets low,high --methods none,ssao,pathtrace --out-dir " + dir;
    CliResult r = runCli(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("rendering the reference"), std::string::npos) << r.err;

    std::ifstream jf(dir + "/bench.json");
    const nlohmann::json j = nlohmann::json::parse(jf);
    EXPECT_FALSE(j["machine"]["gl_renderer"].get<std::string>().empty());
    ASSERT_EQ(j["results"].size(), 6u);  // {none, ssao, pathtrace} x {low, high}
    for (const auto& row : j["results"]) {
        EXPECT_EQ(row["scene"], "cornell");
        EXPECT_GT(row["gpu_ms"].get<double>(), 0.0) << row.dump();
        // Wall clock includes the GPU work it waited for (glFinish): never below the GPU figure by much.
        EXPECT_GT(row["wall_ms"].get<double>(), 0.5 * row["gpu_ms"].get<double>()) << row.dump();
        EXPECT_GT(row["gpu_bytes"].get<int64_t>(), 0) << row.dump();
        EXPECT_GE(row["flip"].get<double>(), 0.0);
        EXPECT_LE(row["flip"].get<double>(), 1.0);
        EXPECT_GE(row["rmse"].get<double>(), 0.0);
        EXPECT_TRUE(row["pass_ms"].is_object());
        // Throughput only where rays are counted (the path tracer).
        EXPECT_EQ(row.contains("mrays_per_s"), row["method"] == "pathtrace") << row.dump();
        if (row["method"] == "pathtrace") {
            EXPECT_GT(row["mrays_per_s"].get<double>(), 0.0);
        }
        if (row["method"] == "ssao") {
            EXPECT_GT(row["ao_rmse_vs_raytraced"].get<double>(), 0.0);
            EXPECT_LT(row["ao_rmse_vs_raytraced"].get<double>(), 0.5);
        }
        // Both costs: after a cut, the frames until final (the path tracer's are its samples: 4 at
        // low, 64 at high) and their GPU ms, and the error at 1, 2, 4, ... frames and the last.
        const auto& cut = row["converge"];
        const int frames = cut["frames"].get<int>();
        EXPECT_EQ(frames, row["method"] != "pathtrace" ? 1 : row["preset"] == "low" ? 4 : 64) << row.dump();
        EXPECT_GE(cut["gpu_ms"].get<double>(), cut["frame_gpu_ms"].get<double>() * (frames > 1 ? 1.0 : 0.0));
        const auto& quality = row["quality"];
        ASSERT_FALSE(quality.empty());
        EXPECT_EQ(quality.front()["frames"], 1);
        EXPECT_EQ(quality.back()["frames"], frames);
        for (size_t i = 1; i < quality.size(); ++i) {
            EXPECT_EQ(quality[i]["frames"].get<int>(), std::min(2 * quality[i - 1]["frames"].get<int>(), frames));
            EXPECT_GE(quality[i]["gpu_ms"].get<double>(), quality[i - 1]["gpu_ms"].get<double>());
        }
        if (row["method"] == "none") {  // final in its first frame: the curve's one point is the image scored
            EXPECT_NEAR(quality.back()["flip"].get<double>(), row["flip"].get<double>(), 1e-9);
        }
        if (row["method"] == "pathtrace" && row["preset"] == "high") {
            EXPECT_GT(quality.front()["rmse"].get<double>(), 1.5 * quality.back()["rmse"].get<double>()) << row.dump();
        }
        // The Cornell box's point light, halved: the path tracer starts its samples over.
        ASSERT_TRUE(row.contains("light_edit")) << row.dump();
        EXPECT_EQ(row["light_edit"]["frames"].get<int>(), row["method"] == "pathtrace" ? frames : 1) << row.dump();
        // When the image stopped changing, measured on the images: at once for a method final in one
        // frame; not before the path tracer's image has lost its first frames' noise.
        for (const auto* c : {&cut, &row["light_edit"]}) {
            const int settled = (*c)["settled_frames"].get<int>(), run = (*c)["frames"].get<int>();
            EXPECT_GE(settled, 1) << row.dump();
            EXPECT_LE(settled, run) << row.dump();
            EXPECT_LE((*c)["settled_gpu_ms"].get<double>(), (*c)["gpu_ms"].get<double>()) << row.dump();
            if (run == 1) {
                EXPECT_EQ(settled, 1) << row.dump();
            }
            if (row["method"] == "pathtrace" && row["preset"] == "high") {
                EXPECT_GT(settled, 4) << row.dump();
            }
        }
    }
    std::ifstream cf(dir + "/bench.csv");
    std::string line;
    int lines = 0;
    while (std::getline(cf, line)) ++lines;
    EXPECT_EQ(lines, 7);  // header + 6 rows
    const ImageU8 chart = readPng(dir + "/cornell_chart.png"), grid = readPng(dir + "/cornell_grid.png");
    EXPECT_GT(chart.width, 100);
    EXPECT_GT(chart.height, chart.width) << "two panels, one above the other";
    EXPECT_GT(grid.width, 100);
    EXPECT_GT(readPng(dir + "/cornell_quality.png").width, 100);

    r = runCli(args);  // second run: the reference comes from the cache
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("reference from cache"), std::string::npos) << r.err;
}

// A cell measures what a user's first run pays: the lightmap's bake, not its disk cache (the
// 2026-12-06 table read every bake from the cache the previous run had left: final at frame 1).
TEST(Bench, CellsMeasureTheBakeNotItsDiskCache) {
    BenchJob job;
    job.kind = JobKind::Cell;
    job.method = "lightmap";
    job.preset = "low";
    EXPECT_EQ(getParam(jobSettings(job, RenderSettings{}), "lightmap.cache").number, 0.0);
    job.method = "vct";  // a method without a disk cache keeps its settings
    EXPECT_NO_THROW(jobSettings(job, RenderSettings{}));
}

// A 16x16 low-preset bench of `flags` into `dir`: its bench.json (no results when it failed).
nlohmann::json tinyBench(const std::string& flags, const std::string& dir) {
    const CliResult r = runCli("bench --size 16x16 --frames 2 --warmup 1 --reference-spp 4 --presets low " + flags +
                               " --out-dir " + dir);
    EXPECT_EQ(r.status, 0) << r.err;
    if (r.status != 0) return {{"results", nlohmann::json::array()}};
    std::ifstream jf(dir + "/bench.json");
    return nlohmann::json::parse(jf);
}

// A baked method's cell reports its atlas beside the bake's time (its convergence) and memory:
// atlas_texels in JSON and CSV, absent for a method without one.
TEST(Bench, ALightmapCellReportsItsAtlasTexels) {
    const std::string dir = tempDir("bench_lightmap");
    const nlohmann::json j = tinyBench("--scenes builtin:cornell --methods none,lightmap", dir);
    ASSERT_EQ(j["results"].size(), 2u);
    for (const auto& row : j["results"]) {
        if (row["method"] == "none") {
            EXPECT_FALSE(row.contains("atlas_texels")) << row.dump();
            continue;
        }
        const int64_t texels = row.value("atlas_texels", int64_t(0));
        EXPECT_GT(texels, 0) << row.dump();
        EXPECT_GT(row["converge"]["frames"].get<int>(), 1) << "the bake's frames: " << row.dump();
    }
    std::ifstream cf(dir + "/bench.csv");
    std::vector<std::vector<std::string>> lines;
    for (std::string line; std::getline(cf, line);) {  // no field of bench.csv holds a comma
        std::istringstream fields(line + ",");
        lines.emplace_back();
        for (std::string field; std::getline(fields, field, ',');) lines.back().push_back(field);
    }
    ASSERT_EQ(lines.size(), 3u);  // the header, none, lightmap
    const auto column = std::find(lines[0].begin(), lines[0].end(), "atlas_texels");
    ASSERT_NE(column, lines[0].end());
    const size_t c = size_t(column - lines[0].begin());
    EXPECT_EQ(lines[1].at(c), "");
    EXPECT_EQ(lines[2].at(c), std::to_string(j["results"][1]["atlas_texels"].get<int64_t>()));
}

// --emitters lights,gi: each cell once per mode, against one reference, the mode in its row.
TEST(Bench, EmitterModesGiveARowEach) {
    const std::string dir = tempDir("bench_emitters");
    const nlohmann::json j = tinyBench("--scenes builtin:cornell-area --methods none --emitters lights,gi", dir);
    ASSERT_EQ(j["results"].size(), 2u);
    EXPECT_EQ(j["results"][0]["emitters"], "lights");
    EXPECT_EQ(j["results"][1]["emitters"], "gi");
    EXPECT_FALSE(j["results"][0].contains("light_edit")) << "cornell-area has no punctual light to edit";
    // ReSTIR lights the room only with lights: the two images differ.
    EXPECT_NE(j["results"][0]["rmse"].get<double>(), j["results"][1]["rmse"].get<double>());
    for (const char* bad : {"lights,lights", "lights,", "candle"}) {
        const CliResult r = runCli(std::string("bench --scenes builtin:cornell-area --size 16x16 --reference-spp 4 --presets low "
                                         "--methods none --emitters ") + bad + " --out-dir " + dir + "/bad");
        EXPECT_NE(r.status, 0) << bad;
        EXPECT_EQ(countLines(r.err), 1) << bad << ": " << r.err;
    }
}

TEST(Bench, BadFlagsFailCleanly) {
    const std::string dir = tempDir("bench_bad");
    for (const std::string& args : {std::string("bench --presets ultra --out-dir ") + dir,
                                    std::string("bench --methods magic --out-dir ") + dir,
                                    std::string("bench --scenes builtin:nothing --out-dir ") + dir,
                                    std::string("bench --metric beauty --out-dir ") + dir,
                                    std::string("bench --size 0x0 --out-dir ") + dir}) {
        CliResult r = runCli(args);
        EXPECT_NE(r.status, 0) << args;
        EXPECT_EQ(countLines(r.err), 1) << args << ": " << r.err;
        EXPECT_FALSE(fileExists(dir + "/bench.json")) << args;
    }
}

}  // namespace
}  // namespace gis::test
