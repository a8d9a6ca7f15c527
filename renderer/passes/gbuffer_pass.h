// G-buffer: depth plus four colour targets (base colour, normal, material, emission).
#pragma once

#include <map>

#include "renderer.h"

namespace gis {

class GBufferPass final : public Pass {
public:
    GBufferPass(int width, int height, gl::MemoryLedger& ledger);
    const char* name() const override { return "gbuffer"; }
    std::vector<std::string> outputs() const override {
        return {resource::kGbufferDepth, resource::kGbufferBaseColor, resource::kGbufferNormal, resource::kGbufferMaterial, resource::kGbufferEmissive};
    }
    void execute(Frame& frame) override;
    // Rasterised from the camera, the geometry and the materials (their textures and overrides).
    void invalidate(Changes c) override {
        if (c & (ChangeCamera | ChangeGeometry | ChangeMaterials | ChangeBrdfModels)) stale_ = true;
    }
    bool settled() const override { return !stale_; }
    std::vector<DebugViewDesc> debugViews() const override { return views(); }
    // The G-buffer views, also listed for methods that build a G-buffer only when one is asked for.
    static std::vector<DebugViewDesc> views();
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();

private:
    GLuint programFor(const GpuMaterial& material);  // the program for the material's textures

    gl::Texture depth_, baseColor_, normal_, material_, emissive_;
    gl::Object fbo_;
    std::map<unsigned, gl::Object> programs_;  // by GpuMaterial::textures, built on first need
    bool stale_ = true;  // a change since the last execute()
};

}  // namespace gis
