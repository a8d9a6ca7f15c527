#include "presets.h"

#include <algorithm>

namespace gis {

namespace {
int presetIndex(const std::string& preset) {
    const auto& names = presetNames();
    auto it = std::find(names.begin(), names.end(), preset);
    if (it == names.end()) throw Error("unknown preset '" + preset + "' (expected low, medium or high)");
    return int(it - names.begin());
}

// --gi none: the rasterizer's cost and accuracy knob is shadow-map resolution.
constexpr int kShadowMap[3] = {256, 1024, 2048};
constexpr int kShadowCube[3] = {128, 512, 1024};
// --gi ssao: directions x points per direction, and resolution.
constexpr int kAoSamples[3] = {8, 16, 64};
constexpr int kAoSteps[3] = {2, 4, 8};
constexpr bool kAoHalfRes[3] = {true, false, false};
// --gi pathtrace at low sample counts: the reference's own speed/noise trade.
constexpr int kPathTraceSpp[3] = {4, 16, 64};
}  // namespace

const std::vector<std::string>& presetNames() {
    static const std::vector<std::string> names{"low", "medium", "high"};
    return names;
}

std::vector<std::string> benchmarkMethods() { return {"none", "ssao", "pathtrace"}; }

void applyPreset(RenderSettings& s, const std::string& method, const std::string& preset) {
    checkGiMethod(method);
    const int i = presetIndex(preset);
    s.gi = method;
    if (method == "none") {
        s.shadowMapSize = kShadowMap[i];
        s.shadowCubeSize = kShadowCube[i];
    } else if (method == "ssao") {
        s.aoSamples = kAoSamples[i];
        s.aoSteps = kAoSteps[i];
        s.aoHalfResolution = kAoHalfRes[i];
    } else if (method == "pathtrace") {
        s.spp = kPathTraceSpp[i];
        s.samplesPerFrame = s.spp;
    }
}

std::string describePreset(const std::string& method, const std::string& preset) {
    const int i = presetIndex(preset);
    if (method == "none")
        return "shadow maps " + std::to_string(kShadowMap[i]) + ", cubes " + std::to_string(kShadowCube[i]);
    if (method == "pathtrace") return std::to_string(kPathTraceSpp[i]) + " spp";
    if (method == "ssao")
        return std::to_string(kAoSamples[i]) + " directions x " + std::to_string(kAoSteps[i]) + " steps" +
               (kAoHalfRes[i] ? ", half resolution" : "");
    return preset;
}

}  // namespace gis
