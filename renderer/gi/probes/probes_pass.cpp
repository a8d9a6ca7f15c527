#include "gi/probes/probes_pass.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "gi/method.h"
#include "gi/probes/probe_uniforms.h"
#include "gl/dispatch.h"
#include "services/scene_services.h"
#include "voxel/voxelizer.h"

namespace gis {

using namespace probes;

namespace {
constexpr int kDistanceTexels = kOctDistanceSize * kOctDistanceSize;

// The ray set's rotation for update `n`: a uniformly random rotation (Shoemake's unit quaternion
// from three uniforms), seeded by the update's number so renders are repeatable.
glm::mat3 randomRotation(int n) {
    std::mt19937 rng(0x9e3779b9u + uint32_t(n) * 7919u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float u1 = u(rng), u2 = u(rng) * 6.2831853f, u3 = u(rng) * 6.2831853f;
    const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
    return glm::mat3_cast(glm::quat(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3)));
}

int batchSize(const ProbeSettings& s, int probes) {
    return s.probesPerFrame > 0 ? std::min(s.probesPerFrame, probes) : probes;
}

// The farthest a probe ray may go, and the distance a miss records: the volume's diagonal.
float missDistance(const VolumeFit& fit) { return fit.size * 1.7320508f; }

ParamValue choiceValue(const char* name) {
    ParamValue v;
    v.text = name;
    return v;
}
}  // namespace

int64_t probeStorageBytes(const ProbeSettings& s, int probes) { return int64_t(probes) * bytesPerProbe(s.storageKind()); }
int64_t probeRayBytes(const ProbeSettings& s, int probes) { return int64_t(batchSize(s, probes)) * s.rays * 16; }

const ProgramDesc kClassifyProgram{"probe_classify", {"gi/probes/probe_classify.comp"}, {}};
const ProgramDesc kTraceProgram{"probe_trace", {"gi/probes/probe_trace.comp"}, {}};
const ProgramDesc kBlendProgram{"probe_blend", {"gi/probes/probe_blend.comp"}, {}};
const ProgramDesc kShadeProgram{"probe_shade", {"gi/probes/probe_shade.comp"}, {}};
const ProgramDesc kDebugProgram{"probe_debug", {"gi/probes/probe_debug.comp"}, {}};
const ProgramDesc kRaysProgram{"probe_rays", {"gi/probes/probe_rays.comp"}, {}};

std::vector<ProgramDesc> ProbesPass::programs() {
    std::vector<ProgramDesc> all = Voxelizer::programs();
    for (const ProgramDesc& p : VoxelRadiance::programs()) all.push_back(p);
    for (const ProgramDesc& p : DistanceField::programs()) all.push_back(p);
    for (const ProgramDesc* p : {&kClassifyProgram, &kTraceProgram, &kBlendProgram, &kShadeProgram, &kDebugProgram,
                                 &kRaysProgram})
        all.push_back(*p);
    return all;
}

namespace {
// What probes ask of the scene volume: one cube of voxels with their distance field (the rays'
// sphere tracing) and their direct light and emission (what the rays see).
VolumeRequest volumeRequest(const ProbeSettings& s) {
    VolumeRequest r;
    r.method = "probes";
    r.resolution = s.sdfResolution;
    r.resolutionKey = "probes.sdf-resolution";
    r.distanceField = true;
    return r;
}
}  // namespace

ProbesPass::ProbesPass(SceneServices& services, const RenderSettings& settings)
    : built_(probeParams().read("probes", settings.params)), maxUpdates_(built_.maxUpdates) {
    checkProbeSettings(built_);
    const gl::MemoryScope scope{&services.ledger, name()};
    grid_ = fitProbeGrid(services.bounds(), built_.spacing);
    const int count = grid_.count();
    volume_ = &services.volume(volumeRequest(built_));
    fit_ = volume_->grid().fit;
    batch_ = batchSize(built_, count);
    irradiance_ = gl::createBuffer(scope, int64_t(count) * irradianceBytesPerProbe(built_.storageKind()), nullptr);
    glClearNamedBufferData(irradiance_.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    // Distance moments start at "nothing within reach" so that, before the first update, every
    // probe counts as visible.
    const float miss = missDistance(fit_);
    std::vector<glm::vec2> far(size_t(count) * kDistanceTexels, glm::vec2(miss, miss * miss));
    distance_ = gl::createBuffer(scope, int64_t(far.size() * sizeof(glm::vec2)), far.data());
    state_ = gl::createBuffer(scope, int64_t(count) * 32, nullptr);
    glClearNamedBufferData(state_.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    rays_ = gl::createBuffer(scope, probeRayBytes(built_, count), nullptr);
    change_ = gl::createBuffer(scope, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    diffuse_ = gl::createTexture2D(scope, GL_RGBA16F, settings.width, settings.height);
    sampler_ = gl::createSampler();
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(sampler_.id(), w, GL_CLAMP_TO_EDGE);
    classifyProgram_ = buildProgram(kClassifyProgram);
    traceProgram_ = buildProgram(kTraceProgram);
    blendProgram_ = buildProgram(kBlendProgram);
    shadeProgram_ = buildProgram(kShadeProgram);
    debugProgram_ = buildProgram(kDebugProgram);
    raysProgram_ = buildProgram(kRaysProgram);
}

// The scene volume rebuilds what the change touched (a light edit relights it alone); the probes
// restart.
void ProbesPass::invalidate(Changes c) {
    if (c & (ChangeGeometry | ChangeMaterials | ChangeLights)) {
        // Restart the updates: the running mean starts over, so the new light is followed at once.
        needClassify_ = true;
        converged_ = false;
        pendingChange_ = false;
        updates_ = finished_ = 0;
    }
}

void ProbesPass::setGridUniforms(GLuint p) const {
    glProgramUniform3fv(p, UP_GRID_FIRST, 1, &grid_.first[0]);
    glProgramUniform3fv(p, UP_GRID_STEP, 1, &grid_.step[0]);
    glProgramUniform3i(p, UP_GRID_COUNTS, grid_.counts.x, grid_.counts.y, grid_.counts.z);
    glProgramUniform1i(p, UP_STORAGE, built_.storage);
}

// Only the programs that read the distance field declare these: setting a location a program
// does not have is GL_INVALID_OPERATION.
void ProbesPass::setVolumeUniforms(GLuint p) const {
    glProgramUniform4f(p, UP_VOLUME, fit_.origin.x, fit_.origin.y, fit_.origin.z, fit_.size);
    glProgramUniform1i(p, UP_SDF_RESOLUTION, fit_.resolution);
}

void ProbesPass::bindProbeBuffers() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, irradiance_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, distance_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, state_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, rays_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, change_.id());
}

void ProbesPass::classify() {
    const GLuint p = classifyProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    setVolumeUniforms(p);
    glProgramUniform1i(p, UP_MODE, built_.inside);
    volume_->field().bind(0);
    glBindSamplers(0, 2, nullptr);
    bindProbeBuffers();
    gl::dispatchCompute(gl::groupsFor(grid_.count(), 64), 1, 1, "probes: classify");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    needClassify_ = false;
    // A grid with no usable probe gives black indirect light everywhere: say so once (a read-back
    // per classification, i.e. per geometry or light change, not per frame).
    const StateCounts c = stateCounts();
    if (c.active + c.relocated == 0 && !warnedAllOff_) {
        std::fprintf(stderr,
                     "gisandbox: warning: probes: all %d probes are inside geometry and switched off "
                     "(probes.inside=%s); indirect.diffuse is black. Change probes.spacing or use "
                     "probes.inside=relocate\n",
                     grid_.count(), built_.inside == 0 ? "relocate" : "off");
        warnedAllOff_ = true;
    }
}

void ProbesPass::trace(const Frame& frame, const ProbeSettings& s, int first, int batch) {
    const GLuint p = traceProgram_.id();
    const glm::vec3 environment = frame.settings.background.value_or(frame.scene.cpu.background);
    glUseProgram(p);
    setGridUniforms(p);
    setVolumeUniforms(p);
    glProgramUniform1i(p, UP_RAYS, built_.rays);
    glProgramUniform1i(p, UP_FIRST_PROBE, first);
    glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
    glProgramUniform3fv(p, UP_ENVIRONMENT, 1, &environment[0]);
    glProgramUniform4f(p, UP_BLEND_PARAMS, s.hysteresis, s.bounces ? 1.0f : 0.0f, missDistance(fit_),
                       s.visibility ? 1.0f : 0.0f);
    glProgramUniform4f(p, UP_SHADE_PARAMS, s.normalBias, 1.0f, 0.0f, 0.0f);
    volume_->field().bind(0);
    const GLuint voxels[2] = {volume_->radianceTexture(), volume_->grid().albedo.id()};
    glBindTextures(2, 2, voxels);
    glBindSamplers(0, 2, nullptr);
    const GLuint samplers[2] = {sampler_.id(), sampler_.id()};
    glBindSamplers(2, 2, samplers);
    bindProbeBuffers();
    gl::dispatchComputeSplit(batch, [&](GLuint slot) { glProgramUniform1i(p, UP_SLOT_OFFSET, int(slot)); });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindSamplers(2, 2, nullptr);
}

void ProbesPass::blend(int mode, const ProbeSettings& s, int first, int batch) {
    const GLuint p = blendProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniform1i(p, UP_RAYS, built_.rays);
    glProgramUniform1i(p, UP_FIRST_PROBE, first);
    glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
    glProgramUniform4f(p, UP_BLEND_PARAMS, s.hysteresis, 0.0f, 0.0f, 0.0f);
    glProgramUniform1i(p, UP_MODE, mode);
    bindProbeBuffers();
    gl::dispatchComputeSplit(batch, [&](GLuint slot) { glProgramUniform1i(p, UP_SLOT_OFFSET, int(slot)); });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void ProbesPass::update(Frame& frame, const ProbeSettings& s) {
    const uint32_t zero[4] = {0, 0, 0, 0};
    glNamedBufferSubData(change_.id(), 0, 16, zero);
    rotation_ = randomRotation(updates_);
    {
        auto t = frame.step("trace");
        trace(frame, s, firstProbe_, batch_);
    }
    {
        auto t = frame.step("blend irradiance");
        blend(0, s, firstProbe_, batch_);
    }
    {
        auto t = frame.step("blend distance");
        blend(1, s, firstProbe_, batch_);
    }
    lastFirst_ = firstProbe_;
    firstProbe_ = (firstProbe_ + batch_) % grid_.count();
    ++updates_;
    pendingChange_ = true;
}

// The last update's largest change, read at the start of the next frame rather than right after
// the dispatch: by then the GPU has finished it, so the read does not stall the frame that
// submitted it, and the decision still comes before the next update would be dispatched.
void ProbesPass::finishUpdate(const ProbeSettings& s) {
    uint32_t bits = 0;
    glGetNamedBufferSubData(change_.id(), 0, 4, &bits);
    pendingChange_ = false;
    std::memcpy(&lastChange_, &bits, 4);
    if (!std::isfinite(lastChange_)) lastChange_ = 1.0f;
    cycleChange_ = std::max(cycleChange_, lastChange_);
    ++finished_;
    const int batchesPerCycle = (grid_.count() + batch_ - 1) / batch_;
    if (finished_ % batchesPerCycle == 0) {  // every probe got one more update
        const int cycles = finished_ / batchesPerCycle;
        // Two cycles at least: the first update of a probe replaces its value and reports no change.
        if ((cycles >= 2 && cycleChange_ < s.threshold) || cycles >= s.maxUpdates) converged_ = true;
        cycleChange_ = 0.0f;
    }
}

void ProbesPass::shade(const Frame& frame, const ProbeSettings& s) {
    const GLuint p = shadeProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform4f(p, UP_SHADE_PARAMS, s.normalBias, s.intensity, s.visibility ? 1.0f : 0.0f, 0.0f);
    const GLuint gbuffer[2] = {frame.texture(resource::kGbufferDepth), frame.texture(resource::kGbufferNormal)};
    glBindTextures(4, 2, gbuffer);
    glBindSamplers(4, 2, nullptr);
    bindProbeBuffers();
    glBindImageTexture(0, diffuse_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(diffuse_.width, 8), gl::groupsFor(diffuse_.height, 8), 1, "probes");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

Pass::Progress ProbesPass::progress() const {
    const int target = maxUpdates_ * ((grid_.count() + batch_ - 1) / batch_);
    // Converged early: the target becomes the updates done, so `--timings` divides by those.
    if (converged_) return {finished_, finished_, "updates"};
    return {std::min(finished_, target - 1), target, "updates"};
}

void ProbesPass::execute(Frame& frame) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    maxUpdates_ = live.maxUpdates;
    volume_->update(frame);
    if (needClassify_) {
        classify();
        firstProbe_ = 0;
        cycleChange_ = 0.0f;
    }
    if (!converged_ && pendingChange_) finishUpdate(live);
    updatedLastFrame_ = !converged_;
    if (!converged_) update(frame, live);
    {
        auto t = frame.step("shade");
        shade(frame, live);
    }
    frame.put(resource::kIndirectDiffuse, diffuse_);
}

ProbesPass::StateCounts ProbesPass::stateCounts() const {
    std::vector<glm::vec4> state(size_t(grid_.count()) * 2);
    glGetNamedBufferSubData(state_.id(), 0, GLsizeiptr(state.size() * sizeof(glm::vec4)), state.data());
    StateCounts c;
    for (size_t i = 0; i < state.size(); i += 2) {
        const float s = state[i].w;
        (s > 1.5f ? c.off : (s > 0.5f ? c.relocated : c.active))++;
    }
    return c;
}

std::vector<glm::vec3> ProbesPass::readIrradiance(int probe) const {
    const int stride = irradianceVec4s(built_.storageKind());
    std::vector<glm::vec4> raw(static_cast<size_t>(stride));
    glGetNamedBufferSubData(irradiance_.id(), GLintptr(int64_t(probe) * stride * 16), GLsizeiptr(stride * 16), raw.data());
    std::vector<glm::vec3> out;
    for (const glm::vec4& v : raw) out.emplace_back(v);
    return out;
}

std::vector<DebugViewDesc> ProbesPass::debugViews() const {
    return {{"probes.spheres", "every probe as a sphere showing its irradiance (E/pi) towards the viewer; dark red: "
                               "switched off (inside geometry), blue rim: relocated"},
            {"probes.state", "every probe as a sphere coloured by state: green active, blue relocated, red off"},
            {"probes.rays", "the rays of probe probes.debug-probe from its last update, coloured by their radiance"}};
}

void ProbesPass::drawRays(const Frame& frame, GLuint target) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    const int count = grid_.count();
    const int probe = live.debugProbe < 0 ? probeIndexNear(grid_, grid_.position(0) + 0.5f * glm::vec3(grid_.counts - 1) * grid_.step)
                                          : std::min(live.debugProbe, count - 1);
    // The ray buffer holds the last batch only: a probe outside it has no rays to show.
    const int slot = lastFirst_ < 0 ? -1 : (probe - lastFirst_ + count) % count;
    const GLuint p = raysProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniformMatrix4fv(p, UP_VIEW_PROJ, 1, GL_FALSE, &frame.camera.viewProj[0][0]);
    glProgramUniform1i(p, UP_RAYS, built_.rays);
    glProgramUniform1i(p, UP_FIRST_PROBE, slot < batch_ ? slot : -1);
    glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
    glProgramUniform1i(p, UP_MODE, probe);
    dispatchDebugDraw(frame, target);
}

// The debug views' common end: depth and probe buffers bound, one thread per pixel into `target`.
void ProbesPass::dispatchDebugDraw(const Frame& frame, GLuint target) {
    const GLuint depth = frame.texture(resource::kGbufferDepth);
    glBindTextures(4, 1, &depth);
    glBindSamplers(4, 1, nullptr);
    bindProbeBuffers();
    glBindImageTexture(0, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(diffuse_.width, 8), gl::groupsFor(diffuse_.height, 8), 1, "probes");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void ProbesPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    if (view == "probes.rays") {
        drawRays(frame, target);
        return;
    }
    const GLuint p = debugProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniform1i(p, UP_MODE, view == "probes.state" ? 1 : 0);
    glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
    const float radius = 0.15f * std::min(grid_.step.x, std::min(grid_.step.y, grid_.step.z));
    glProgramUniform4f(p, UP_SHADE_PARAMS, 0.0f, 0.0f, 0.0f, radius);
    dispatchDebugDraw(frame, target);
}

GiMethod probesMethod() {
    GiMethod m;
    m.name = "probes";
    m.summary = "irradiance probes sphere-traced through the SDF, SH or octahedral storage, Chebyshev visibility";
    m.params = probeParams().rows;
    m.presets = {
        {"low", "SH L1, spacing 1/3, 64 rays, 32^3 field",
         {{"probes.spacing", {0.34}}, {"probes.rays", {64.0}}, {"probes.storage", choiceValue("sh1")},
          {"probes.sdf-resolution", {32.0}}}},
        {"medium", "SH L2, spacing 1/4, 128 rays, 64^3 field", {}},
        {"high", "octahedral maps, spacing 1/6, 256 rays, 64^3 field",
         {{"probes.spacing", {0.167}}, {"probes.rays", {256.0}}, {"probes.storage", choiceValue("octahedral")}}},
    };
    m.programs = &ProbesPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        const int probes = fitProbeGrid(scene.bounds, p.spacing).count();
        const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
        return std::vector<std::pair<std::string, uint64_t>>{
            {"probe voxels and distance field", uint64_t(sceneVolumeBytes(volumeRequest(p), 1))},
            {"probes (irradiance, distance moments, state)", uint64_t(probeStorageBytes(p, probes))},
            {"probe rays", uint64_t(probeRayBytes(p, probes))},
            {"probe screen target", pixels * 8}};
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<ProbesPass>(b.services, b.settings)); };
    // Updates stop when converged (40-70 updates on the Cornell box) or after max-updates; the
    // bench renders this many frames first. Capped so that a huge max-updates cannot stall it; with
    // probes.per-frame below the probe count a pass over all probes takes several frames, which
    // this cannot know (it sees no scene): such a bench row may be scored before convergence.
    m.framesToConverge = [](const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        return std::min(p.maxUpdates, 200);
    };
    return m;
}

std::vector<std::string> ProbesPass::stats() const {
    const probes::Storage storage = probes::Storage(built_.storage);
    const int64_t perProbe = probes::bytesPerProbe(storage);
    char line[200];
    std::snprintf(line, sizeof line, "probes %dx%dx%d = %d, %s storage, %lld bytes per probe (%.1f KiB)",
                  grid_.counts.x, grid_.counts.y, grid_.counts.z, grid_.count(), probes::storageName(storage),
                  static_cast<long long>(perProbe), double(perProbe * grid_.count()) / 1024.0);
    return {line, describeVolume(fit_, "voxels / distance-field cells")};
}

}  // namespace gis
