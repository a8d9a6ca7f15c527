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

#include <string>

#include <glm/glm.hpp>

#include "environment.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "gl/uniform_block.h"

namespace gis {

// What every program reads of the environment (shaders/environment.glsl's u_env).
#define GIS_ENVIRONMENT_BLOCK(M, A) \
    M(vec4, constant)          /* rgb: a constant environment's radiance */ \
    M(int, width)              /* a map's texels */ \
    M(int, height) \
    M(int, isMap)              /* 0: the constant above is the environment */ \
    M(float, cdfTotal)         /* the sampling CDFs' total weight */ \
    M(float, texelSteradians)  /* the mean solid angle of a level-0 texel */ \
    M(float, rotation)         /* radians the map is turned about +Y (environmentToMap in environment.h) */ \
    M(int, light)              /* 1: a light of the direct pass (emitters.environment): GI rays miss into black */ \
    A(vec4, sh, 9)             /* rgb: the radiance's SH9 projection (environment.h's basis order) */
GIS_UNIFORM_BLOCK(EnvironmentBlock, 11, GIS_ENVIRONMENT_BLOCK)

// The texture units the environment holds in every program (GLSL's ENV_*_UNIT defines,
// shader_constants.cpp), five consecutive ones no pass uses for anything else: bind() clears their
// samplers as one range.
constexpr int kEnvironmentBrdfUnit = 11;
constexpr int kEnvironmentRadianceUnit = kEnvironmentBrdfUnit + 1;
constexpr int kEnvironmentSpecularUnit = kEnvironmentBrdfUnit + 2;
constexpr int kEnvironmentMarginalUnit = kEnvironmentBrdfUnit + 3;
constexpr int kEnvironmentConditionalUnit = kEnvironmentBrdfUnit + 4;
constexpr int kEnvironmentUnits = 5;
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

    // Binds the block and the textures; `constant` is the radiance of a constant environment
    // (ignored for a map), `rotationDegrees` turns a map about +Y (RenderSettings::environmentRotation).
    // The textures stay in the map's frame, so a rotation needs no rebuild: the prefiltered chain
    // is a lobe symmetric about each texel's direction, and the CDFs' pdf is per steradian.
    // `directLight`: the environment is a light of the direct pass (environmentIsLight), so the GI
    // methods' rays that leave the scene see black (environment.glsl's environmentMiss*).
    void bind(glm::vec3 constant, float rotationDegrees, bool directLight);

    static std::vector<ProgramDesc> programs();
    // GPU bytes a width x height map's textures take (the memory budget's estimate, before loading),
    // and the split-sum table every environment holds.
    static int64_t mapBytes(int width, int height);
    // The memory estimate's part for an environment map: a refusal it leads advises a smaller map.
    static constexpr const char* kMemoryPart = "environment map textures (radiance, specular chain, sampling CDFs)";
    static int64_t tableBytes();

private:
    void uploadConstant(gl::MemoryScope scope);
    void upload(gl::MemoryScope scope, const EnvironmentMap& map);
    void prefilterSpecular();
    void buildBrdfTable();

    gl::Texture radiance_, specular_, marginal_, conditional_, brdf_;
    EnvironmentBlock values_;
    gl::UniformBuffer<EnvironmentBlock> block_;
};

}  // namespace gis
