#include "gl/context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <sys/resource.h>

#include "gl/gl.h"
#include "error.h"

namespace gis {

Backend parseBackend(const std::string& name) {
    if (name == "auto") return Backend::Auto;
    if (name == "egl") return Backend::Egl;
    if (name == "osmesa") return Backend::OSMesa;
    if (name == "glfw") return Backend::Glfw;
    throw Error("unknown backend '" + name + "' (expected auto, egl, osmesa or glfw)");
}

const char* backendName(Backend backend) {
    switch (backend) {
        case Backend::Auto: return "auto";
        case Backend::Egl: return "egl";
        case Backend::OSMesa: return "osmesa";
        case Backend::Glfw: return "glfw";
    }
    return "?";
}

namespace {

void GLAPIENTRY debugCallback(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei,
                              const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    std::fprintf(stderr, "GL debug [%s, id %u]: %s\n",
                 type == GL_DEBUG_TYPE_ERROR ? "error" : "message", id, message);
}

// Shared by every backend once its context is current.
void finishContext(GlContext& ctx, const ContextOptions& options) {
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return std::string(s ? reinterpret_cast<const char*>(s) : "?");
    };
    ctx.renderer = str(GL_RENDERER);
    ctx.version = str(GL_VERSION);
    ctx.vendor = str(GL_VENDOR);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw Error(std::string(backendName(ctx.backend())) + ": OpenGL 4.5 core is required, got " +
                    ctx.version + " (" + ctx.renderer + ")");
    // Filter across cube face edges (point-light shadow PCF near a face boundary needs it).
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    const char* env = std::getenv("GIS_GL_DEBUG");
    bool debug = options.debug || (env && std::strcmp(env, "0") != 0);
#ifndef NDEBUG
    debug = true;
#endif
    if (debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
    }
}

}  // namespace

namespace {
// The address space a GL context needs: under `ulimit -v` of 300 to 700 MB Mesa's llvmpipe segfaulted
// inside shader compilation (LLVM's JIT; vct and sdf at 700 MB) or failed an allocation, with no
// message; every method rendered at 1 GiB. A GPU driver maps more, not less.
constexpr rlim_t kMinAddressSpaceBytes = rlim_t(1) << 30;

void checkAddressSpaceLimit() {
    struct rlimit limit {};
    if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur >= kMinAddressSpaceBytes)
        return;
    throw Error("the address-space limit (ulimit -v) is " + std::to_string(limit.rlim_cur >> 20) +
                " MiB: OpenGL needs at least " + std::to_string(kMinAddressSpaceBytes >> 20) +
                " MiB (software GL compiles shaders with LLVM and crashed below it); raise the limit");
}
}  // namespace

std::unique_ptr<GlContext> createContext(const ContextOptions& options) {
    checkAddressSpaceLimit();
    std::unique_ptr<GlContext> ctx;
    Backend b = options.backend;
    if (b == Backend::Auto && options.window) b = Backend::Glfw;
    if (b == Backend::Auto) {
        // Headless: EGL first (the GPU when there is one), OSMesa when EGL cannot give 4.5 core.
        try {
            ctx = createEglContext(options);
            finishContext(*ctx, options);
            return ctx;
        } catch (const Error& eglError) {
            ctx.reset();
            try {
                ctx = createOSMesaContext(options);
            } catch (const Error& osmesaError) {
                throw Error(std::string("no headless OpenGL 4.5 context: ") + eglError.what() +
                            "; " + osmesaError.what());
            }
        }
    } else if (b == Backend::Egl) {
        ctx = createEglContext(options);
    } else if (b == Backend::OSMesa) {
        ctx = createOSMesaContext(options);
    } else {
        ctx = createGlfwContext(options);
    }
    finishContext(*ctx, options);
    return ctx;
}

}  // namespace gis
