// Shared by the view tests: one headless GL context for the test binary, live GL object counts.
#pragma once

#include <string>

#include "gl/context.h"
#include "image.h"

namespace gis::test {

GlContext& viewContext();  // EGL, else OSMesa; created on first use

// Live GL objects of each kind in the current context, found by asking glIs* about every name up
// to the highest one handed out so far (Mesa hands out names in increasing order). Programs flagged
// for deletion (deleted by us, still referenced inside GL) are not counted.
struct GlObjectCounts {
    int textures = 0, buffers = 0, framebuffers = 0, vertexArrays = 0, samplers = 0, queries = 0, programs = 0;
    int total() const { return textures + buffers + framebuffers + vertexArrays + samplers + queries + programs; }
};
GlObjectCounts countGlObjects();
std::string describe(const GlObjectCounts& c);

// Mean absolute difference over R, G, B in 8-bit levels; sizes must match.
double meanAbsDiff(const ImageU8& a, const ImageU8& b);

}  // namespace gis::test
