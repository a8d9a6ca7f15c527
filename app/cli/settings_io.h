// Settings files of the interactive sandbox (JSON): everything the panel sets, the camera and the
// edited lights. `gisandbox view --settings FILE` starts from one, the panel saves and loads them,
// `gisandbox render --settings FILE` renders a pane of one headless, and every screenshot's JSON
// sidecar is one (plus timings), so a screenshot can be reproduced.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "renderer.h"
#include "cli/view_state.h"

namespace gis::view {

constexpr int kSettingsVersion = 1;

nlohmann::ordered_json viewStateToJson(const ViewState& state);
// Reads the keys present over `state` (missing keys keep its values), validating each value as the
// panel would. Throws gis::Error naming the key.
void viewStateFromJson(const nlohmann::json& json, ViewState& state);

// Written atomically. Throws gis::Error naming the file. Loading also accepts a screenshot's JSON
// sidecar (its "settings" object).
void saveViewSettings(const std::string& path, const ViewState& state);
ViewState loadViewSettings(const std::string& path);

// Every field of a RenderSettings and every parameter of its method (screenshot sidecars).
nlohmann::ordered_json renderSettingsToJson(const RenderSettings& settings);

// Method parameters in JSON: {"ssao.samples": 32, "vct.conservative": "geometry", ...}, each value
// of its row's type, validated by the row.
nlohmann::ordered_json paramToJson(const ParamDesc& desc, const ParamValue& value);
ParamValue paramFromJson(const std::string& fullKey, const nlohmann::json& value);
nlohmann::ordered_json paramsToJson(const ParamValues& values);

nlohmann::ordered_json lightToJson(const Light& light);
Light lightFromJson(const nlohmann::json& json);

}  // namespace gis::view
