// `bench --merge DIR`: the cells' results gathered into bench.json, bench.csv and per scene a grid,
// a chart and a quality chart, in manifest order. All or nothing: any cell or reference whose
// result is missing, failed, cut short or altered is reported by id and nothing is written.
#pragma once

#include <string>
#include <vector>

#include "bench/bench_cell.h"
#include "bench/bench_plan.h"

namespace gis {

// A scene name as a file name: anything but letters, digits, - and _ becomes _.
std::string fileSafeName(std::string s);

// Returns 0, or throws gis::Error after listing every problem on stderr, one line each.
int mergeBench(const std::vector<BenchJob>& jobs, const SweepDirs& dirs, const std::string& metric);

}  // namespace gis
