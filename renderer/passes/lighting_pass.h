// Deferred lighting: punctual lights with shadows, emission, and the indirect light a GI method
// gives under the lighting contract, into a linear RGBA16F (or 32F) radiance target.
//
// The lighting contract: a method's passes may output, before this pass runs,
//   "indirect.diffuse"   RGB: the cosine-weighted mean incoming radiance, E / pi (multiplied by the
//                        diffuse colour);
//   "indirect.specular"  RGB: radiance pre-integrated over the specular lobe (multiplied by the
//                        split-sum directional albedo from F0, F90, roughness and N.V);
//   "ao"                 R: occlusion of the indirect/ambient term.
// and the emitter-light module (renderer/emitters/) "emitters.direct", RGB direct radiance from
// emissive triangles, added as it is.
// Any that is missing falls back to the constant ambient (or to 1 for "ao"). No method edits this
// pass or lighting.frag.
//
// Its debug views are the terms of what it outputs, each drawn by the same shader with one term
// kept: "direct", "indirect.diffuse", "indirect.specular" and "emission" are radiance
// contributions that add up to "radiance" (before tone mapping), "ao" the occlusion the indirect
// terms were multiplied by.
#pragma once

#include <map>
#include <set>

#include "frame.h"
#include "gl/shader.h"

namespace gis {

class LightingPass final : public Pass {
public:
    // The contract's terms the method passes before this one produce, by name. `lit`: false when a
    // method's bake holds the lights' direct light (GiMethod::bakesDirectLight): no light is drawn.
    LightingPass(int width, int height, bool hdr32, const std::set<std::string>& produced, bool lit,
                 gl::MemoryLedger& ledger);
    const char* name() const override { return "lighting"; }
    std::vector<std::string> inputs() const override;
    std::vector<std::string> outputs() const override { return {resource::kRadiance}; }
    void execute(Frame& frame) override;
    // Every kind of change alters the lit image (camera position, lights, BRDFs, ambient ...); the
    // renderer re-runs it too when an input was re-produced (ReSTIR accumulating, a GI pass).
    void invalidate(Changes) override { stale_ = true; }
    bool settled() const override { return !stale_; }
    std::vector<DebugViewDesc> debugViews() const override;
    void drawDebugView(const std::string& view, const Frame& frame, GLuint target) override;
    static std::vector<ProgramDesc> programs();
    // The names of the term views ("direct", "indirect.diffuse" ...), for callers without a pass.
    static std::vector<std::string> termViewNames();

private:
    // The variant the frame needs (LightingVariant), outputting the term view `term` names (an
    // index into the term views) or, for -1, the lit sum.
    GLuint programFor(const Frame& frame, int term);
    void draw(const Frame& frame, GLuint program, GLuint fbo, float maxRadiance);
    bool stale_ = true;

    gl::Texture radiance_, unit_;   // unit_: a 1x1 stand-in (ao = 1) for terms no method gives
    gl::Object fbo_, viewFbo_, vao_;  // viewFbo_: a term view's target
    std::map<std::string, gl::Object> programs_;  // by variant name, built on first need
    bool hasAo_, hasDiffuse_, hasSpecular_, hasEmitters_, lit_;
};

class TonemapPass final : public Pass {
public:
    TonemapPass(int width, int height, gl::MemoryLedger& ledger);
    const char* name() const override { return "tonemap"; }
    std::vector<std::string> inputs() const override { return {resource::kRadiance}; }
    std::vector<std::string> outputs() const override { return {resource::kDisplay}; }
    void execute(Frame& frame) override;
    // Exposure and tone mapper are live parameters; the radiance is an input.
    void invalidate(Changes c) override {
        if (c & ChangeLiveParams) stale_ = true;
    }
    bool settled() const override { return !stale_; }
    static std::vector<ProgramDesc> programs();

private:
    bool stale_ = true;
    gl::Texture display_;
    gl::Object fbo_, program_, vao_;
};

}  // namespace gis
