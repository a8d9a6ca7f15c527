#include "gi/vct/vct_settings.h"

#include <cmath>

namespace gis {

namespace {
void checkRange(const char* key, float v, float lo, float hi, bool openLow) {
    if (!std::isfinite(v) || v > hi || (openLow ? v <= lo : v < lo))
        throw Error(std::string(key) + " " + std::to_string(v) + " is out of range " + (openLow ? "(" : "[") +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
}
}  // namespace

void checkVctSettings(const VctSettings& s) {
    const int r = s.resolution;
    if (r < 8 || r > 512 || (r & (r - 1)) != 0)
        throw Error("vct.resolution " + std::to_string(r) + " must be a power of two in [8, 512]");
    if (s.bounces < 1 || s.bounces > 4)
        throw Error("vct.bounces " + std::to_string(s.bounces) + " is out of range [1, 4]");
    if (s.coneSet < 0 || s.coneSet > 1) throw Error("vct.cones " + std::to_string(s.coneSet) + " must be 0 (six) or 1 (four)");
    checkRange("vct.step", s.stepFactor, 0.0f, 2.0f, true);
    checkRange("vct.max_distance", s.maxDistance, 0.0f, 2.0f, true);
    checkRange("vct.offset", s.offset, 0.0f, 8.0f, false);
    checkRange("vct.intensity", s.intensity, 0.0f, 16.0f, false);
    if (s.debugChannel < 0 || s.debugChannel > 3)
        throw Error("vct.debug_channel " + std::to_string(s.debugChannel) + " is out of range [0, 3]");
    if (s.debugLevel < 0 || s.debugLevel > 9)
        throw Error("vct.debug_level " + std::to_string(s.debugLevel) + " is out of range [0, 9]");
    if (s.sliceAxis < 0 || s.sliceAxis > 2) throw Error("vct.slice_axis " + std::to_string(s.sliceAxis) + " is out of range [0, 2]");
    checkRange("vct.slice_position", s.slicePosition, 0.0f, 1.0f, false);
}

VctSettings vctPreset(const std::string& name) {
    VctSettings s;
    if (name == "low") {
        s.resolution = 32;
        s.anisotropic = false;
        s.coneSet = 1;
        s.stepFactor = 1.0f;
        s.specular = false;
    } else if (name == "medium") {
        s.resolution = 64;
    } else if (name == "high") {
        s.resolution = 128;
        s.anisotropic = true;
        s.bounces = 2;
        s.stepFactor = 0.33f;
    } else {
        throw Error("unknown vct preset '" + name + "' (expected low, medium or high)");
    }
    return s;
}

}  // namespace gis
