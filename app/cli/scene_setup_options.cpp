#include "cli/scene_setup_options.h"

#include <CLI/CLI.hpp>

#include <cstdio>

#include "gi/method.h"
#include "scene/scene_lighting.h"

namespace gis {

void addSceneSetupOptions(CLI::App& cmd, SceneSetupOptions& o) {
    cmd.add_option("--lighting", o.lighting,
                   "auto (the scene's lights, or a default sun and sky when it has no light and no emission strong "
                   "enough to light it, and no --environment map), "
                   "scene, default (sun and sky instead), none")
        ->capture_default_str();
    cmd.add_option("--camera", o.camera,
                   "The file's camera N, or auto (frame the scene's bounds; the default for files without cameras)");
    cmd.add_option("--camera-pos", o.cameraPos, "Camera position X,Y,Z (with --look-at)")->delimiter(',')->expected(3);
    cmd.add_option("--look-at", o.lookAt, "Point the camera looks at X,Y,Z (with --camera-pos)")->delimiter(',')->expected(3);
    cmd.add_option("--fov", o.fov, "Vertical field of view in degrees, with --camera-pos")->capture_default_str();
    cmd.add_option("--emitters", o.emitters,
                   "How emissive surfaces light the scene: lights (direct light by ReSTIR, the GI volume without "
                   "emission), gi (only through the GI method), off (only the visible emission), auto (the default: "
                   "lights when the emission is bright enough to light the scene, else off); sets emitters.mode");
}

CameraRequest cameraRequest(const SceneSetupOptions& o) {
    CameraRequest r;
    if (!o.cameraPos.empty() || !o.lookAt.empty()) {
        if (o.cameraPos.size() != 3 || o.lookAt.size() != 3) throw Error("--camera-pos and --look-at go together, X,Y,Z each");
        if (!o.camera.empty()) throw Error("--camera and --camera-pos exclude each other");
        r.hasPosition = true;
        r.position = glm::vec3(o.cameraPos[0], o.cameraPos[1], o.cameraPos[2]);
        r.lookAt = glm::vec3(o.lookAt[0], o.lookAt[1], o.lookAt[2]);
        r.fovDegrees = o.fov;
        if (!std::isfinite(glm::length(r.position)) || !std::isfinite(glm::length(r.lookAt)))
            throw Error("--camera-pos and --look-at must be finite");
        return r;
    }
    if (o.camera == "auto") {
        r.autoFrame = true;
    } else if (!o.camera.empty()) {
        char* end = nullptr;
        const long index = std::strtol(o.camera.c_str(), &end, 10);
        if (*end != '\0' || index < 0 || index > 1000000)
            throw Error("--camera '" + o.camera + "' is not a camera index (0, 1, ...) or auto");
        r.index = int(index);
    }
    return r;
}

int prepareScene(Scene& scene, const SceneSetupOptions& o, float aspect, RenderSettings* settings, bool ambientGiven) {
    if (settings && !o.emitters.empty()) setParam(*settings, "emitters.mode", o.emitters);
    const LightingMode mode =
        lightingUnderEnvironment(parseLightingMode(o.lighting), settings && !settings->environment.empty());
    // Measured before: applyLighting keeps the emission but the reason belongs in the line.
    const double emitted = mode == LightingMode::Auto ? meanEmittedRadiance(scene) : 0.0;
    if (applyLighting(scene, mode)) {
        char why[200] = "the scene has no light";
        if (mode == LightingMode::Default) std::snprintf(why, sizeof why, "--lighting default");
        else if (emitted > 0.0)
            std::snprintf(why, sizeof why,
                          "the scene's emission is a surface detail, not a light (mean emitted radiance %.3g over its "
                          "surfaces, below %g; --emitters lights makes it one)", emitted, kEmitterLightingFloor);
        std::fprintf(stderr,
                     "gisandbox: %s: added the default sun (irradiance %g, elevation %g deg, azimuth %g deg) and sky "
                     "(radiance %g); --lighting scene renders without them\n",
                     why, kDefaultSunIrradiance, kDefaultSunElevationDegrees, kDefaultSunAzimuthDegrees, kDefaultSkyRadiance);
        if (settings && !ambientGiven) settings->ambient = glm::vec3(kDefaultSkyRadiance);
    } else if (mode == LightingMode::Auto && scene.lights.empty() && emitted > 0.0) {
        // Only emission lights it: say so, since a model whose emission is a detail (labels, screens)
        // then renders dark where a user expected the default sky.
        std::fprintf(stderr,
                     "gisandbox: the scene is lit by its emission alone (mean emitted radiance %.3g over its surfaces, "
                     "at least %g); --lighting default adds a sun and sky\n",
                     emitted, kEmitterLightingFloor);
    }
    return resolveCamera(scene, cameraRequest(o), aspect);
}

}  // namespace gis
