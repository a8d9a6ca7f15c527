// GLFW window context (GLX on X11): the interactive app, or a hidden window for `--backend glfw`.
#include "gl/gl.h"  // glad first: it must own the GL declarations
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <string>

#include "gl/context.h"
#include "error.h"

namespace gis {
namespace {

std::string lastGlfwError() {
    const char* desc = nullptr;
    glfwGetError(&desc);
    return desc ? desc : "unknown GLFW error";
}

class GlfwContext final : public GlContext {
public:
    GLFWwindow* handle = nullptr;
    ~GlfwContext() override {
        if (handle) glfwDestroyWindow(handle);
        glfwTerminate();
    }
    Backend backend() const override { return Backend::Glfw; }
    GLFWwindow* window() override { return handle; }
};

}  // namespace

std::unique_ptr<GlContext> createGlfwContext(const ContextOptions& options) {
    if (!glfwInit()) throw Error("glfw: cannot initialise (no display? set DISPLAY or use --backend egl): " +
                                 lastGlfwError());
    auto ctx = std::make_unique<GlfwContext>();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    ctx->handle = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!ctx->handle) throw Error("glfw: could not open an OpenGL 4.5 core window: " + lastGlfwError());
    glfwMakeContextCurrent(ctx->handle);
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)))
        throw Error("glfw: could not load OpenGL entry points");
    ctx->detail = "GLFW window";
    return ctx;
}

}  // namespace gis
