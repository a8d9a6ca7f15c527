// The environment on the GPU: the radiance of every ray that leaves the scene, one module that
// every method reads through shaders/environment.glsl. Either a constant (--background, or the
// scene's own sky: the map of one value, which needs no texture) or an equirectangular map
// (--environment FILE.hdr) with what its readers need:
//   - the radiance with a box-filtered mip chain (cones and wide rays read a level whose texel
//     covers their solid angle);
//   - its 9-coefficient SH projection (the rasterized baseline's diffuse irradiance, Ramamoorthi
//     and Hanrahan 2001);
//   - a GGX-prefiltered chain for the split-sum specular (Karis 2013, "Real Shading in Unreal
//     Engine 4"), one roughness per level;
//   - the split sum's BRDF table for brdf.glsl's GGX (shaders/environment_brdf.glsl);
//   - the marginal and conditional CDFs the path tracer importance-samples it with (PBRT 3rd ed.
//     13.6.7, 14.2.4), as textures.
// bind() puts all of it at fixed units and one uniform block, the same for every program, so a
// pass that reads the environment calls bind() and sets nothing else.
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "environment.h"
#include "gl/gl.h"
#include "gl/shader.h"

namespace gis {

// Where the environment lives in every program (GLSL's ENV_* defines, shader_constants.cpp):
// units and a uniform-block binding no pass uses for anything else.
constexpr int kEnvironmentBlockBinding = 11;
constexpr int kEnvironmentBrdfUnit = 11;
constexpr int kEnvironmentRadianceUnit = 12;
constexpr int kEnvironmentSpecularUnit = 13;
constexpr int kEnvironmentMarginalUnit = 14;
constexpr int kEnvironmentConditionalUnit = 15;
static_assert(kEnvironmentRadianceUnit == kEnvironmentBrdfUnit + 1 && kEnvironmentSpecularUnit == kEnvironmentRadianceUnit + 1 && kEnvironmentMarginalUnit == kEnvironmentRadianceUnit + 2 &&
                  kEnvironmentConditionalUnit == kEnvironmentRadianceUnit + 3,
              "bind() clears the five units' samplers as one range");
// Roughness levels of the prefiltered specular chain: level i holds roughness i / (levels - 1).
constexpr int kEnvironmentSpecularLevels = 6;
// The split-sum table's texels along N.V and along roughness.
constexpr int kEnvironmentBrdfTableSize = 32;

class GpuEnvironment {
public:
    // path empty: a constant environment (bind()'s radiance). Otherwise loads the map (one-line
    // gis::Error for a missing, truncated or non-Radiance file) and builds its textures.
    GpuEnvironment(const std::string& path, gl::MemoryLedger& ledger);
    ~GpuEnvironment();
    GpuEnvironment(const GpuEnvironment&) = delete;
    GpuEnvironment& operator=(const GpuEnvironment&) = delete;

    bool isMap() const { return map_ != nullptr; }
    const std::string& path() const { return path_; }
    // The map as loaded (isMap() only): tests compare against its CPU SH projection.
    const EnvironmentMap& map() const { return *map_; }
    const Sh9& sh() const { return sh_; }
    // Binds the block and the textures; `constant` is the radiance of a constant environment
    // (ignored for a map).
    void bind(glm::vec3 constant);

    static std::vector<ProgramDesc> programs();

private:
    void upload(gl::MemoryScope scope);
    void prefilterSpecular();
    void buildBrdfTable();

    std::string path_;
    std::unique_ptr<EnvironmentMap> map_;
    Sh9 sh_{};
    float total_ = 0.0f;
    gl::Texture radiance_, specular_, marginal_, conditional_, brdf_;
    gl::Buffer block_;
    glm::vec3 uploadedConstant_{-1.0f};
};

}  // namespace gis
