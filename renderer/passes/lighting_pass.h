// Deferred lighting: punctual lights with shadows, emission and the constant ambient baseline,
// into a linear RGBA16F (or 32F) radiance target.
#pragma once

#include "renderer.h"

namespace gis {

class LightingPass final : public Pass {
public:
    LightingPass(int width, int height, int lightCount, bool hdr32, gl::MemoryLedger& ledger);
    const char* name() const override { return "lighting"; }
    std::vector<std::string> inputs() const override {
        return {"gbuffer.depth", "gbuffer.baseColor", "gbuffer.normal", "gbuffer.material", "gbuffer.emissive",
                "lights", "shadow.maps", "shadow.cubes"};
    }
    std::vector<std::string> outputs() const override { return {"radiance"}; }
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();

private:
    gl::Texture radiance_;
    gl::Object fbo_, program_, vao_;
    int lightCount_;
};

class TonemapPass final : public Pass {
public:
    TonemapPass(int width, int height, gl::MemoryLedger& ledger);
    const char* name() const override { return "tonemap"; }
    std::vector<std::string> inputs() const override { return {"radiance"}; }
    std::vector<std::string> outputs() const override { return {"display"}; }
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();

private:
    gl::Texture display_;
    gl::Object fbo_, program_, vao_;
};

}  // namespace gis
