// Counting the NaN and Inf values the shaders replace (finiteOrZero in common.glsl). Release
// shading keeps the guard: one bad sample must not poison a blur, a mip chain or a mean. But a
// guarded NaN is a bug hidden as a black pixel, so with GIS_CHECK_FINITE=1 in the environment
// (the tests set it) every guard also counts what it replaced, per pass, and the renderer reports
// it: tests fail on any, `render` exits with an error naming the pass.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gl/gl.h"

namespace gis {

constexpr int kNonFiniteBinding = 8;  // the counters' shader-storage binding point (NONFINITE_BINDING)

// GIS_CHECK_FINITE is set to 1 (read once; the shaders are compiled with the counting guards).
bool countingNonFinite();

// One counter per pass slot, each at its own aligned offset so a pass binds only its own.
class NonFiniteCounter {
public:
    NonFiniteCounter(int slots, const gl::MemoryScope& scope);
    void bind(int slot) const;
    // Adds what each slot counted since the last read to the totals and clears the counters.
    void collect();
    uint64_t total(int slot) const { return totals_[size_t(slot)]; }

private:
    gl::Buffer buffer_;
    GLint stride_ = 0;
    std::vector<uint64_t> totals_;
};

}  // namespace gis
