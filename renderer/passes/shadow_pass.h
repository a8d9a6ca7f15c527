// Shadow maps for every punctual light, sized by what the scene holds: one 2D array layer per
// directional/spot light (directional fitted to the scene bounds, spot perspective over its cone),
// one cube per point light. View-independent: the maps are rendered once and reused until the
// lights or the geometry change (a camera move keeps them). Outputs the light list (with shadow
// matrices) for the lighting pass.
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
    bool settled() const override { return valid_; }
    void invalidate(Changes changes) override;
    static std::vector<ProgramDesc> programs();
    const std::vector<GpuLight>& lights() const { return lights_; }

private:
    struct View { glm::mat4 viewProj; int layer; bool cube; };
    void layoutLights();  // light list, shadow views and maps for the scene's current lights
    const GpuScene& scene_;
    gl::MemoryLedger& ledger_;
    std::vector<GpuLight> lights_;
    std::vector<View> views_;          // one per 2D layer or cube face
    gl::Buffer lightBuffer_;
    gl::Texture maps_, cubes_;         // 1-layer placeholders when the scene needs none
    gl::Texture cubeFaces_;            // cubes_ seen as a 2D array of faces: "shadow.cubes"
    gl::Object fbo_, program_;
    int mapSize_, cubeSize_;
    bool shadows_;
    bool valid_ = false, reused_ = false;
};

}  // namespace gis
