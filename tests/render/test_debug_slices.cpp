// The debug slices of the volume methods (vct.slice, sdf.slice, hddagi.occupancy) share one frame
// (shaders/debug_slice.glsl): square and centred whatever the image's aspect (they were stretched
// over it), the horizontal axis marked along the bottom and the vertical one along the left edge in
// its axis's colour (x red, y green, z blue), and the slice's position as a bar in the cut axis's
// colour along the top, filled to it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_util.h"
#include "image.h"

namespace {

using gis::test::runCli;
using gis::test::tempDir;

enum Colour { Black, Red, Green, Blue, Other };

// The frame's colours are pure primaries; what the slice itself shows is not asked.
Colour colourAt(const gis::ImageF& img, int x, int y) {
    const float* p = img.at(x, y);
    auto is = [&](float r, float g, float b) {
        return std::abs(p[0] - r) < 0.02f && std::abs(p[1] - g) < 0.02f && std::abs(p[2] - b) < 0.02f;
    };
    if (is(0.0f, 0.0f, 0.0f)) return Black;
    if (is(1.0f, 0.1f, 0.1f)) return Red;
    if (is(0.1f, 1.0f, 0.1f)) return Green;
    if (is(0.2f, 0.4f, 1.0f)) return Blue;
    return Other;
}

TEST(DebugSlices, AreSquareAndMarkTheirAxesAndPosition) {
    const std::string dir = tempDir("debug_slices");
    struct View {
        const char* gi;
        const char* view;
        const char* axisKey;
        const char* positionKey;
    };
    const View views[] = {{"vct", "vct.slice", "vct.slice-axis", "vct.slice-position"},
                          {"sdf", "sdf.slice", "sdf.slice-axis", "sdf.slice-position"},
                          {"hddagi", "hddagi.occupancy", "hddagi.slice-axis", "hddagi.slice-position"}};
    // The low presets and two frames: the frame is asked, not the volume's contents, and the
    // probes' updates (until converged, without --frames) were most of a render's time.
    // 96x64: the slice is the middle 64x64, one-pixel bands (64 / 48) around a 62x62 interior.
    // Image rows run top to bottom: the bottom band is row 63.
    for (const View& v : views) {
        for (const char* axis : {"x", "z"}) {
            const std::string out = dir + "/" + v.gi + "_" + axis + ".exr";
            const gis::test::CliResult r =
                runCli(std::string("render --scene builtin:cornell --size 96x64 --frames 2 --preset low --gi ") + v.gi + " --view " + v.view +
                       " --set " + v.axisKey + "=" + axis + " --set " + v.positionKey + "=0.25 --out '" + out + "'");
            ASSERT_EQ(r.status, 0) << r.err;
            const gis::ImageF img = gis::readExr(out);
            const std::string what = std::string(v.view) + " cut along " + axis;
            const bool cutZ = std::string(axis) == "z";
            EXPECT_EQ(colourAt(img, 8, 32), Black) << what << ": the margin beside the square";
            EXPECT_EQ(colourAt(img, 87, 32), Black) << what;
            EXPECT_EQ(colourAt(img, 48, 63), cutZ ? Red : Green) << what << ": the horizontal axis (x, or y for an x cut)";
            EXPECT_EQ(colourAt(img, 16, 32), cutZ ? Green : Blue) << what << ": the vertical axis (y, or z for an x cut)";
            const Colour cut = cutZ ? Blue : Red;
            EXPECT_EQ(colourAt(img, 17 + 5, 0), cut) << what << ": the position bar, filled to a quarter";
            EXPECT_EQ(colourAt(img, 17 + 20, 0), Black) << what << ": the bar past a quarter";
        }
    }
}

}  // namespace
