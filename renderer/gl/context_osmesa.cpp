// OSMesa: Mesa's off-screen software context (llvmpipe). It needs a client-memory colour buffer
// to be current; we render into framebuffer objects, so a 1x1 buffer is enough.
#include "gl/gl.h"  // glad first: osmesa.h would otherwise pull in the system GL/gl.h
#include <GL/osmesa.h>

#include "gl/context.h"
#include "error.h"

namespace gis {
namespace {

class OSMesaGlContext final : public GlContext {
public:
    OSMesaContext context = nullptr;
    unsigned char pixel[4] = {};
    ~OSMesaGlContext() override {
        if (context) OSMesaDestroyContext(context);
    }
    Backend backend() const override { return Backend::OSMesa; }
};

GLADapiproc osmesaProc(const char* name) { return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name)); }

}  // namespace

std::unique_ptr<GlContext> createOSMesaContext(const ContextOptions&) {
    auto ctx = std::make_unique<OSMesaGlContext>();
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    ctx->context = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx->context) throw Error("osmesa: could not create an OpenGL 4.5 core context");
    if (!OSMesaMakeCurrent(ctx->context, ctx->pixel, GL_UNSIGNED_BYTE, 1, 1))
        throw Error("osmesa: OSMesaMakeCurrent failed");
    if (!gladLoadGL(osmesaProc)) throw Error("osmesa: could not load OpenGL entry points");
    ctx->detail = "OSMesa";
    return ctx;
}

}  // namespace gis
