#include "gl/gl.h"

#include <algorithm>
#include <cmath>

#include "error.h"

namespace gis::gl {

int64_t MemoryLedger::total() const {
    int64_t sum = 0;
    for (const auto& [owner, bytes] : bytesByOwner) sum += bytes;
    return sum;
}

Object& Object::operator=(Object&& o) noexcept {
    if (this != &o) {
        reset();
        id_ = std::exchange(o.id_, 0);
        deleter_ = o.deleter_;
        scope_ = std::move(o.scope_);
        bytes_ = std::exchange(o.bytes_, 0);
        o.scope_ = {};
    }
    return *this;
}

void Object::charge(const MemoryScope& scope, int64_t bytes) {
    scope_ = scope;
    bytes_ = bytes;
    if (scope_.ledger) scope_.ledger->bytesByOwner[scope_.owner] += bytes;
}

void Object::reset() {
    if (id_ && deleter_) deleter_(id_);
    if (scope_.ledger && bytes_) {
        auto it = scope_.ledger->bytesByOwner.find(scope_.owner);
        if (it != scope_.ledger->bytesByOwner.end()) {
            it->second -= bytes_;
            if (it->second == 0) scope_.ledger->bytesByOwner.erase(it);
        }
    }
    id_ = 0;
    bytes_ = 0;
    scope_ = {};
}

void checkOutOfMemory(const std::string& what) {
    GLenum err;
    bool oom = false;
    while ((err = glGetError()) != GL_NO_ERROR)
        if (err == GL_OUT_OF_MEMORY) oom = true;
    if (oom) throw Error("out of GPU memory while " + what);
}

int64_t bytesPerTexel(GLenum format) {
    switch (format) {
        case GL_R8: case GL_R8UI: return 1;
        case GL_RG8: case GL_R16F: case GL_DEPTH_COMPONENT16: return 2;
        case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_RGB10_A2: case GL_R32F: case GL_RG16F:
        case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_R32UI: case GL_DEPTH_COMPONENT24:
            return 4;
        case GL_RGBA16F: case GL_RG32F: return 8;
        case GL_RGBA32F: return 16;
        default: return 4;
    }
}

int mipLevelsFor(int width, int height) {
    return 1 + static_cast<int>(std::floor(std::log2(static_cast<double>(std::max({width, height, 1})))));
}

namespace {
void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }
void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }

int64_t mipChainTexels(int w, int h, int d, int levels, bool mip3d) {
    int64_t sum = 0;
    for (int l = 0; l < levels; ++l) {
        sum += int64_t(w) * h * d;
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
        if (mip3d) d = std::max(1, d / 2);
    }
    return sum;
}

Texture makeTexture(GLenum target, GLenum format, int w, int h, int d, int levels) {
    if (w <= 0 || h <= 0 || d <= 0 || levels <= 0)
        throw Error("invalid texture size " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d));
    Texture t;
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    t.object = Object(id, deleteTexture);
    t.target = target;
    t.format = format;
    t.width = w;
    t.height = h;
    t.depth = d;
    t.levels = levels;
    return t;
}
}  // namespace

Texture createTexture2D(const MemoryScope& scope, GLenum format, int width, int height, int levels) {
    // Past the driver's limit glTextureStorage2D fails with GL_INVALID_VALUE, which the out-of-memory
    // check below does not see: the texture would be incomplete and read as black.
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
    if (width > limit || height > limit)
        throw Error("a " + std::to_string(width) + "x" + std::to_string(height) + " texture for " + scope.owner +
                    " is larger than this GPU's " + std::to_string(limit) + " texels a side (GL_MAX_TEXTURE_SIZE)");
    Texture t = makeTexture(GL_TEXTURE_2D, format, width, height, 1, levels);
    glTextureStorage2D(t.id(), levels, format, width, height);
    checkOutOfMemory("allocating a " + std::to_string(width) + "x" + std::to_string(height) + " texture for " +
                     scope.owner);
    t.object.charge(scope, texture2DBytes(format, width, height, levels));
    return t;
}

int64_t texture2DBytes(GLenum format, int width, int height, int levels) {
    return bytesPerTexel(format) * mipChainTexels(width, height, 1, levels, false);
}

Texture createTexture2DMultisample(const MemoryScope& scope, GLenum format, int width, int height, int samples) {
    Texture t = makeTexture(GL_TEXTURE_2D_MULTISAMPLE, format, width, height, samples, 1);
    glTextureStorage2DMultisample(t.id(), samples, format, width, height, GL_TRUE);
    checkOutOfMemory("allocating a " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                     std::to_string(samples) + "-sample texture for " + scope.owner);
    t.object.charge(scope, bytesPerTexel(format) * int64_t(width) * height * samples);
    return t;
}

Texture createTexture2DArray(const MemoryScope& scope, GLenum format, int width, int height, int layers) {
    Texture t = makeTexture(GL_TEXTURE_2D_ARRAY, format, width, height, layers, 1);
    glTextureStorage3D(t.id(), 1, format, width, height, layers);
    checkOutOfMemory("allocating a texture array for " + scope.owner);
    t.object.charge(scope, bytesPerTexel(format) * int64_t(width) * height * layers);
    return t;
}

Texture createTextureCubeArray(const MemoryScope& scope, GLenum format, int size, int cubes) {
    Texture t = makeTexture(GL_TEXTURE_CUBE_MAP_ARRAY, format, size, size, cubes * 6, 1);
    glTextureStorage3D(t.id(), 1, format, size, size, cubes * 6);
    checkOutOfMemory("allocating a cube map array for " + scope.owner);
    t.object.charge(scope, bytesPerTexel(format) * int64_t(size) * size * cubes * 6);
    return t;
}

Texture createTexture3D(const MemoryScope& scope, GLenum format, int width, int height, int depth, int levels) {
    Texture t = makeTexture(GL_TEXTURE_3D, format, width, height, depth, levels);
    glTextureStorage3D(t.id(), levels, format, width, height, depth);
    checkOutOfMemory("allocating a 3D texture for " + scope.owner);
    t.object.charge(scope, bytesPerTexel(format) * mipChainTexels(width, height, depth, levels, true));
    return t;
}

Texture createTextureView(const Texture& source, GLenum target) {
    GLuint id = 0;
    glGenTextures(1, &id);  // a view needs a name no target has been given yet
    glTextureView(id, target, source.id(), source.format, 0, source.levels, 0, source.depth);
    Texture t;
    t.object = Object(id, deleteTexture);
    t.target = target;
    t.format = source.format;
    t.width = source.width;
    t.height = source.height;
    t.depth = source.depth;
    t.levels = source.levels;
    return t;
}

Buffer createBuffer(const MemoryScope& scope, int64_t size, const void* data, GLbitfield flags) {
    Buffer b;
    GLuint id = 0;
    glCreateBuffers(1, &id);
    b.object = Object(id, deleteBuffer);
    b.size = std::max<int64_t>(size, 1);
    glNamedBufferStorage(id, b.size, size > 0 ? data : nullptr, flags);
    checkOutOfMemory("allocating a buffer of " + std::to_string(size) + " bytes for " + scope.owner);
    b.object.charge(scope, b.size);
    return b;
}

int64_t maxStorageBlockBytes() {
    GLint64 v = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v);
    return v > 0 ? int64_t(v) : int64_t(1) << 27;  // the spec's minimum when the query fails
}

Buffer createStorageBuffer(const MemoryScope& scope, int64_t size, const void* data, GLbitfield flags) {
    const int64_t limit = maxStorageBlockBytes();
    if (size > limit)
        throw Error(scope.owner + ": a shader storage buffer of " + std::to_string(size) + " bytes exceeds this GPU's " +
                    std::to_string(limit) + " (GL_MAX_SHADER_STORAGE_BLOCK_SIZE); use smaller settings");
    return createBuffer(scope, size, data, flags);
}

Object createFramebuffer() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Object(id, deleteFramebuffer);
}

void checkFramebuffer(GLuint fbo, const char* what) {
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "framebuffer for %s is incomplete (status 0x%x)", what, status);
        throw Error(buf);
    }
}

Object createColorTarget(const Texture& color, const char* what) {
    Object fbo = createFramebuffer();
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
    checkFramebuffer(fbo.id(), what);
    return fbo;
}

Object createVertexArray() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return Object(id, deleteVertexArray);
}

Object createSampler() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    return Object(id, deleteSampler);
}

void GpuTimer::begin() {
    if (!begin_[next_]) {
        GLuint ids[2] = {};
        glCreateQueries(GL_TIMESTAMP, 2, ids);
        begin_[next_] = Object(ids[0], deleteQuery);
        end_[next_] = Object(ids[1], deleteQuery);
    }
    if (pending_[next_]) collect(true);  // ring full: the oldest result must be read first
    glQueryCounter(begin_[next_].id(), GL_TIMESTAMP);
    open_ = true;
}

void GpuTimer::end(bool worked) {
    if (!open_) return;
    glQueryCounter(end_[next_].id(), GL_TIMESTAMP);
    pending_[next_] = true;
    worked_[next_] = worked;
    next_ = (next_ + 1) % kRing;
    open_ = false;
}

void GpuTimer::collect(bool wait) {
    // Oldest first, so samples stay in frame order.
    for (int k = 0; k < kRing; ++k) {
        int i = (next_ + k) % kRing;
        if (!pending_[i]) continue;
        if (!wait) {
            GLint available = 0;
            glGetQueryObjectiv(end_[i].id(), GL_QUERY_RESULT_AVAILABLE, &available);
            if (!available) return;
        }
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(begin_[i].id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(end_[i].id(), GL_QUERY_RESULT, &t1);
        samples.push_back(t1 > t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0);
        worked.push_back(worked_[i] ? 1 : 0);
        pending_[i] = false;
    }
}

}  // namespace gis::gl
