#include "environment_gpu.h"

#include <algorithm>
#include <cmath>

#include "gl/dispatch.h"
#include "gl/gpu_budget.h"
#include "emitter_settings.h"
#include "error.h"
#include "frame.h"
#include "uniforms.h"

namespace gis {

namespace {


const ProgramDesc kPrefilterProgram{"environment_prefilter", {"environment_prefilter.comp"}, {}};
const ProgramDesc kBrdfTableProgram{"environment_brdf_lut", {"environment_brdf_lut.comp"}, {}};
constexpr GLenum kFormat = GL_RGBA32F;
// Prefiltered levels are no wider than this: a rough lobe needs no more, and a large map would
// otherwise cost seconds of GGX samples per texel at build time.
constexpr int kSpecularMaxWidth = 256;
constexpr int kPrefilterGroup = 8;  // environment_prefilter.comp's local size

void setLinearMipmapped(GLuint texture) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    // Azimuth wraps around; the poles do not.
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void setNearest(GLuint texture) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

// A width x height map's textures: every size upload() allocates, so mapBytes() counts the same.
struct MapTextures {
    int width, height;                // the radiance, with a full mip chain
    int specularWidth, specularHeight, specularLevels;
};

MapTextures mapTextures(int width, int height) {
    const int sw = std::min(width, kSpecularMaxWidth), sh = std::max(1, sw * height / width);
    return {width, height, sw, sh, std::min(kEnvironmentSpecularLevels, gl::mipLevelsFor(sw, sh))};
}

// The sampling CDFs are the widest textures of a map: (width + 1) x height and (height + 1) x 1. Past
// GL_MAX_TEXTURE_SIZE glTextureStorage2D fails with GL_INVALID_VALUE and every method saw a black sky.
void checkTextureLimit(const EnvironmentMap& map) {
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
    if (map.width + 1 > limit || map.height + 1 > limit)
        throw Error("environment map '" + map.name + "' is " + std::to_string(map.width) + "x" +
                    std::to_string(map.height) + ": this GPU's textures are at most " + std::to_string(limit) +
                    " texels a side (GL_MAX_TEXTURE_SIZE), and the map's sampling tables need one more than its "
                    "width and height; use a smaller map");
}

gl::Texture floatTexture(const gl::MemoryScope& scope, int width, int height, const float* data) {
    gl::Texture t = gl::createTexture2D(scope, GL_R32F, width, height);
    glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, data);
    setNearest(t.id());
    return t;
}

// The map's textures alone against the budget, once the map is loaded: the file may have changed
// since checkMemoryBudget read its header.
void checkMapBudget(const std::string& name, int width, int height) {
    const uint64_t need = uint64_t(GpuEnvironment::mapBytes(width, height));
    const MemoryBudget b = gpuMemoryBudget();
    if (need > b.bytes)
        throw Error("environment map '" + name + "' is " + std::to_string(width) + "x" + std::to_string(height) + ": its " +
                    GpuEnvironment::kMemoryPart + " need about " + bytesText(need) + ", more than the " + bytesText(b.bytes) +
                    " budget: " + b.source + "; use a smaller environment map");
}

}  // namespace

std::vector<ProgramDesc> GpuEnvironment::programs() { return {kPrefilterProgram, kBrdfTableProgram}; }

GpuEnvironment::GpuEnvironment(const std::string& path, gl::MemoryLedger& ledger)
    : block_(gl::MemoryScope{&ledger, "environment"}) {
    const gl::MemoryScope scope{&ledger, "environment"};
    // The split sum's table for either kind: a constant is a uniform map, whose specular is its
    // radiance times the table's directional albedo as a map's is.
    brdf_ = gl::createTexture2D(scope, GL_RG32F, kEnvironmentBrdfTableSize, kEnvironmentBrdfTableSize);
    glTextureParameteri(brdf_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(brdf_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(brdf_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(brdf_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    buildBrdfTable();
    if (path.empty()) {
        uploadConstant(scope);
        return;
    }
    // The map itself is needed only here: what the shaders read of it is in the textures and values_.
    const EnvironmentMap map = loadEnvironmentMap(path);
    // The memory pre-check read the file before this load: an edit in between is caught here.
    checkMapBudget(map.name, map.width, map.height);
    checkTextureLimit(map);
    upload(scope, map);
    const Sh9 sh = projectSh9(map);
    values_.width = map.width;
    values_.height = map.height;
    values_.isMap = 1;
    values_.texelSteradians = 4.0f * 3.14159265f / float(map.width * map.height);
    for (int k = 0; k < 9; ++k) values_.sh[k] = glm::vec4(sh[size_t(k)], 0.0f);
    prefilterSpecular();
}

GpuEnvironment::~GpuEnvironment() = default;

int64_t GpuEnvironment::tableBytes() {
    return gl::texture2DBytes(GL_RG32F, kEnvironmentBrdfTableSize, kEnvironmentBrdfTableSize);
}

int64_t GpuEnvironment::mapBytes(int width, int height) {
    const MapTextures t = mapTextures(width, height);
    return gl::texture2DBytes(kFormat, width, height, gl::mipLevelsFor(width, height)) +
           gl::texture2DBytes(kFormat, t.specularWidth, t.specularHeight, t.specularLevels) +
           gl::texture2DBytes(GL_R32F, height + 1, 1) + gl::texture2DBytes(GL_R32F, width + 1, height);
}

// A constant environment's textures are 1x1 placeholders, so every program's samplers have
// something complete bound and a map is the only difference.
void GpuEnvironment::uploadConstant(gl::MemoryScope scope) {
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (gl::Texture* t : {&radiance_, &specular_}) {
        *t = gl::createTexture2D(scope, kFormat, 1, 1);
        glTextureSubImage2D(t->id(), 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, zero);
        setNearest(t->id());
    }
    marginal_ = floatTexture(scope, 1, 1, zero);
    conditional_ = floatTexture(scope, 1, 1, zero);
}

// A map's textures: its radiance with mips, the specular chain and BRDF table (filled after), and
// the sampling CDFs.
void GpuEnvironment::upload(gl::MemoryScope scope, const EnvironmentMap& map) {
    const int w = map.width, h = map.height;
    const MapTextures t = mapTextures(w, h);
    const int levels = gl::mipLevelsFor(w, h);
    radiance_ = gl::createTexture2D(scope, kFormat, w, h, levels);
    glTextureSubImage2D(radiance_.id(), 0, 0, 0, w, h, GL_RGB, GL_FLOAT, map.texels.data());
    EnvironmentMap level;  // the mips weighted by solid angle (nextMipLevel), not GL's box filter
    for (int i = 1; i < levels; ++i) {
        level = nextMipLevel(i == 1 ? map : level);
        glTextureSubImage2D(radiance_.id(), i, 0, 0, level.width, level.height, GL_RGB, GL_FLOAT, level.texels.data());
    }
    setLinearMipmapped(radiance_.id());
    specular_ = gl::createTexture2D(scope, kFormat, t.specularWidth, t.specularHeight, t.specularLevels);
    setLinearMipmapped(specular_.id());
    const EnvironmentSampler sampler(map);
    values_.cdfTotal = sampler.marginalCdf().back();
    marginal_ = floatTexture(scope, h + 1, 1, sampler.marginalCdf().data());
    conditional_ = floatTexture(scope, w + 1, h, sampler.conditionalCdf().data());
}

// Every level of the specular chain, roughness 0 included, filtered from the radiance's mip chain
// (environment_prefilter.comp: GGX samples read at the level their pdf covers).
void GpuEnvironment::prefilterSpecular() {
    const gl::Object program = buildProgram(kPrefilterProgram);
    glUseProgram(program.id());
    block_.set(values_);
    glBindTextureUnit(kEnvironmentRadianceUnit, radiance_.id());
    glBindSampler(kEnvironmentRadianceUnit, 0);
    for (int level = 0; level < specular_.levels; ++level) {
        const int w = std::max(1, specular_.width >> level), h = std::max(1, specular_.height >> level);
        const float roughness = specular_.levels > 1 ? float(level) / float(specular_.levels - 1) : 0.0f;
        glProgramUniform1f(program.id(), U_ENV_ROUGHNESS, roughness);
        glBindImageTexture(I_ENVIRONMENT_PREFILTER_LEVEL, specular_.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, kFormat);
        gl::dispatchCompute(GLuint((w + kPrefilterGroup - 1) / kPrefilterGroup),
                        GLuint((h + kPrefilterGroup - 1) / kPrefilterGroup), 1, "environment prefilter");
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

// The split sum's BRDF table (shaders/environment_brdf.glsl), once per environment.
void GpuEnvironment::buildBrdfTable() {
    const gl::Object program = buildProgram(kBrdfTableProgram);
    glUseProgram(program.id());
    glBindImageTexture(I_ENVIRONMENT_BRDF_TABLE, brdf_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    const GLuint groups = GLuint((kEnvironmentBrdfTableSize + kPrefilterGroup - 1) / kPrefilterGroup);
    gl::dispatchCompute(groups, groups, 1, "environment BRDF table");
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GpuEnvironment::bind(glm::vec3 constant, float rotationDegrees, bool directLight) {
    if (values_.isMap == 0) values_.constant = glm::vec4(constant, 0.0f);
    values_.rotation = glm::radians(rotationDegrees);
    values_.light = directLight ? 1 : 0;
    block_.set(values_);
    glBindTextureUnit(kEnvironmentBrdfUnit, brdf_.id());
    glBindTextureUnit(kEnvironmentRadianceUnit, radiance_.id());
    glBindTextureUnit(kEnvironmentSpecularUnit, specular_.id());
    glBindTextureUnit(kEnvironmentMarginalUnit, marginal_.id());
    glBindTextureUnit(kEnvironmentConditionalUnit, conditional_.id());
    // The textures' own filtering and wrapping, whatever sampler object a unit last held.
    glBindSamplers(kEnvironmentBrdfUnit, kEnvironmentUnits, nullptr);
}

// Frame's, defined beside what it binds: the frame (below every pass) need not include the
// environment's GPU side (above the scene's uniforms and the emitter settings).
void Frame::bindEnvironment() const {
    environment->bind(background(), settings.environmentRotation, environmentIsLight(scene.cpu, settings));
}

}  // namespace gis
