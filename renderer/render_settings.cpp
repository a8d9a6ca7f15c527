#include "render_settings.h"

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "error.h"

namespace gis {

namespace {
const char* const kDiffuseNames[kDiffuseModelCount] = {"lambert", "wrap", "toon", "burley"};
const char* const kSpecularNames[kSpecularModelCount] = {"ggx", "blinn", "toon", "none"};
}  // namespace

DiffuseModel parseDiffuse(const std::string& s) {
    for (int i = 0; i < kDiffuseModelCount; ++i)
        if (s == kDiffuseNames[i]) return DiffuseModel(i);
    throw Error("unknown diffuse BRDF '" + s + "' (expected lambert, wrap, toon or burley)");
}

SpecularModel parseSpecular(const std::string& s) {
    for (int i = 0; i < kSpecularModelCount; ++i)
        if (s == kSpecularNames[i]) return SpecularModel(i);
    throw Error("unknown specular BRDF '" + s + "' (expected ggx, blinn, toon or none)");
}

Tonemapper parseTonemapper(const std::string& s) {
    if (s == "aces") return Tonemapper::Aces;
    if (s == "linear") return Tonemapper::Linear;
    throw Error("unknown tonemapper '" + s + "' (expected aces or linear)");
}

bool physicallyBased(DiffuseModel d, SpecularModel s) {
    return (d == DiffuseModel::Lambert || d == DiffuseModel::Burley) && (s == SpecularModel::Ggx || s == SpecularModel::None);
}

void checkEnvironmentChoice(bool background, const std::string& environment, bool ambient) {
    if (background && !environment.empty())
        throw Error("background and environment both set the radiance of rays that leave the scene: give one of them");
    if (ambient && !environment.empty())
        throw Error("--ambient has no effect with --environment (the map lights what the ambient would): drop one");
}

namespace {
std::string rotationText(float degrees) {
    char text[64];
    std::snprintf(text, sizeof text, "environment rotation %g degrees", double(degrees));
    return text;
}
}  // namespace

void checkEnvironmentRotationValue(float degrees) {
    if (std::isfinite(degrees) && std::abs(degrees) <= kMaxEnvironmentRotation) return;
    char range[64];
    std::snprintf(range, sizeof range, ": it must be a finite number in [-%g, %g]", double(kMaxEnvironmentRotation),
                  double(kMaxEnvironmentRotation));
    throw Error(rotationText(degrees) + range);
}

void checkEnvironmentRotation(float degrees, const std::string& environment) {
    checkEnvironmentRotationValue(degrees);
    if (degrees != 0.0f && environment.empty())
        throw Error(rotationText(degrees) + " turns an environment map, and there is none: give one (--environment "
                                            "FILE.hdr) or leave the rotation at 0");
}

CameraMatrices cameraMatrices(const Scene& scene, int cameraIndex, float aspect) {
    if (!scene.cameras.empty() && (cameraIndex < 0 || cameraIndex >= int(scene.cameras.size())))
        throw Error("camera " + std::to_string(cameraIndex) + " does not exist (the scene has " +
                    std::to_string(scene.cameras.size()) + ")");
    const Camera cam = scene.cameras.empty() ? defaultCamera(scene.bounds, aspect) : scene.cameras[cameraIndex];
    CameraMatrices m;
    m.view = glm::inverse(cam.cameraToWorld);
    m.position = glm::vec3(cam.cameraToWorld[3]);
    m.znear = cam.znear;
    m.zfar = cam.zfar;
    if (cam.orthographic) {
        // Keep the file's vertical extent; the width follows the viewport's aspect.
        m.proj = glm::ortho(-cam.ymag * aspect, cam.ymag * aspect, -cam.ymag, cam.ymag, cam.znear, cam.zfar);
    } else if (cam.zfar <= 0.0f) {
        m.proj = glm::infinitePerspective(cam.yfov, aspect, cam.znear);
    } else {
        m.proj = glm::perspective(cam.yfov, aspect, cam.znear, cam.zfar);
    }
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
    return m;
}

}  // namespace gis
