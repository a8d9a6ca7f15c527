// Shadow maps for every punctual light, sized by what the scene holds: one 2D array layer per spot
// light (perspective over its cone), one cube per point light, and two layers per directional
// light: one fitted to the scene's bounds, which every lookup may use (the volume's light
// injection, the tracers' hits), and one fitted to the part of the camera's view near it, which
// the lighting pass prefers where it reaches (a building's sun patches are sharp at building
// scale, where one map over the scene has texels a large share of a window). The scene's maps are
// rendered once and reused until the lights or the geometry change; the camera's map follows the
// camera, on a grid of its own texels, so a still view renders nothing. Outputs the light list
// (with shadow matrices) for the lighting pass.
#pragma once

#include <glm/glm.hpp>

#include "lights.h"
#include "frame.h"
#include "gl/shader.h"

namespace gis {

class ShadowPass final : public Pass {
public:
    // `lit`: false when the frame draws no light of its own (a bake holds it): no maps are made.
    ShadowPass(const GpuScene& scene, const RenderSettings& settings, bool lit, gl::MemoryLedger& ledger);
    const char* name() const override { return "shadows"; }
    std::vector<std::string> outputs() const override { return {resource::kLights, resource::kShadowMaps, resource::kShadowCubes}; }
    void execute(Frame& frame) override;
    bool reusedLastFrame() const override { return reused_; }
    bool settled() const override { return valid_ && !fitPending_; }
    void invalidate(Changes changes) override;
    static std::vector<ProgramDesc> programs();
    const std::vector<GpuLight>& lights() const { return lights_; }

private:
    struct View { glm::mat4 viewProj; int layer; bool cube; };
    // A directional light's map around the camera: its light and layer, the light's view, the
    // scene map's light-space box (x, y; z as near and far) it is a part of, the scene's diameter.
    struct CameraMap {
        size_t light;
        int layer;
        glm::mat4 lightView;
        glm::vec2 lo, hi;
        float zNear, zFar, sceneDiameter;
    };
    void layoutLights();  // light list, shadow views and maps for the scene's current lights
    // Fits each camera map to `camera`, writes the light's viewCascade, and adds to `render` the
    // maps whose fit changed (every one when `all`).
    void fitCameraMaps(const CameraMatrices& camera, bool all, std::vector<View>& render);
    void renderViews(const std::vector<View>& views);
    const GpuScene& scene_;
    gl::MemoryLedger& ledger_;
    std::vector<GpuLight> lights_;
    std::vector<View> views_;          // one per 2D layer or cube face, fitted to the scene
    std::vector<CameraMap> cameraMaps_;
    gl::Buffer lightBuffer_;
    gl::Texture maps_, cubes_;         // 1-layer placeholders when the scene needs none
    gl::Texture cubeFaces_;            // cubes_ seen as a 2D array of faces: "shadow.cubes"
    gl::Object fbo_, program_;
    int mapSize_, cubeSize_;
    bool shadows_;
    bool valid_ = false, reused_ = false;
    bool fitPending_ = false;  // the camera moved: the camera maps are fitted again
};

}  // namespace gis
