// Running one bench job (a reference or a cell) in the current GL context and writing its result:
// references to the cache directory (CACHE/ID.exr + CACHE/ID.json), cells to OUT/cells
// (ID.png + ID.json). The same function serves `bench --cell ID` and the in-process `bench`.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_plan.h"

namespace gis {

struct SweepDirs {
    std::string outDir;
    std::string cacheDir;  // references; shared between sweeps (and machines) by content id
};
SweepDirs sweepDirs(const std::string& outDir, const std::string& cacheDir);  // cacheDir "" = OUT/cache
void createSweepDirs(const SweepDirs& dirs);  // throws gis::Error naming the one it cannot create

std::string recordPath(const SweepDirs& dirs, const BenchJob& job);   // ID.json
std::string imagePath(const SweepDirs& dirs, const BenchJob& job);    // ID.exr (references), ID.png (cells)

// The GL renderer this process measures on: {"gl_renderer", "gl_version", "backend"}.
nlohmann::ordered_json currentMachine(const std::string& backend);

enum class JobOutcome { Ran, AlreadyDone };

// Runs `job` unless its valid result is there already (then a no-op, unless `force`). A cell needs
// its references' valid results in the cache and throws gis::Error naming the missing one. A job
// whose id no longer matches its scene file and settings (changed since --plan) is refused. On
// failure the message is left in ID.failed for --merge. `openGl` makes a GL context current (once
// per process is enough) and returns currentMachine; it is called only once the job will render,
// so a job that is done, or a cell without its reference, never starts one.
using GlOpener = std::function<nlohmann::ordered_json()>;
JobOutcome runJob(const BenchJob& job, const SweepDirs& dirs, bool force, const GlOpener& openGl);

}  // namespace gis
