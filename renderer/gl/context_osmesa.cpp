// OSMesa: Mesa's off-screen software context (llvmpipe). It needs a client-memory colour buffer
// to be current; we render into framebuffer objects, so a 1x1 buffer is enough.
//
// The library is opened at run time, not linked: it pulls in Mesa's whole software stack (LLVM,
// z3, ICU: hundreds of MB), which a machine with a GPU driver behind EGL never uses, and which
// would otherwise have to travel with the binary to such a machine (scripts/gpu-bench.sh pack).
#include "gl/gl.h"  // glad first: osmesa.h would otherwise pull in the system GL/gl.h
#include <GL/osmesa.h>
#include <dlfcn.h>

#include "gl/context.h"
#include "error.h"

namespace gis {
namespace {

// The four entry points we call, by the names and types osmesa.h declares them with.
struct OSMesaApi {
    decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
    decltype(&OSMesaDestroyContext) destroyContext = nullptr;
};

template <class Fn>
void bindSymbol(void* library, const char* name, Fn& fn) {
    fn = reinterpret_cast<Fn>(dlsym(library, name));
    if (!fn) throw Error(std::string("osmesa: libOSMesa has no ") + name);
}

// Opened once and kept for the process: contexts made from it may outlive any one caller.
const OSMesaApi& osmesaApi() {
    static const OSMesaApi api = [] {
        void* library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (!library) throw Error(std::string("osmesa: cannot load libOSMesa.so.8 (") + dlerror() + ")");
        OSMesaApi a;
        bindSymbol(library, "OSMesaCreateContextAttribs", a.createContextAttribs);
        bindSymbol(library, "OSMesaMakeCurrent", a.makeCurrent);
        bindSymbol(library, "OSMesaGetProcAddress", a.getProcAddress);
        bindSymbol(library, "OSMesaDestroyContext", a.destroyContext);
        return a;
    }();
    return api;
}

class OSMesaGlContext final : public GlContext {
public:
    OSMesaContext context = nullptr;
    unsigned char pixel[4] = {};
    ~OSMesaGlContext() override {
        if (context) osmesaApi().destroyContext(context);
    }
    Backend backend() const override { return Backend::OSMesa; }
};

GLADapiproc osmesaProc(const char* name) { return reinterpret_cast<GLADapiproc>(osmesaApi().getProcAddress(name)); }

}  // namespace

std::unique_ptr<GlContext> createOSMesaContext(const ContextOptions&) {
    const OSMesaApi& api = osmesaApi();
    auto ctx = std::make_unique<OSMesaGlContext>();
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    ctx->context = api.createContextAttribs(attribs, nullptr);
    if (!ctx->context) throw Error("osmesa: could not create an OpenGL 4.5 core context");
    if (!api.makeCurrent(ctx->context, ctx->pixel, GL_UNSIGNED_BYTE, 1, 1))
        throw Error("osmesa: OSMesaMakeCurrent failed");
    if (!gladLoadGL(osmesaProc)) throw Error("osmesa: could not load OpenGL entry points");
    ctx->detail = "OSMesa";
    return ctx;
}

}  // namespace gis
