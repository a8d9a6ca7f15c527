#include "probes/probe_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "gl/bind.h"
#include "gl/dispatch.h"
#include "gl/shader.h"
#include "probes/probe_uniforms.h"
#include "scene/scene_lighting.h"
#include "volume/scene_volume.h"

namespace gis::probes {

namespace {

constexpr int kDistanceTexels = kOctDistanceSize * kOctDistanceSize;
constexpr int kStateVec4s = 2;  // per probe: offset + state; update count, last change

// The ray set's rotation for update `n`: a uniformly random rotation (Shoemake's unit quaternion
// from three uniforms), seeded by the update's number so renders are repeatable.
glm::mat3 randomRotation(int n) {
    std::mt19937 rng(0x9e3779b9u + uint32_t(n) * 7919u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float u1 = u(rng), u2 = u(rng) * 6.2831853f, u3 = u(rng) * 6.2831853f;
    const float a = std::sqrt(1.0f - u1), b = std::sqrt(u1);
    return glm::mat3_cast(glm::quat(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3)));
}

// The farthest a probe ray may go, and the distance a miss records: the coarsest cascade's diagonal.
float missDistance(const SceneVolume& v) { return v.cascadeVolume(v.cascadeCount() - 1).size * 1.7320508f; }

bool sameGrid(const ProbeGrid& a, const ProbeGrid& b) {
    return a.first == b.first && a.step == b.step && a.counts == b.counts;
}

const ProgramDesc kClassifyProgram{"probe_classify", {"probes/probe_classify.comp"}, {}};
const ProgramDesc kTraceProgram{"probe_trace", {"probes/probe_trace.comp"}, {}};
const ProgramDesc kClassifyOccupancyProgram{"probe_classify_occupancy", {"probes/probe_classify.comp"}, {{"PROBE_TRACER_OCCUPANCY", "1"}}};
const ProgramDesc kTraceOccupancyProgram{"probe_trace_occupancy", {"probes/probe_trace.comp"}, {{"PROBE_TRACER_OCCUPANCY", "1"}}};
const ProgramDesc kBlendProgram{"probe_blend", {"probes/probe_blend.comp"}, {}};
const ProgramDesc kDebugProgram{"probe_debug", {"probes/probe_debug.comp"}, {}};
const ProgramDesc kRaysProgram{"probe_rays", {"probes/probe_rays.comp"}, {}};
}  // namespace

std::vector<ProgramDesc> fieldPrograms() {
    return {kClassifyProgram, kTraceProgram, kClassifyOccupancyProgram, kTraceOccupancyProgram,
            kBlendProgram,    kDebugProgram, kRaysProgram};
}

ProbeGrid cascadeProbeGrid(const SceneVolume& volume, const Aabb& sceneBounds, float spacing, int cascade) {
    if (cascade == volume.cascadeCount() - 1) return fitProbeGrid(sceneBounds, spacing, volume.layout().scene.bounds);
    const SdfVolume v = volume.cascadeVolume(cascade);
    return fitProbeGrid(Aabb{v.origin, v.origin + glm::vec3(v.size)}, spacing);
}

std::vector<ProbeGrid> cascadeProbeGrids(const SceneVolume& volume, const Aabb& sceneBounds, float spacing) {
    std::vector<ProbeGrid> grids;
    for (int i = 0; i < volume.cascadeCount(); ++i) grids.push_back(cascadeProbeGrid(volume, sceneBounds, spacing, i));
    return grids;
}

void followCascades(ProbeField& field, const SceneVolume& volume, const Aabb& sceneBounds, float spacing) {
    for (int i = 0; i < volume.cascadeCount(); ++i) field.place(i, cascadeProbeGrid(volume, sceneBounds, spacing, i));
}

int cascadeProbeCount(const Aabb& sceneBounds, const CascadeLayout& layout, float spacing) {
    int count = fitProbeGrid(sceneBounds, spacing, layout.scene.bounds).count();
    const float e = layout.extent(0);
    if (layout.count > 1) count += (layout.count - 1) * fitProbeGrid(Aabb{glm::vec3(0.0f), glm::vec3(e)}, spacing).count();
    return count;
}

int batchCapacity(const FieldSettings& s, int probes) {
    return s.rayBudget > 0 ? std::clamp(s.rayBudget / std::max(s.rays, 1), 1, std::max(probes, 1)) : std::max(probes, 1);
}
int64_t fieldStorageBytes(const FieldSettings& s, int probes) { return int64_t(probes) * bytesPerProbe(s.storage); }
int64_t fieldRayBytes(const FieldSettings& s, int probes) {
    const int64_t batch = batchCapacity(s, probes);
    return batch * s.rays * 16 + batch * 4;
}

void checkFieldSettings(const FieldSettings& s, const std::string& budgetKey, const std::string& raysKey) {
    if (s.rayBudget > 0 && s.rayBudget < s.rays)
        throw Error(budgetKey + ": " + std::to_string(s.rayBudget) + " rays per frame pay for no probe update (" +
                    raysKey + " is " + std::to_string(s.rays) + "); use 0 (no budget) or at least " +
                    std::to_string(s.rays));
}

ProbeField::ProbeField(const gl::MemoryScope& scope, SceneVolume& volume, std::vector<ProbeGrid> grids,
                       const FieldSettings& built)
    : built_(built), volume_(&volume), grids_(std::move(grids)), maxUpdates_(built.maxUpdates), update_(scope) {
    if (grids_.empty() || int(grids_.size()) > kMaxGrids) throw Error("probes: between 1 and 4 probe grids");
    for (const ProbeGrid& g : grids_) count_ += g.count();
    if (count_ > kMaxProbes)
        throw Error("probes: " + std::to_string(count_) + " probes exceed the limit of " + std::to_string(kMaxProbes));
    needClassify_.assign(grids_.size(), true);
    capacity_ = batchCapacity(built_, count_);
    irradiance_ = gl::createStorageBuffer(scope, int64_t(count_) * irradianceBytesPerProbe(built_.storage), nullptr);
    glClearNamedBufferData(irradiance_.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    // Distance moments start at "nothing within reach" so that, before the first update, every
    // probe counts as visible.
    const float miss = missDistance(volume);
    std::vector<glm::vec2> far(size_t(count_) * kDistanceTexels, glm::vec2(miss, miss * miss));
    distance_ = gl::createStorageBuffer(scope, int64_t(far.size() * sizeof(glm::vec2)), far.data());
    state_ = gl::createStorageBuffer(scope, int64_t(count_) * kStateBytesPerProbe, nullptr);
    glClearNamedBufferData(state_.id(), GL_R32F, GL_RED, GL_FLOAT, nullptr);
    rays_ = gl::createStorageBuffer(scope, int64_t(capacity_) * built_.rays * 16, nullptr);
    batch_ = gl::createStorageBuffer(scope, int64_t(capacity_) * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
    change_ = gl::createStorageBuffer(scope, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    probeUpdates_.assign(size_t(count_), 0.0f);
    probeChange_.assign(size_t(count_), 0.0f);
    probeOff_.assign(size_t(count_), false);
    sampler_ = gl::createSampler();
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(sampler_.id(), w, GL_CLAMP_TO_EDGE);
    const bool occupancy = built_.tracer == Tracer::Occupancy;
    classifyProgram_ = buildProgram(occupancy ? kClassifyOccupancyProgram : kClassifyProgram);
    traceProgram_ = buildProgram(occupancy ? kTraceOccupancyProgram : kTraceProgram);
    blendProgram_ = buildProgram(kBlendProgram);
    debugProgram_ = buildProgram(kDebugProgram);
    raysProgram_ = buildProgram(kRaysProgram);
}

void ProbeField::restart() {
    converged_ = false;
    pending_ = false;
    updates_ = finished_ = 0;
}

void ProbeField::place(int g, const ProbeGrid& grid) {
    if (sameGrid(grids_[size_t(g)], grid)) return;
    if (grid.counts != grids_[size_t(g)].counts) throw Error("probes: a placed grid keeps its probe counts");
    grids_[size_t(g)] = grid;
    needClassify_[size_t(g)] = true;
    converged_ = false;
}

void ProbeField::invalidate(Changes c) {
    if (c & (ChangeGeometry | ChangeMaterials)) bounceUpdates_ = 0;   // worked out again from the materials
    if (c & (ChangeGeometry | ChangeMaterials | ChangeLights)) {
        std::fill(needClassify_.begin(), needClassify_.end(), true);
        restart();
    }
}

Pass::Progress ProbeField::progress() const {
    if (converged_) return {finished_, finished_, "updates"};
    const int target = maxUpdates();
    return {std::min(finished_, target - 1), target, "updates"};
}

int ProbeField::maxUpdates() const { return maxUpdates_ * ((count_ + capacity_ - 1) / capacity_); }

void ProbeField::setGridUniforms(GLuint p) const {
    glm::vec3 first[kMaxGrids]{}, step[kMaxGrids]{};
    glm::ivec3 counts[kMaxGrids]{};
    for (size_t g = 0; g < grids_.size(); ++g) {
        first[g] = grids_[g].first;
        step[g] = grids_[g].step;
        counts[g] = grids_[g].counts;
    }
    glProgramUniform3fv(p, UP_GRID_FIRST, kMaxGrids, &first[0][0]);
    glProgramUniform3fv(p, UP_GRID_STEP, kMaxGrids, &step[0][0]);
    glProgramUniform3iv(p, UP_GRID_COUNTS, kMaxGrids, &counts[0][0]);
    glProgramUniform1i(p, UP_GRID_COUNT, int(grids_.size()));
    glProgramUniform1i(p, UP_STORAGE, int(built_.storage));
}

// Only the programs that trace the volume (classify, trace, the screen gather) declare these: setting a location a
// program does not have is GL_INVALID_OPERATION. The field's layers lie where the voxels do.
void ProbeField::setFieldUniforms(GLuint p) const {
    glm::vec4 cascades[kMaxGrids]{};
    const int count = volume_->cascadeCount();
    for (int i = 0; i < count; ++i) {
        const SdfVolume v = volume_->cascadeVolume(i);
        cascades[i] = glm::vec4(v.origin, v.size);
    }
    glProgramUniform4fv(p, UP_CASCADES, kMaxGrids, &cascades[0][0]);
    glProgramUniform1i(p, UP_CASCADE_COUNT, count);
    glProgramUniform1i(p, UP_SDF_RESOLUTION, volume_->layout().resolution());
}

void ProbeField::bindTracer() const {
    if (built_.tracer == Tracer::Occupancy) {
        volume_->occupancy().bind();
        return;
    }
    static_assert(TP_FIELD_COARSE == TP_FIELD_DISTANCE + 1, "DistanceField::bind binds both levels from one unit");
    volume_->field().bind(TP_FIELD_DISTANCE);
    glBindSamplers(TP_FIELD_DISTANCE, 2, nullptr);  // the field's own filtering
}

void ProbeField::bindBuffers() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_IRRADIANCE, irradiance_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_DISTANCE, distance_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_STATE, state_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_RAYS, rays_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_CHANGE, change_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SP_BATCH, batch_.id());
}

void ProbeField::bindForGather(GLuint program) const {
    setGridUniforms(program);
    bindBuffers();
}

void ProbeField::bindForScreenGather(GLuint program) const {
    bindForGather(program);
    setFieldUniforms(program);
    bindTracer();
}

void ProbeField::classify(int grid) {
    const GLuint p = classifyProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    setFieldUniforms(p);
    glProgramUniform1i(p, UP_MODE, built_.relocate ? 0 : 1);
    glProgramUniform1i(p, UP_CLASSIFY_GRID, grid);
    bindTracer();
    bindBuffers();
    gl::dispatchCompute(gl::groupsFor(count_, 64), 1, 1, "probes: classify");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    int first = 0;
    for (int g = 0; g < grid; ++g) first += grids_[size_t(g)].count();
    std::fill_n(probeUpdates_.begin() + first, grids_[size_t(grid)].count(), 0.0f);
    std::fill_n(probeChange_.begin() + first, grids_[size_t(grid)].count(), 0.0f);
    // Which probes the classification switched off the CPU learns with the next read-back; until
    // then they count as on (the GPU skips an off probe's rays).
    std::fill_n(probeOff_.begin() + first, grids_[size_t(grid)].count(), false);
    needClassify_[size_t(grid)] = false;
    roundStart_ = 0.0f;
    roundChange_ = 0.0f;
    restart();
}

// The last update's per-probe counts and changes, and its ray count, read at the start of the next
// frame rather than right after the dispatch: by then the GPU has finished it, so the read does not
// stall the frame that submitted it, and the decision still comes before the next update.
void ProbeField::readBack(const FieldSettings& live) {
    pending_ = false;
    ++finished_;
    uint32_t counters[2] = {0, 0};
    glGetNamedBufferSubData(change_.id(), 0, 8, counters);
    std::memcpy(&lastChange_, &counters[0], 4);
    if (!std::isfinite(lastChange_)) lastChange_ = 1.0f;
    lastRays_ = counters[1];
    rays_total_.bounce += lastRays_;
    std::vector<glm::vec4> state(size_t(count_) * kStateVec4s);
    glGetNamedBufferSubData(state_.id(), 0, GLsizeiptr(state.size() * sizeof(glm::vec4)), state.data());
    float fewest = 3.4e38f;
    for (int i = 0; i < count_; ++i) {
        const glm::vec4& s = state[size_t(i) * 2 + 1];
        probeUpdates_[size_t(i)] = s.x;
        probeChange_[size_t(i)] = std::isfinite(s.y) ? s.y : 1.0f;
        probeOff_[size_t(i)] = state[size_t(i) * 2].w > 1.5f;
        if (!probeOff_[size_t(i)]) fewest = std::min(fewest, s.x);
    }
    for (int i : lastBatchProbes_) roundChange_ = std::max(roundChange_, probeChange_[size_t(i)]);
    if (fewest == 3.4e38f) {  // every probe is off: nothing to update
        converged_ = true;
        return;
    }
    // A round ends when every probe has had one more update. The field has converged when a whole
    // round (after the second, since a probe's first update replaces its value and reports no
    // change) changed no probe by the threshold, or every probe has had max-updates.
    if (fewest > roundStart_) {
        const float settled = live.bounces ? float(bounceUpdates_) + 2.0f : 2.0f;
        if ((fewest >= settled && roundChange_ < live.threshold) || fewest >= float(live.maxUpdates)) converged_ = true;
        roundStart_ = fewest;
        roundChange_ = 0.0f;
    }
}

// This frame's probes: as many as the budget pays for, the least updated first (so every probe
// gets its turn: a round), and among those the ones the camera sees, then the most changed.
std::vector<int> ProbeField::schedule(const Frame& frame, const FieldSettings& live) const {
    std::vector<int> due;
    std::vector<float> key(size_t(count_), 0.0f);
    int base = 0;
    for (const ProbeGrid& g : grids_) {
        for (int l = 0; l < g.count(); ++l) {
            const int i = base + l;
            const float n = probeUpdates_[size_t(i)];
            if (probeOff_[size_t(i)] || n >= float(live.maxUpdates)) continue;
            const glm::vec4 c = frame.camera.viewProj * glm::vec4(g.position(l), 1.0f);
            const bool visible = c.w > 0.0f && std::abs(c.x) <= 1.2f * c.w && std::abs(c.y) <= 1.2f * c.w;
            key[size_t(i)] = n * 4.0f + (visible ? 0.0f : 2.0f) - std::min(probeChange_[size_t(i)], 1.0f);
            due.push_back(i);
        }
        base += g.count();
    }
    if (int(due.size()) > capacity_) {
        std::stable_sort(due.begin(), due.end(), [&](int a, int b) { return key[size_t(a)] < key[size_t(b)]; });
        due.resize(size_t(capacity_));
    }
    return due;
}

void ProbeField::bindForHitLight(GLuint p, const FieldSettings& live) const {
    setGridUniforms(p);
    setFieldUniforms(p);
    setUpdateBlock(live);
    bindTracer();
    // The radiance and the albedo (for the multi-bounce term), filtered; the slab voxels' sides
    // (texelFetch: no sampler).
    gl::bindTextures({{TP_VOXEL_RADIANCE, volume_->radianceTexture()}, {TP_VOXEL_ALBEDO, volume_->albedoTexture()}},
                     sampler_.id());
    gl::bindTextures({{TP_VOXEL_SIDES, volume_->sidesTexture()}});
    bindBuffers();
}

void ProbeField::releaseHitLight() const {
    for (int unit : {TP_VOXEL_RADIANCE, TP_VOXEL_ALBEDO}) glBindSampler(GLuint(unit), 0);
}

void ProbeField::trace(const Frame& frame, const FieldSettings& s, int batch) {
    const GLuint p = traceProgram_.id();
    frame.bindEnvironment();
    glUseProgram(p);
    glProgramUniform1i(p, UP_RAYS, built_.rays);
    glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
    bindForHitLight(p, s);
    gl::dispatchComputeSplit(batch, [&](GLuint slot) { glProgramUniform1i(p, UP_SLOT_OFFSET, int(slot)); });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    releaseHitLight();
}

void ProbeField::setUpdateBlock(const FieldSettings& s) const {
    ProbeUpdateBlock b;
    b.hysteresis = s.hysteresis;
    b.replacingUpdates = s.bounces ? float(bounceUpdates_) : 0.0f;
    b.missDistance = missDistance(*volume_);
    b.multiBounce = s.bounces ? 1 : 0;
    b.visibility = visibilityMode(s.visibility, s.pathTest);
    b.normalBias = s.normalBias;
    b.hitThreshold = s.hitThreshold;
    update_.set(b);
}

void ProbeField::blend(int mode, const FieldSettings& s, int batch) {
    const GLuint p = blendProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniform1i(p, UP_RAYS, built_.rays);
    glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
    setUpdateBlock(s);
    glProgramUniform1i(p, UP_MODE, mode);
    bindBuffers();
    gl::dispatchComputeSplit(batch, [&](GLuint slot) { glProgramUniform1i(p, UP_SLOT_OFFSET, int(slot)); });
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void ProbeField::update(Frame& frame, const FieldSettings& live) {
    maxUpdates_ = live.maxUpdates;
    if (bounceUpdates_ == 0) bounceUpdates_ = feedbackBouncesFor(frame.scene.cpu);
    bool classified = false;
    for (size_t g = 0; g < grids_.size(); ++g)
        if (needClassify_[g]) {
            auto t = frame.step("probe classify");
            classify(int(g));
            classified = true;
        }
    // A field with no usable probe gives black indirect light everywhere: say so once (a read-back
    // per classification, i.e. per geometry, light or cascade change, not per frame). A solid object's
    // grid has a layer in the air around it (fitProbeGrid), so no spacing the user picks would
    // do better: this is a scene with no room for a probe, or probes.inside=off.
    if (classified && !warnedAllOff_) {
        const StateCounts c = stateCounts();
        if (c.active + c.relocated == 0) {
            std::fprintf(stderr,
                         "gisandbox: warning: probes: all %d probes are inside geometry and switched off (%s); the "
                         "probes' indirect light is black\n",
                         count_, built_.relocate ? "relocate found no way out" : "inside=off");
            warnedAllOff_ = true;
        }
    }
    if (pending_) readBack(live);
    std::vector<int> batch = converged_ ? std::vector<int>{} : schedule(frame, live);
    updatedLastFrame_ = !batch.empty();
    if (batch.empty()) {
        converged_ = true;
        return;
    }
    const uint32_t zero[4] = {0, 0, 0, 0};
    glNamedBufferSubData(change_.id(), 0, 16, zero);
    glNamedBufferSubData(batch_.id(), 0, GLsizeiptr(batch.size() * 4), batch.data());
    rotation_ = randomRotation(updates_);
    const int n = int(batch.size());
    {
        auto t = frame.step("probe trace");
        trace(frame, live, n);
    }
    {
        auto t = frame.step("probe blend irradiance");
        blend(0, live, n);
    }
    {
        auto t = frame.step("probe blend distance");
        blend(1, live, n);
    }
    lastBatchProbes_ = std::move(batch);
    lastBatch_ = n;
    ++updates_;
    pending_ = true;
}

ProbeField::StateCounts ProbeField::stateCounts() const {
    std::vector<glm::vec4> state(size_t(count_) * kStateVec4s);
    glGetNamedBufferSubData(state_.id(), 0, GLsizeiptr(state.size() * sizeof(glm::vec4)), state.data());
    StateCounts c;
    for (size_t i = 0; i < state.size(); i += 2) {
        const float s = state[i].w;
        (s > 1.5f ? c.off : (s > 0.5f ? c.relocated : c.active))++;
    }
    return c;
}

std::vector<glm::vec3> ProbeField::readIrradiance(int probe) const {
    const int stride = irradianceVec4s(built_.storage);
    std::vector<glm::vec4> raw(static_cast<size_t>(stride));
    glGetNamedBufferSubData(irradiance_.id(), GLintptr(int64_t(probe) * stride * 16), GLsizeiptr(stride * 16), raw.data());
    std::vector<glm::vec3> out;
    for (const glm::vec4& v : raw) out.emplace_back(v);
    return out;
}

std::vector<DebugViewDesc> ProbeField::debugViews(const std::string& prefix, const std::string& debugProbe) const {
    return {{prefix + ".spheres", "every probe as a sphere showing its irradiance (E/pi) towards the viewer; dark "
                                  "red: switched off (inside geometry), blue rim: relocated"},
            {prefix + ".state", "every probe as a sphere coloured by state: green active, blue relocated, red off"},
            {prefix + ".rays", "the rays of " + debugProbe + " from its last update, coloured by their radiance"}};
}

// The debug views' common end: depth and probe buffers bound, one thread per pixel into `target`.
void ProbeField::dispatchDebugDraw(const Frame& frame, GLuint target) {
    const GLuint depth = frame.texture(resource::kGbufferDepth);
    glBindTextures(TP_GATHER_DEPTH, 1, &depth);
    glBindSamplers(TP_GATHER_DEPTH, 1, nullptr);
    bindBuffers();
    glBindImageTexture(IP_OUTPUT, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    const int w = frame.settings.width, h = frame.settings.height;
    gl::dispatchCompute(gl::groupsFor(w, 8), gl::groupsFor(h, 8), 1, "probes");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void ProbeField::drawDebugView(const std::string& view, const Frame& frame, GLuint target, const FieldSettings& live) {
    if (view == "rays") {
        const ProbeGrid& g = grids_[0];
        const int probe = live.debugProbe < 0 ? probeIndexNear(g, g.first + 0.5f * glm::vec3(g.counts - 1) * g.step)
                                              : std::min(live.debugProbe, count_ - 1);
        // The ray buffer holds the last batch only: a probe outside it has no rays to show.
        const auto at = std::find(lastBatchProbes_.begin(), lastBatchProbes_.end(), probe);
        const GLuint p = raysProgram_.id();
        glUseProgram(p);
        setGridUniforms(p);
        glProgramUniformMatrix4fv(p, UP_VIEW_PROJ, 1, GL_FALSE, &frame.camera.viewProj[0][0]);
        glProgramUniform1i(p, UP_RAYS, built_.rays);
        glProgramUniform1i(p, UP_BATCH_SLOT, at == lastBatchProbes_.end() ? -1 : int(at - lastBatchProbes_.begin()));
        glProgramUniformMatrix3fv(p, UP_ROTATION, 1, GL_FALSE, &rotation_[0][0]);
        glProgramUniform1i(p, UP_MODE, probe);
        dispatchDebugDraw(frame, target);
        return;
    }
    const GLuint p = debugProgram_.id();
    glUseProgram(p);
    setGridUniforms(p);
    glProgramUniform1i(p, UP_MODE, view == "state" ? 1 : 0);
    glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
    const glm::vec3 step = grids_[0].step;
    glProgramUniform1f(p, UP_SPHERE_RADIUS, 0.15f * std::min(step.x, std::min(step.y, step.z)));
    dispatchDebugDraw(frame, target);
}

std::string ProbeField::describe() const {
    std::string counts;
    for (const ProbeGrid& g : grids_)
        counts += (counts.empty() ? "" : " + ") + std::to_string(g.counts.x) + "x" + std::to_string(g.counts.y) + "x" +
                  std::to_string(g.counts.z);
    const int64_t perProbe = bytesPerProbe(built_.storage);
    char line[240];
    std::snprintf(line, sizeof line, "probes %s = %d, %s storage, %lld bytes per probe (%.1f KiB); %s", counts.c_str(),
                  count_, storageName(built_.storage), static_cast<long long>(perProbe),
                  double(perProbe * count_) / 1024.0,
                  built_.rayBudget > 0 ? ("ray budget " + std::to_string(built_.rayBudget) + " per frame (" +
                                          std::to_string(capacity_) + " probes)").c_str()
                                       : "every due probe each frame");
    return line;
}

}  // namespace gis::probes
