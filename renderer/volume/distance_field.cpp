#include "volume/distance_field.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "gl/dispatch.h"
#include "frame.h"
#include "gl/shader.h"
#include "scene/scene.h"
#include "volume/sdf_uniforms.h"

namespace gis {

namespace {

using namespace sdf;

constexpr int kGroup = 4;  // local size of every shaders/volume/*.comp, per axis

GLuint groups(int n) { return GLuint((n + kGroup - 1) / kGroup); }

void dispatch(int n) { gl::dispatchCompute(groups(n), groups(n), groups(n), "distance field"); }

int coarseSize(int resolution) { return (resolution + kSdfCoarseFactor - 1) / kSdfCoarseFactor; }

// A timed step when the caller gave timers (the pass's frame.step), nothing otherwise.
std::optional<StepTimers::Scope> timed(StepTimers* timers, const std::string& step) {
    if (!timers) return std::nullopt;
    return timers->scope(step);
}

void setSampling(const gl::Texture& t, GLenum filter) {
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, filter);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(t.id(), wrap, GL_CLAMP_TO_EDGE);
}

}  // namespace

JfaVariant parseJfaVariant(const std::string& s) {
    if (s == "plain") return JfaVariant::Plain;
    if (s == "1+jfa") return JfaVariant::OnePlusJfa;
    if (s == "jfa+2") return JfaVariant::JfaPlusTwo;
    throw Error("unknown JFA variant '" + s + "' (plain, 1+jfa, jfa+2)");
}

const char* jfaVariantName(JfaVariant v) {
    switch (v) {
        case JfaVariant::Plain: return "plain";
        case JfaVariant::OnePlusJfa: return "1+jfa";
        case JfaVariant::JfaPlusTwo: return "jfa+2";
    }
    return "plain";
}

std::vector<int> jfaSteps(int resolution, JfaVariant v) {
    int n = 1;
    while (n < resolution) n *= 2;
    std::vector<int> steps;
    // 1+JFA: a step-1 pass first spreads every seed to its neighbours, so clusters of close seeds
    // compete before the long jumps carry them (Rong & Tan 2007).
    if (v == JfaVariant::OnePlusJfa) steps.push_back(1);
    for (int k = n / 2; k >= 1; k /= 2) steps.push_back(k);
    // JFA+2: two more passes with jumps 2 and 1 repair most cells the long jumps got wrong.
    if (v == JfaVariant::JfaPlusTwo) steps.insert(steps.end(), {2, 1});
    if (steps.empty()) steps.push_back(1);  // a single cell: one pass keeps it well defined
    return steps;
}

int64_t distanceFieldBytes(int resolution, int layers) {
    const int64_t n = resolution, c = coarseSize(resolution);
    return 4 * (n * n * n + c * c * c) * layers;
}

int64_t distanceFieldBuildBytes(int resolution, int layers) {
    const int64_t n = resolution;
    return distanceFieldBytes(resolution, layers) + 2 * 4 * n * n * n;  // layers are built one at a time
}

namespace {
void checkVolume(const SdfVolume& volume) {
    const int n = volume.resolution;
    if (n < 1 || n > kSdfMaxResolution)
        throw Error("distance field resolution " + std::to_string(n) + " is out of range [1, " +
                    std::to_string(kSdfMaxResolution) + "]");
    if (!(volume.size > 0.0f) || !std::isfinite(volume.size))
        throw Error("distance field volume has no size");
}
}  // namespace

DistanceField::DistanceField(const SdfVolume& volume, const gl::MemoryScope& scope, int layers) : scope_(scope) {
    checkVolume(volume);
    if (layers < 1 || layers > 64) throw Error("distance field layers " + std::to_string(layers) + " out of range [1, 64]");
    volumes_.assign(size_t(layers), volume);
    const int n = volume.resolution;
    distance_ = gl::createTexture3D(scope, GL_R32F, n, n, n * layers);
    setSampling(distance_, GL_LINEAR);
    const int c = coarseSize(n);
    coarse_ = gl::createTexture3D(scope, GL_R32F, c, c, c * layers);
    setSampling(coarse_, GL_NEAREST);
    seedProgram_ = buildProgram({"sdf_seed", {"volume/jfa_seed.comp"}, {}});
    stepProgram_ = buildProgram({"sdf_jfa", {"volume/jfa_step.comp"}, {}});
    resolveProgram_ = buildProgram({"sdf_resolve", {"volume/sdf_resolve.comp"}, {}});
    coarseProgram_ = buildProgram({"sdf_coarse", {"volume/sdf_coarse.comp"}, {}});
}

std::vector<ProgramDesc> DistanceField::programs() {
    return {{"sdf_seed", {"volume/jfa_seed.comp"}, {}},
            {"sdf_jfa", {"volume/jfa_step.comp"}, {}},
            {"sdf_resolve", {"volume/sdf_resolve.comp"}, {}},
            {"sdf_coarse", {"volume/sdf_coarse.comp"}, {}}};
}

void DistanceField::setVolume(int layer, const SdfVolume& volume) {
    checkVolume(volume);
    if (volume.resolution != volumes_.at(size_t(layer)).resolution)
        throw Error("distance field layer: resolution differs from the field's");
    volumes_[size_t(layer)] = volume;
}

void DistanceField::build(const SdfSeeds& seeds, JfaVariant variant, StepTimers* timers, int layer,
                          const std::string& prefix) {
    const SdfVolume& volume = volumes_.at(size_t(layer));
    const int n = volume.resolution;
    // Transient: two nearest-seed images, released when the field is resolved.
    gl::Texture ping = gl::createTexture3D(scope_, GL_R32UI, n, n, n);
    gl::Texture pong = gl::createTexture3D(scope_, GL_R32UI, n, n, n);
    {
        auto t = timed(timers, prefix + "seed");
        glUseProgram(seedProgram_.id());
        glProgramUniform1i(seedProgram_.id(), US_RESOLUTION, n);
        glBindTextureUnit(TF_SEED_OCCUPANCY, seeds.occupancy);
        glBindImageTexture(IF_SEED_SEEDS, ping.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
        dispatch(n);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glUseProgram(stepProgram_.id());
    glProgramUniform1i(stepProgram_.id(), US_RESOLUTION, n);
    const std::vector<int> steps = jfaSteps(n, variant);
    for (size_t k = 0; k < steps.size(); ++k) {
        // One timed step per pass ("jfa.1.32" ... "jfa.6.1"): every pass reads 27 cells per cell,
        // whatever its jump, so they should cost the same; the rows show whether the long jumps
        // (scattered reads) cost more in practice.
        auto t = timed(timers, prefix + "jfa." + std::to_string(k + 1) + "." + std::to_string(steps[k]));
        glProgramUniform1i(stepProgram_.id(), US_JFA_STEP, steps[k]);
        glBindImageTexture(IF_STEP_SOURCE, ping.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(IF_STEP_TARGET, pong.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
        dispatch(n);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        std::swap(ping, pong);  // the result is always in `ping`
    }
    {
        auto t = timed(timers, prefix + "resolve");
        const GLuint p = resolveProgram_.id();
        glUseProgram(p);
        glProgramUniform1i(p, US_RESOLUTION, n);
        glProgramUniform1i(p, US_LAYER, layer);
        glProgramUniform1f(p, US_CELL_SIZE, volume.cellSize());
        glProgramUniform1f(p, US_FAR, volume.farValue());
        glProgramUniform1i(p, US_HAS_NORMALS, seeds.normals ? 1 : 0);
        glBindTextureUnit(TF_RESOLVE_NORMALS, seeds.normals);
        glBindImageTexture(IF_RESOLVE_SEEDS, ping.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(IF_RESOLVE_DISTANCE, distance_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        dispatch(n);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        buildCoarse(layer);
    }
    for (int unit : {IF_STEP_SOURCE, IF_STEP_TARGET}) glBindImageTexture(GLuint(unit), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
}

void DistanceField::buildCoarse(int layer) {
    const SdfVolume& volume = volumes_.at(size_t(layer));
    const GLuint p = coarseProgram_.id();
    glUseProgram(p);
    glProgramUniform1i(p, US_RESOLUTION, volume.resolution);
    glProgramUniform1i(p, US_LAYER, layer);
    glProgramUniform1f(p, US_CELL_SIZE, volume.cellSize());
    glProgramUniform1i(p, US_COARSE_FACTOR, kSdfCoarseFactor);
    glBindTextureUnit(TF_COARSE_DISTANCE, distance_.id());
    glBindImageTexture(IF_COARSE_TARGET, coarse_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
    dispatch(coarse_.width);  // one layer: the coarse texture is width^3 per layer
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void DistanceField::upload(const std::vector<float>& distances, int layer) {
    const int n = volume(layer).resolution;
    if (distances.size() != size_t(n) * n * n) throw Error("distance field upload: wrong number of cells");
    glTextureSubImage3D(distance_.id(), 0, 0, 0, layer * n, n, n, n, GL_RED, GL_FLOAT, distances.data());
    buildCoarse(layer);
}

std::vector<float> DistanceField::readBack(int layer) const {
    const int n = volume(layer).resolution;
    std::vector<float> out(size_t(n) * n * n);
    glGetTextureSubImage(distance_.id(), 0, 0, 0, layer * n, n, n, n, GL_RED, GL_FLOAT,
                         GLsizei(out.size() * sizeof(float)), out.data());
    return out;
}

void DistanceField::bind(GLuint unit) const {
    glBindTextureUnit(unit, distance_.id());
    glBindTextureUnit(unit + 1, coarse_.id());
}

}  // namespace gis
