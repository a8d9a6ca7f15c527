// One interface over the three ways gisandbox gets an OpenGL 4.5 core context:
// EGL (headless: NVIDIA through the device platform when present, Mesa surfaceless otherwise),
// OSMesa (headless, software), and a GLFW window (GLX, interactive).
#pragma once

#include <memory>
#include <string>

struct GLFWwindow;

namespace gis {

enum class Backend { Auto, Egl, OSMesa, Glfw };

Backend parseBackend(const std::string& name);  // throws gis::Error
const char* backendName(Backend backend);

struct ContextOptions {
    Backend backend = Backend::Auto;  // Auto: EGL, then OSMesa (headless) / GLFW (window)
    bool window = false;              // interactive: Auto means GLFW
    bool visible = false;             // GLFW only
    int width = 256, height = 256;    // window size; headless work renders into FBOs anyway
    bool debug = false;               // KHR_debug context and message callback
    std::string title = "gisandbox";
};

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual Backend backend() const = 0;
    virtual GLFWwindow* window() { return nullptr; }
    std::string renderer, version, vendor;  // GL_RENDERER, GL_VERSION, GL_VENDOR
    std::string detail;                     // how it was made (EGL device or platform, ...)
};

// Creates the context, makes it current, loads GL entry points and checks for 4.5 core.
// Throws gis::Error naming the backend and what failed (no display, no 4.5, ...).
std::unique_ptr<GlContext> createContext(const ContextOptions& options);

std::unique_ptr<GlContext> createEglContext(const ContextOptions& options);
std::unique_ptr<GlContext> createOSMesaContext(const ContextOptions& options);
std::unique_ptr<GlContext> createGlfwContext(const ContextOptions& options);

}  // namespace gis
