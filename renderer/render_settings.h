// The render's settings: what a frame is rendered with (size, method and its parameters, BRDF
// models, tone mapping, shadows ...) and the camera it looks through. No GL types: the app, the
// bench and the metrics read them without a context.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "param_table.h"
#include "scene/scene.h"

namespace gis {

// BRDF models (shaders/brdf.glsl): the values are the GLSL DIFFUSE_* / SPECULAR_* ids.
enum class DiffuseModel { Lambert = 0, LambertWrap = 1, Toon = 2, Burley = 3 };
enum class SpecularModel { Ggx = 0, BlinnPhong = 1, Toon = 2, None = 3 };
constexpr int kDiffuseModelCount = 4;
constexpr int kSpecularModelCount = 4;
enum class Tonemapper { Aces, Linear };

DiffuseModel parseDiffuse(const std::string& s);    // lambert, wrap, toon, burley
SpecularModel parseSpecular(const std::string& s);  // ggx, blinn, toon, none
Tonemapper parseTonemapper(const std::string& s);
// Lambert or Burley diffuse with GGX or no specular: what the path tracer (the reference) renders.
bool physicallyBased(DiffuseModel diffuse, SpecularModel specular);

// The method a render uses when none is named: the one place outside renderer/gi/ that names one.
constexpr const char* kDefaultGiMethod = "none";

struct RenderSettings {
    int width = 256, height = 256;
    int camera = 0;                    // index into Scene::cameras; a default camera when there are none
    std::string gi = kDefaultGiMethod;  // a method in the registry (renderer/gi/methods.cpp)
    ParamValues params;                // "method.key" -> value, where not the row's default
    DiffuseModel diffuse = DiffuseModel::Lambert;
    SpecularModel specular = SpecularModel::Ggx;
    Tonemapper tonemap = Tonemapper::Aces;
    float exposureEV = 0.0f;
    glm::vec3 ambient{0.03f};          // constant ambient radiance, used where no method gives indirect light
    int shadowMapSize = 1024;          // directional and spot lights
    int shadowCubeSize = 512;          // point lights
    bool shadows = true;
    bool hdr32 = false;                // RGBA32F lighting buffer instead of RGBA16F
    std::optional<glm::vec3> background;  // overrides the scene's environment radiance
    // An equirectangular Radiance .hdr lighting the scene from afar (renderer/environment_gpu.h);
    // empty: the constant `background` (or the scene's own). The two are exclusive.
    std::string environment;
    // Degrees the map is turned about +Y (environment.h's environmentToMap): finite, in
    // [-kMaxEnvironmentRotation, kMaxEnvironmentRotation], and zero without a map.
    float environmentRotation = 0.0f;
    int samplesPerFrame = 1;           // progressive methods: samples added by each renderFrame()
    uint32_t seed = 0;                 // fixed: the same settings give the same image
    std::string view = "final";        // "final" or a debug view some pass offers (Renderer::views)
};

// An environment is a map or a constant, not both: --background with --environment (or the
// viewer's `background` with `environment`) is one error, the same for every caller; and a map is
// the baseline's ambient, so an ambient given beside it (`ambient`) would be ignored: refused too.
void checkEnvironmentChoice(bool background, const std::string& environment, bool ambient = false);
// A turn past a whole one in either direction is no use, and a magnitude that large loses the
// degrees' precision in float.
constexpr float kMaxEnvironmentRotation = 360.0f;
// --environment-rotation (the settings key environment_rotation, the viewer's line) as every caller
// checks it: a finite number within the range, and non-zero only with a map to turn.
void checkEnvironmentRotation(float degrees, const std::string& environment);
// The number alone, where the map is not known yet (a script line before its context).
void checkEnvironmentRotationValue(float degrees);

struct CameraMatrices {
    glm::mat4 view{1.0f}, proj{1.0f}, viewProj{1.0f}, invViewProj{1.0f};
    glm::vec3 position{0.0f};
    float znear = 0.01f, zfar = 100.0f;
};
CameraMatrices cameraMatrices(const Scene& scene, int cameraIndex, float aspect);

}  // namespace gis
