// Small RAII types over OpenGL objects. Every texture and buffer is charged to an owner (a pass,
// the scene) in a MemoryLedger when it is allocated and credited back when it is destroyed, so the
// app can say how much GPU memory each technique holds.
#pragma once

#include <glad/gl.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace gis::gl {

// The largest finite value of a half float (RGBA16F): radiance is clamped there, not to Inf
// (GLSL's MAX_HALF_FLOAT, renderer/shader_constants.cpp).
constexpr float kMaxHalfFloat = 65504.0f;

// Bytes held per owner. Lives as long as the renderer; resources keep a pointer to it.
struct MemoryLedger {
    std::map<std::string, int64_t> bytesByOwner;
    int64_t total() const;
};

// Where an allocation is charged: which ledger, under which owner's name.
struct MemoryScope {
    MemoryLedger* ledger = nullptr;
    std::string owner;
};

// Moves, never copies; releases the GL name (and its ledger charge) when it dies.
class Object {
public:
    using Deleter = void (*)(GLuint);
    Object() = default;
    Object(GLuint id, Deleter deleter) : id_(id), deleter_(deleter) {}
    Object(Object&& o) noexcept { *this = std::move(o); }
    Object& operator=(Object&& o) noexcept;
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    ~Object() { reset(); }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void charge(const MemoryScope& scope, int64_t bytes);
    int64_t bytes() const { return bytes_; }
    void reset();

private:
    GLuint id_ = 0;
    Deleter deleter_ = nullptr;
    MemoryScope scope_;
    int64_t bytes_ = 0;
};

struct Texture {
    Object object;
    GLenum target = 0;
    GLenum format = 0;
    int width = 0, height = 0, depth = 1, levels = 1;  // depth = layers (array) or slices (3D)
    GLuint id() const { return object.id(); }
};

// Immutable-storage textures (glTextureStorage*). Throws gis::Error on GL_OUT_OF_MEMORY.
Texture createTexture2D(const MemoryScope& scope, GLenum format, int width, int height, int levels = 1);
Texture createTexture2DArray(const MemoryScope& scope, GLenum format, int width, int height, int layers);
// `samples` per texel (GL_TEXTURE_2D_MULTISAMPLE, fixed sample locations); depth holds the samples.
Texture createTexture2DMultisample(const MemoryScope& scope, GLenum format, int width, int height, int samples);
Texture createTextureCubeArray(const MemoryScope& scope, GLenum format, int size, int cubes);
Texture createTexture3D(const MemoryScope& scope, GLenum format, int width, int height, int depth, int levels = 1);
// Another view of `source`'s storage (glTextureView): all its levels and layers, seen as `target`
// (a cube map array as a 2D array of its faces, say). Holds no memory of its own.
Texture createTextureView(const Texture& source, GLenum target);
int64_t bytesPerTexel(GLenum format);
// What createTexture2D charges for these arguments (memory estimates made before allocating).
int64_t texture2DBytes(GLenum format, int width, int height, int levels = 1);
int mipLevelsFor(int width, int height);

struct Buffer {
    Object object;
    int64_t size = 0;
    GLuint id() const { return object.id(); }
};
Buffer createBuffer(const MemoryScope& scope, int64_t size, const void* data, GLbitfield flags = 0);
// A buffer the shaders read as a shader storage block. One past GL_MAX_SHADER_STORAGE_BLOCK_SIZE
// would bind as GL_INVALID_VALUE and the pass would read nothing: it is refused here (gis::Error
// naming the owner, the size and the limit) before anything renders.
Buffer createStorageBuffer(const MemoryScope& scope, int64_t size, const void* data, GLbitfield flags = 0);
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE of the current context (at least 2^27 bytes by the GL 4.5 spec).
int64_t maxStorageBlockBytes();

Object createFramebuffer();
// Throws gis::Error naming `what` when the framebuffer is not complete.
void checkFramebuffer(GLuint fbo, const char* what);
// A framebuffer rendering into level 0 of `color` (attachment 0), checked complete.
Object createColorTarget(const Texture& color, const char* what);
Object createVertexArray();
Object createSampler();

// Pairs of GL_TIMESTAMP queries in a small ring, so reading a result never stalls the frame that
// issued it in interactive use; headless code calls collect(true). (Timestamps rather than
// GL_TIME_ELAPSED: llvmpipe's first TIME_ELAPSED query of a context reports time since an epoch.)
class GpuTimer {
public:
    void begin();
    // worked = false: the pass reused its cached results this frame (kept apart in `worked`, so a
    // converged or cached pass is not reported as taking 0 ms of real work).
    void end(bool worked = true);
    // Reads every finished query into samples (milliseconds). wait = block until all are done.
    void collect(bool wait);
    void clear() { samples.clear(), worked.clear(); }
    std::vector<double> samples;
    std::vector<uint8_t> worked;  // per sample: 1 if the pass did work in that frame

private:
    static constexpr int kRing = 4;
    Object begin_[kRing], end_[kRing];
    bool pending_[kRing] = {};
    bool worked_[kRing] = {};
    int next_ = 0;
    bool open_ = false;
};

// Throws gis::Error("out of GPU memory while ...") if GL reported GL_OUT_OF_MEMORY.
void checkOutOfMemory(const std::string& what);

}  // namespace gis::gl
