// Quality presets per GI method: what "low", "medium" and "high" mean for each. The benchmark
// sweeps them; the panel will offer the same names.
#pragma once

#include <string>
#include <vector>

#include "renderer.h"

namespace gis {

const std::vector<std::string>& presetNames();            // low, medium, high
std::vector<std::string> benchmarkMethods();               // every --gi method except the reference
// Sets the method and its preset's parameters; throws gis::Error for unknown names.
void applyPreset(RenderSettings& settings, const std::string& method, const std::string& preset);
// A short description, e.g. "shadow maps 1024 / cubes 512".
std::string describePreset(const std::string& method, const std::string& preset);

}  // namespace gis
