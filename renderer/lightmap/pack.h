// Rectangles into square atlases: skyline bottom-left, largest first (Jylänki 2010, "A Thousand
// Ways to Pack the Bin", the SKYLINE-BL variant), with a gutter between rectangles.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace gis::lightmap::detail {

struct Placement {
    int atlas = 0;
    glm::ivec2 at{0};  // min corner of the rectangle (its gutter lies outside it)
};

struct Packing {
    std::vector<Placement> places;  // per rectangle, in input order
    std::vector<int> atlasSizes;
};

// Rectangles `sizes` (texels, each at least 1) at least `gutter` texels from each other and from
// the atlas border. The first atlas is the smallest side (in steps of 1/16) that takes
// everything, up to `maxSize`; beyond that the rest spills into further atlases of `maxSize`. Throws gis::Error when
// `maxAtlases` do not suffice or a rectangle cannot fit one atlas.
Packing pack(const std::vector<glm::ivec2>& sizes, int gutter, int maxSize, int maxAtlases);

}  // namespace gis::lightmap::detail
