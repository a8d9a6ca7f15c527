// The flags that say how a scene is lit and seen, shared by render, bench and view:
// --lighting auto|scene|default|none, --camera N|auto, --camera-pos X,Y,Z --look-at X,Y,Z --fov DEG.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "renderer.h"

namespace CLI { class App; }

namespace gis {

struct SceneSetupOptions {
    std::string lighting = "auto";
    std::string camera;                     // "" (the file's first, else auto), N or "auto"
    std::vector<float> cameraPos, lookAt;
    float fov = 40.0f;
    std::string emitters;                   // "" (emitters.mode's default, auto), auto, lights, gi or off
};

void addSceneSetupOptions(CLI::App& cmd, SceneSetupOptions& o);
// Validates the flags (one message each) into a camera request and a lighting mode.
CameraRequest cameraRequest(const SceneSetupOptions& o);
// Applies lighting and camera to a loaded scene; returns the camera index to render from. When the
// default sun and sky are added it says so on stderr once, and, unless the user set --ambient,
// makes the constant ambient the sky's radiance, so every method sees the same sky. --emitters
// sets emitters.mode in `settings`.
int prepareScene(Scene& scene, const SceneSetupOptions& o, float aspect, RenderSettings* settings, bool ambientGiven);

}  // namespace gis
