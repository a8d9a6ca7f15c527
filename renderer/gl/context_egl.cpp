// EGL headless context. Order: a hardware EGL device (NVIDIA exposes one per GPU through
// EGL_EXT_platform_device), then Mesa's surfaceless platform (llvmpipe on machines without a GPU).
// We always render into framebuffer objects, so the context is made current with no surface.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

#include "gl/context.h"
#include "gl/gl.h"
#include "error.h"

namespace gis {
namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

class EglContext final : public GlContext {
public:
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    ~EglContext() override {
        if (display != EGL_NO_DISPLAY) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
            eglTerminate(display);
        }
    }
    Backend backend() const override { return Backend::Egl; }
};

// Returns a display on a hardware device, or EGL_NO_DISPLAY when there is none.
EGLDisplay hardwareDeviceDisplay(std::string& detail) {
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExt, "EGL_EXT_device_enumeration") ||
        !hasExtension(clientExt, "EGL_EXT_platform_device"))
        return EGL_NO_DISPLAY;
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!queryDevices || !queryDeviceString || !getPlatformDisplay) return EGL_NO_DISPLAY;
    EGLint count = 0;
    if (!queryDevices(0, nullptr, &count) || count <= 0) return EGL_NO_DISPLAY;
    std::vector<EGLDeviceEXT> devices(count);
    queryDevices(count, devices.data(), &count);
    for (EGLint i = 0; i < count; ++i) {
        const char* ext = queryDeviceString(devices[i], EGL_EXTENSIONS);
        if (hasExtension(ext, "EGL_MESA_device_software")) continue;  // that is llvmpipe again
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY) continue;
        EGLint major, minor;
        if (!eglInitialize(d, &major, &minor)) continue;
        detail = "EGL device platform, device " + std::to_string(i);
        return d;
    }
    return EGL_NO_DISPLAY;
}

EGLDisplay surfacelessDisplay(std::string& detail) {
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExt, "EGL_MESA_platform_surfaceless")) return EGL_NO_DISPLAY;
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return EGL_NO_DISPLAY;
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major, minor;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor)) return EGL_NO_DISPLAY;
    detail = "EGL Mesa surfaceless platform";
    return d;
}

}  // namespace

std::unique_ptr<GlContext> createEglContext(const ContextOptions& options) {
    auto ctx = std::make_unique<EglContext>();
    ctx->display = hardwareDeviceDisplay(ctx->detail);
    if (ctx->display == EGL_NO_DISPLAY) ctx->display = surfacelessDisplay(ctx->detail);
    if (ctx->display == EGL_NO_DISPLAY)
        throw Error("egl: no EGL device and no Mesa surfaceless platform (is libegl-mesa0 installed?)");
    if (!eglBindAPI(EGL_OPENGL_API)) throw Error("egl: eglBindAPI(EGL_OPENGL_API) failed");

    const char* dispExt = eglQueryString(ctx->display, EGL_EXTENSIONS);
    EGLConfig config = nullptr;
    if (!hasExtension(dispExt, "EGL_KHR_no_config_context")) {
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                        EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(ctx->display, configAttribs, &config, 1, &n) || n < 1)
            throw Error("egl: no EGL config with OpenGL support");
    }
    if (!hasExtension(dispExt, "EGL_KHR_surfaceless_context"))
        throw Error("egl: display lacks EGL_KHR_surfaceless_context");
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                     EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
    ctx->context = eglCreateContext(ctx->display, config, EGL_NO_CONTEXT, contextAttribs);
    if (ctx->context == EGL_NO_CONTEXT)
        throw Error("egl: could not create an OpenGL 4.5 core context (EGL error 0x" +
                    [] { char b[16]; std::snprintf(b, sizeof b, "%x", eglGetError()); return std::string(b); }() +
                    ")");
    if (!eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->context))
        throw Error("egl: eglMakeCurrent failed");
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)))
        throw Error("egl: could not load OpenGL entry points");
    return ctx;
}

}  // namespace gis
