#include "gi/vct/vct_pass.h"

#include <cmath>

#include "gl/bind.h"
#include "gl/dispatch.h"
#include "debug_view.h"
#include "gi/method.h"
#include "scene/scene_lighting.h"
#include "services/scene_services.h"
#include "gi/vct/vct_bindings.h"
#include "volume/voxel_uniforms.h"

namespace gis {

using namespace voxel;
using namespace vct;

namespace {
ConeSettings coneSettingsOf(const VctSettings& s) {
    return {s.coneSet, s.stepFactor, s.maxDistance * float(s.resolution), s.offset, s.skyRays};
}

int tracedSize(int fullSize, int scale) { return (fullSize + scale - 1) / scale; }

// What VCT asks of the scene volume (vctVolumeRequest), with the feedback light when vct.feedback.
VolumeRequest volumeRequest(const VctSettings& s) {
    VolumeRequest r = vctVolumeRequest(s);
    r.feedback = s.feedback;
    return r;
}

// The request of valid settings (checkVctSettings throws first, naming the parameter).
VolumeRequest checkedVolumeRequest(const RenderSettings& settings) {
    const VctSettings s = vctParams().read("vct", settings.params);
    checkVctSettings(s);
    return volumeRequest(s);
}

// The traced diffuse, specular (RGBA16F) and ao (R16F); the sky-filtered diffuse (RGBA16F, full
// resolution); above scale 1 two full-resolution histories of three RGBA16F textures each.
uint64_t screenTargetBytes(const VctSettings& v, int width, int height) {
    const int scale = v.tracePixels();
    const uint64_t traced = uint64_t(tracedSize(width, scale)) * uint64_t(tracedSize(height, scale)) * 18;
    const uint64_t full = uint64_t(width) * uint64_t(height) * 8;
    return traced + full + (scale == 1 ? 0 : full * 2 * 3);
}

// The pixel of its scale x scale block a traced texel stands for in frame `frame`: the phases in
// Bayer order, so consecutive frames sample far-apart pixels of the block and every scale^2
// consecutive frames sample each pixel once.
glm::ivec2 jitterPhase(int scale, uint32_t frame) {
    glm::ivec2 phase{0};
    uint32_t k = frame % uint32_t(scale * scale);
    for (int n = scale / 2; n >= 1; n /= 2, k >>= 2) {
        const int low = int(k & 1u), high = int((k >> 1) & 1u);
        phase += glm::ivec2(low ^ high, low) * n;
    }
    return phase;
}
}  // namespace

// The ray scene's texture array in the trace (its sky rays), above the G-buffer's units.
const ProgramDesc kTraceProgram{"vct_trace", {"gi/vct/vct_trace.comp"}, {{"RAY_SCENE_TEXTURE_UNIT", "TC_TRACE_RAY_SCENE"}}};
const ProgramDesc kDebugProgram{"vct_debug", {"gi/vct/vct_debug.comp"}, {}};
const ProgramDesc kUpsampleProgram{"vct_upsample", {"gi/vct/vct_upsample.comp"}, {}};
const ProgramDesc kSkyFilterProgram{"vct_sky_filter", {"gi/vct/vct_sky_filter.comp"}, {}};

std::vector<ProgramDesc> VctPass::programs() {
    std::vector<ProgramDesc> all = SceneVolume::programs(volumeRequest(VctSettings{}));
    all.push_back(kDebugProgram);
    all.push_back(kTraceProgram);
    all.push_back(kUpsampleProgram);
    all.push_back(kSkyFilterProgram);
    return all;
}

VctPass::VctPass(SceneServices& services, const RenderSettings& settings)
    : VolumePass(services.volume(checkedVolumeRequest(settings))), built_(vctParams().read("vct", settings.params)),
      live_(built_), services_(&services), cones_({&services.ledger, name()}), debug_({&services.ledger, name()}) {
    // Everything is charged to the pass, so --timings, info and the panel show the method's whole
    // footprint on its row (its README page lists it per texture).
    const gl::MemoryScope trace{&services.ledger, name()};
    const int scale = built_.tracePixels();
    const int tw = tracedSize(settings.width, scale), th = tracedSize(settings.height, scale);
    diffuse_ = gl::createTexture2D(trace, GL_RGBA16F, tw, th);
    skyFiltered_ = gl::createTexture2D(trace, GL_RGBA16F, settings.width, settings.height);
    specular_ = gl::createTexture2D(trace, GL_RGBA16F, tw, th);
    ao_ = gl::createTexture2D(trace, GL_R16F, tw, th);
    traceProgram_ = buildProgram(kTraceProgram);
    debugProgram_ = buildProgram(kDebugProgram);
    skyFilterProgram_ = buildProgram(kSkyFilterProgram);
    if (scale == 1) return;
    for (History& h : history_)
        for (gl::Texture* t : {&h.diffuse, &h.specular, &h.geometry})
            *t = gl::createTexture2D(trace, GL_RGBA16F, settings.width, settings.height);
    upsampleProgram_ = buildProgram(kUpsampleProgram);
}

void VctPass::invalidate(Changes changes) {
    framesUnchanged_ = 0;
    if (changes & ChangeCamera) cameraMoved_ = true;
    if (changes & ~Changes(ChangeCamera)) hasHistory_ = false;
}

void VctPass::trace(const Frame& frame, const VctSettings& s, glm::ivec2 jitter) {
    const GLuint p = traceProgram_.id();
    const VolumeFit& fit = volume_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    frame.bindEnvironment();
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UV_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, UV_CONE_SET, s.coneSet);
    voxel::ConeTraceBlock cones;
    cones.stepFactor = s.stepFactor;
    cones.maxDistance = s.maxDistance * float(fit.resolution);
    cones.offset = s.offset;
    cones.specular = s.specular ? 1 : 0;
    cones.skyRays = s.skyRays;
    cones_.set(cones);
    glProgramUniform1i(p, UV_ANISOTROPIC, volume_->tracedRadiance().mipMode());
    glProgramUniform1f(p, UV_INTENSITY, s.intensity);
    glProgramUniform3i(p, UV_TRACE_JITTER, built_.tracePixels(), jitter.x, jitter.y);
    glProgramUniform1f(p, UV_SPECULAR_ROUGHNESS, s.specularRoughness);
    gl::bindTextures({{TC_TRACE_DEPTH, frame.texture(resource::kGbufferDepth)},
                      {TC_TRACE_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {TC_TRACE_MATERIAL, frame.texture(resource::kGbufferMaterial)}});
    volume_->bind();
    if (s.skyRays > 0) services_->rays().bind(TC_TRACE_RAY_SCENE);
    glBindImageTexture(IC_TRACE_DIFFUSE, diffuse_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IC_TRACE_SPECULAR, specular_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IC_TRACE_AO, ao_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    gl::dispatchCompute(gl::groupsFor(diffuse_.width, 8), gl::groupsFor(diffuse_.height, 8), 1, "vct");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VctPass::filterSky(const Frame& frame, const gl::Texture& diffuse) {
    const GLuint p = skyFilterProgram_.id();
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UV_CAMERA_POS, 1, &frame.camera.position[0]);
    gl::bindTextures({{TC_SKY_FILTER_DEPTH, frame.texture(resource::kGbufferDepth)},
                      {TC_SKY_FILTER_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {TC_SKY_FILTER_DIFFUSE, diffuse.id()}});
    glBindImageTexture(IC_SKY_FILTER_OUTPUT, skyFiltered_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(skyFiltered_.width, 8), gl::groupsFor(skyFiltered_.height, 8), 1, "vct sky filter");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

const gl::Texture& VctPass::skyFilteredDiffuse(Frame& frame, const gl::Texture& diffuse) {
    if (live_.skyRays == 0) return diffuse;
    auto t = frame.step("sky filter");
    filterSky(frame, diffuse);
    return skyFiltered_;
}

void VctPass::upsample(const Frame& frame, glm::ivec2 jitter) {
    const GLuint p = upsampleProgram_.id();
    const History& previous = history_[current_];
    const History& next = history_[1 - current_];
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UV_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform3i(p, UV_TRACE_JITTER, built_.tracePixels(), jitter.x, jitter.y);
    glProgramUniformMatrix4fv(p, UV_PREV_VIEW_PROJ, 1, GL_FALSE, &lastCamera_.viewProj[0][0]);
    glProgramUniform3fv(p, UV_PREV_CAMERA_POS, 1, &lastCamera_.position[0]);
    glProgramUniform2i(p, UV_HISTORY, hasHistory_ ? 1 : 0, cameraMoved_ ? 1 : 0);
    gl::bindTextures({{TC_UPSAMPLE_DEPTH, frame.texture(resource::kGbufferDepth)},
                      {TC_UPSAMPLE_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {TC_UPSAMPLE_TRACED_DIFFUSE, diffuse_.id()},
                      {TC_UPSAMPLE_TRACED_SPECULAR, specular_.id()},
                      {TC_UPSAMPLE_HISTORY_DIFFUSE, previous.diffuse.id()},
                      {TC_UPSAMPLE_HISTORY_SPECULAR, previous.specular.id()},
                      {TC_UPSAMPLE_HISTORY_GEOMETRY, previous.geometry.id()}});
    glBindImageTexture(IC_UPSAMPLE_DIFFUSE, next.diffuse.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IC_UPSAMPLE_SPECULAR, next.specular.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IC_UPSAMPLE_GEOMETRY, next.geometry.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(next.diffuse.width, 8), gl::groupsFor(next.diffuse.height, 8), 1, "vct upsample");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    current_ = 1 - current_;
}

std::vector<DebugViewDesc> VctPass::debugViews() const {
    return {{"vct.voxels", "the voxel grid ray-marched from the camera (vct.debug-channel, vct.debug-level)"},
            {"vct.slice", "one slice of the voxel grid (vct.slice-axis, vct.slice-position, vct.debug-channel)"},
            {"vct.ao", "the diffuse cones' occlusion (1 = open), already part of indirect.diffuse (as traced: one "
                       "texel per vct.trace-scale block)"}};
}

void VctPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    if (view == "vct.ao") {
        drawChannel(DisplayChannel::Grey, ao_.id(), frame, target);
        return;
    }
    const VctSettings live = vctParams().read("vct", frame.settings.params);
    const GLuint p = debugProgram_.id();
    const VolumeFit& fit = volume_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    const bool slice = view == "vct.slice";
    voxel::VctDebugBlock debug;
    debug.channel = live.debugChannel;
    debug.level = live.debugLevel;
    debug.sliceAxis = slice ? live.sliceAxis : -1;
    debug.slicePosition = live.slicePosition;
    debug_.set(debug);
    volume_->bind();
    glBindImageTexture(IC_DEBUG_VIEW, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(frame.settings.width, 8), gl::groupsFor(frame.settings.height, 8), 1, "vct");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

Pass::Progress VctPass::progress() const {
    if (!built_.feedback) return {};
    return {std::min(feedbackUpdates_, feedbackTarget_), feedbackTarget_, "feedback updates"};
}

bool VctPass::updateFeedback(Frame& frame, const ConeSettings& cones) {
    if (volume_->lastUpdate(0) != SceneVolume::Update::Cached || feedbackTarget_ == 0) {
        auto t = frame.step("feedback.restart");
        volume_->restartFeedback();
        feedbackUpdates_ = 0;
        feedbackTarget_ = feedbackBouncesFor(frame.scene.cpu);  // the materials may have changed
    }
    if (feedbackDone()) return false;
    auto t = frame.step("feedback");
    frame.bindEnvironment();
    volume_->addFeedbackBounce(cones);
    ++feedbackUpdates_;
    return true;
}

ConeSettings VctPass::bounceCones(const Frame& frame) const {
    VctSettings cones = vctParams().read("vct", frame.settings.params);
    cones.resolution = built_.resolution;
    return coneSettingsOf(cones);
}

void VctPass::run(Frame& frame) {
    live_ = vctParams().read("vct", frame.settings.params);
    // A new bounce changes every pixel: the reduced-resolution history gathers anew after the last.
    if (built_.feedback && updateFeedback(frame, bounceCones(frame))) framesUnchanged_ = 0;
    const glm::ivec2 jitter = jitterPhase(built_.tracePixels(), framesTraced_++);
    {
        auto t = frame.step("trace");
        trace(frame, live_, jitter);
    }
    if (built_.tracePixels() == 1) {
        frame.put(resource::kIndirectDiffuse, skyFilteredDiffuse(frame, diffuse_));
        frame.put(resource::kIndirectSpecular, specular_);
    } else {
        {
            auto t = frame.step("upsample");
            upsample(frame, jitter);
        }
        // The history keeps the exact samples; the filter runs on the full-resolution result, so
        // a converged frame is the full-resolution trace's, filtered alike.
        frame.put(resource::kIndirectDiffuse, skyFilteredDiffuse(frame, history_[current_].diffuse));
        frame.put(resource::kIndirectSpecular, history_[current_].specular);
        hasHistory_ = true;
        cameraMoved_ = false;
        lastCamera_ = frame.camera;
    }
    ++framesUnchanged_;
}

GiMethod vctMethod() {
    GiMethod m;
    m.name = "vct";
    m.summary = "voxel cone tracing: conservative voxelization, shadow-mapped light injection, cone-traced indirect";
    m.params = vctParams().rows;
    m.shaderTables.bindings = tableRows(vct::kVctBindings);
    m.presets = {
        {"low", "32^3, isotropic mips, one bounce, four cones, step 1, no specular cone",
         {{"vct.resolution", {32.0}},
          {"vct.bounces", {1.0}},
          {"vct.anisotropic", {0.0}},
          {"vct.step", {1.0}},
          {"vct.specular", {0.0}},
          {"vct.cones", ParamValue::choice("four")}}},
        {"medium", "64^3, directional mips, three bounces, six cones", {}},
        // Traced at quarter resolution: once converged (framesToConverge, 16 frames) its image is
        // the full-resolution trace's, at a sixteenth of the cones per frame (issue #24: a high
        // preset within 3x what Godot's GIProbe 128 adds to a frame). The offset is medium's distance
        // in the scene (twice the voxels at twice the resolution): at medium's voxel count, the
        // cones' first samples filtered in more of their own surface, a lit floor lighting itself
        // (both Cornell boxes measured, renderer/gi/vct/README.md). Two bounces: each gathers over
        // eight times medium's voxels once per lighting, and a third scored no better against Cycles.
        {"high", "128^3, directional mips, two bounces, offset 3, trace scale 4",
         {{"vct.resolution", {128.0}},
          {"vct.bounces", {2.0}},
          {"vct.offset", {3.0}},
          {"vct.trace-scale", ParamValue::choice("4")}}},
        // The trace is the per-frame cost, so it is cut on every axis (the table in
        // renderer/gi/vct/README.md). The volume is medium's, as GIProbe 64's is the one this
        // preset is compared with: half as many voxels let a building's 20 cm walls share a
        // voxel's light between their two sides (issue #39), and the volume and its bounces cost
        // only when the scene or its lights change, not per frame.
        {"realtime",
         "64^3, directional mips, three bounces, four cones, step 2, half-length cones, specular cone below "
         "roughness 0.5, trace scale 4",
         {{"vct.cones", ParamValue::choice("four")},
          {"vct.step", {2.0}},
          {"vct.max-distance", {0.5}},
          {"vct.specular-roughness", {0.5}},
          {"vct.trace-scale", ParamValue::choice("4")}}},
    };
    m.programs = &VctPass::programs;
    m.estimateMemory = [](const Scene&, const RenderSettings& s) {
        const VctSettings v = vctParams().read("vct", s.params);
        const VolumeRequest r = volumeRequest(v);
        const int n = r.resolution;
        std::vector<std::pair<std::string, uint64_t>> rows{
            {"VCT voxel grid and voxelization sums", uint64_t(voxelGridBytes(n))},
            {"VCT radiance mips",
             uint64_t(voxelRadianceBytes(n, r.anisotropic, r.bounces, r.cullUnlitOutsides, r.hitLights))},
            {"VCT screen targets", screenTargetBytes(v, s.width, s.height)}};
        if (r.feedback)
            rows.push_back({"VCT bounce feedback", uint64_t(voxelFeedbackBytes(n, r.anisotropic, r.hitLights))});
        return rows;
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<VctPass>(b.services, b.settings)); };
    m.framesToConverge = [](const RenderSettings& s) { return vctParams().read("vct", s.params).framesToConverge(); };
    m.checkSettings = [](const ParamValues& values) { checkVctSettings(vctParams().read("vct", values)); };
    return m;
}

}  // namespace gis
