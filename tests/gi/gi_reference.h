// What the GI methods' tests score against, shared by vct, sdf and probes: a built-in scene's
// rasterized direct light and its path-traced images, each rendered once per process and only
// when a test asks for it, with the pixels that see each face; and the one switch that turns on
// the slow measurement tests.
//
//   GIS_REF_CACHE=DIR      shares the rendered references between processes: ctest sets it to a
//                          folder it empties at the start of each run (tests/CMakeLists.txt); set
//                          by hand, it keeps them between runs (tuning, at your own risk of an
//                          older build's images)
//   GIS_MEASURE=vct,sdf    runs those methods' measurement tests (`all`: every method's)
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "image.h"
#include "render_test_util.h"
#include "renderer.h"

namespace gis::test {

// The frame the references are rendered at: no ambient (the indirect term comes from the method).
struct ReferenceSpec {
    int size = 128;       // square, pixels
    int spp = 64;         // path tracer samples per pixel
    bool hdr32 = false;   // RGBA32F lighting buffer
};

// `gi` at the spec's size with no ambient (and the spec's spp for the path tracer).
RenderSettings referenceSettings(const std::string& gi, const ReferenceSpec& spec);

class GiReference {
public:
    GiReference(const std::string& builtin, const ReferenceSpec& spec);
    const ImageF& direct() const;                 // --gi none: the rasterizer's direct light and emission
    const ImageF& pathTraced(int bounces) const;  // 0: direct light only
    const ImageF& ptDirect() const { return pathTraced(0); }
    const ImageF& ptOneBounce() const { return pathTraced(1); }
    const ImageF& ptFull() const { return pathTraced(16); }
    ImageF ptIndirect() const;                    // one bounce minus direct
    const std::vector<PixelHit>& hits() const { return hits_; }
    const std::vector<bool>& interior() const { return interior_; }  // pixels 2 away from a face's edge
    // The mean over the interior pixels of a face (kCornellFaces) of channel c, or of R, G, B.
    double regionMean(const ImageF& img, int region, int channel = -1) const;
    // Colour bleeding on the Cornell floor: red over green of `indirect` on the floor's interior
    // pixels in the image's left quarter (near the red wall) and in its right quarter (near the green).
    struct FloorBleeding {
        double nearRed, nearGreen;
    };
    FloorBleeding floorBleeding(const ImageF& indirect) const;

private:
    const ImageF& render(const std::string& what, const RenderSettings& settings) const;
    std::string builtin_;
    ReferenceSpec spec_;
    Scene scene_;
    std::vector<PixelHit> hits_;
    std::vector<bool> interior_;
    mutable std::map<std::string, std::unique_ptr<ImageF>> images_;
};

// The reference of a built-in scene at `spec`, made once per process.
const GiReference& giReference(const std::string& builtin, const ReferenceSpec& spec);

// The Cornell box's faces as castPixels numbers them (draw * 8 + face, in the order built).
extern const std::map<std::string, int> kCornellFaces;

// a + b and a - b in R, G, B (a's alpha kept).
ImageF add(const ImageF& a, const ImageF& b);
ImageF subtract(const ImageF& a, const ImageF& b);

// Whether GIS_MEASURE names `method` (or says `all`).
bool measuring(const std::string& method);

}  // namespace gis::test
