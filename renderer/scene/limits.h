// Magnitude limits on what scene files give the renderer.
#pragma once

namespace gis {

// The largest radiance taken from a file: an environment map's texel, a glTF material's emission
// (emissiveFactor x KHR_materials_emissive_strength). Sums of it over the sphere (the SH projection,
// the sampling CDFs) and its square (variance estimates) stay far below a float's maximum (3.4e38),
// where 3e38 made inf, then NaN the shaders zeroed: black pixels. The viewer's settings hold their
// numbers to the same magnitude (kMaxSettingMagnitude).
constexpr float kMaxRadiance = 1e18f;

}  // namespace gis
