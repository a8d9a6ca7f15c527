// G-buffer: depth plus four colour targets (base colour, normal, material, emission). In a scene
// with emissive surfaces the emission is antialiased: the scene is drawn a few more times, offset
// by less than a pixel, into a multisampled emission target, and the mean of all their samples
// (the box filter the Cycles references and the path tracer use) replaces the emission target. An emitter's edge
// otherwise differs from the references by up to its radiance in every pixel it crosses, whatever
// the GI does (the emitters' README: cornell_box's outline).
#pragma once

#include <map>

#include "frame.h"
#include "gl/shader.h"

namespace gis {

// Samples per pixel of the emission's antialiasing in `scene`: 0 without an emissive surface.
int emissionSamples(const Scene& scene);
// GPU bytes the antialiasing holds at width x height (the memory estimate).
int64_t emissionAntialiasingBytes(const Scene& scene, int width, int height);

class GBufferPass final : public Pass {
public:
    GBufferPass(const Scene& scene, int width, int height, gl::MemoryLedger& ledger);
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
    void drawScene(const Frame& frame, const glm::mat4& viewProj);  // every draw into the bound framebuffer
    void antialiasEmission(const Frame& frame);

    gl::Texture depth_, baseColor_, normal_, material_, emissive_;
    gl::Object fbo_;
    // The emission's antialiasing (emissionSamples() > 0): multisampled depth and emission, and
    // the program that adds their mean to emissive_.
    gl::Texture multisampleDepth_, multisampleEmissive_;
    gl::Object multisampleFbo_, resolveProgram_;
    std::map<unsigned, gl::Object> programs_;  // by GpuMaterial::textures, built on first need
    bool stale_ = true;  // a change since the last execute()
};

}  // namespace gis
