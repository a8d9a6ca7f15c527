// Deferred lighting: punctual lights with shadows, emission and the constant ambient baseline,
// into a linear RGBA16F (or 32F) radiance target.
#pragma once

#include "renderer.h"

namespace gis {

class LightingPass final : public Pass {
public:
    // useAo: multiply the ambient term by the "ao" texture another pass (SSAO) wrote.
    LightingPass(int width, int height, int lightCount, bool hdr32, bool useAo, gl::MemoryLedger& ledger);
    const char* name() const override { return "lighting"; }
    std::vector<std::string> inputs() const override {
        std::vector<std::string> in{"gbuffer.depth", "gbuffer.baseColor", "gbuffer.normal", "gbuffer.material",
                                    "gbuffer.emissive", "lights", "shadow.maps", "shadow.cubes"};
        if (useAo_) in.push_back("ao");
        return in;
    }
    std::vector<std::string> outputs() const override { return {"radiance"}; }
    void execute(Frame& frame) override;
    static std::vector<ProgramDesc> programs();

private:
    gl::Texture radiance_, noAo_;
    gl::Object fbo_, program_, vao_;
    int lightCount_;
    bool useAo_;
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
