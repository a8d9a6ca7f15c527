#include "nonfinite_counter.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace gis {

bool countingNonFinite() {
    static const bool on = [] {
        const char* env = std::getenv("GIS_CHECK_FINITE");
        return env && std::strcmp(env, "1") == 0;
    }();
    return on;
}

namespace {
GLint storageStride() {
    GLint alignment = 0;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    return std::max<GLint>(alignment, GLint(sizeof(uint32_t)));
}
}  // namespace

NonFiniteCounter::NonFiniteCounter(int slots, const gl::MemoryScope& scope)
    : stride_(storageStride()), totals_(size_t(std::max(slots, 1)), 0) {
    const std::vector<uint8_t> zeros(size_t(stride_) * totals_.size(), 0);
    buffer_ = gl::createBuffer(scope, int64_t(zeros.size()), zeros.data(), GL_DYNAMIC_STORAGE_BIT);
}

void NonFiniteCounter::bind(int slot) const {
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kNonFiniteBinding, buffer_.id(), GLintptr(slot) * stride_,
                      sizeof(uint32_t));
}

void NonFiniteCounter::collect() {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint8_t> bytes(size_t(stride_) * totals_.size());
    glGetNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(bytes.size()), bytes.data());
    bool any = false;
    for (size_t k = 0; k < totals_.size(); ++k) {
        uint32_t n = 0;
        std::memcpy(&n, bytes.data() + k * size_t(stride_), sizeof n);
        totals_[k] += n;
        any = any || n > 0;
    }
    if (!any) return;
    const std::vector<uint8_t> zeros(bytes.size(), 0);
    glNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(zeros.size()), zeros.data());
}

}  // namespace gis
