#include "gi/sdf/sdf_pass.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gl/bind.h"
#include "gl/dispatch.h"
#include "debug_view.h"
#include "gi/method.h"
#include "gi/sdf/sdf_gi_uniforms.h"
#include "probes/probe_uniforms.h"
#include "services/scene_services.h"

namespace gis {

using namespace sdfgi;

namespace {

constexpr int kGroup = 8;  // local size of the 2D shaders/gi/sdf/*.comp

void dispatch2D(int w, int h) { gl::dispatchCompute(gl::groupsFor(w, kGroup), gl::groupsFor(h, kGroup), 1, "sdf"); }

// Traced pixel q stands for full-resolution pixel q * scale (sdf_gbuffer.glsl); at a reduced scale
// one more traced pixel per row and column stands for the last full-resolution one, so the
// upsampling interpolates up to the frame's edge instead of holding the last value.
int tracedSize(int fullSize, int scale) { return scale == 1 ? fullSize : (fullSize - 1) / scale + 2; }

// A static view's history is a running mean (up to 256 frames): after 4 / (1 - temporal) frames
// (40 at the default) the frame-to-frame change is below 1% (the convergence test).
int sdfFramesToConverge(float temporal) {
    return temporal <= 0.0f ? 1 : std::min(64, int(std::ceil(4.0f / (1.0f - temporal))));
}

}  // namespace

const ProgramDesc kTraceProgram{"sdf_gi_trace", {"gi/sdf/sdf_trace.comp"}, {}};
const ProgramDesc kTemporalProgram{"sdf_gi_temporal", {"gi/sdf/sdf_temporal.comp"}, {}};
const ProgramDesc kFilterProgram{"sdf_gi_filter", {"gi/sdf/sdf_filter.comp"}, {}};
const ProgramDesc kDebugProgram{"sdf_gi_debug", {"gi/sdf/sdf_debug.comp"}, {}};

std::vector<ProgramDesc> SdfGiPass::programs() {
    std::vector<ProgramDesc> all = SceneVolume::programs(sdfVolumeRequest(SdfGiSettings{}));
    for (const ProgramDesc& p : probes::fieldPrograms()) all.push_back(p);
    for (const ProgramDesc& p : probes::ScreenReflection::programs()) all.push_back(p);
    for (const ProgramDesc* p : {&kTraceProgram, &kTemporalProgram, &kFilterProgram, &kDebugProgram}) all.push_back(*p);
    return all;
}


std::vector<std::pair<std::string, uint64_t>> SdfGiPass::estimateMemory(const Scene& scene, const RenderSettings& settings) {
    const SdfGiSettings s = sdfParams().read("sdf", settings.params);
    const int scale = s.tracePixels();
    const VolumeRequest request = sdfVolumeRequest(s);
    const CascadeLayout layout = volumeLayout(sceneAirBounds(scene), request, viewDepthFor(request, scene, settings));  // as SceneServices fits it
    const int count = layout.count;
    const uint64_t traced = uint64_t(tracedSize(settings.width, scale)) * uint64_t(tracedSize(settings.height, scale));
    const uint64_t full = uint64_t(settings.width) * uint64_t(settings.height);
    std::vector<std::pair<std::string, uint64_t>> rows;
    rows.push_back({"SDF scene volume (" + std::to_string(count) + " cascade" + (count > 1 ? "s" : "") +
                        ": voxels, light, field)",
                    uint64_t(sceneVolumeBytes(request, count))});
    // raw, reflection, info, 2 histories (RGBA16F), occlusion (R16F), 2 distances (R32F);
    // full resolution: diffuse, specular (RGBA16F), ao (R16F)
    rows.push_back({"SDF trace", traced * (5 * 8 + 2 + 2 * 4) + full * (2 * 8 + 2)});
    if (s.probeGather()) {
        const int probes = probes::cascadeProbeCount(scene.bounds, layout, s.probeSpacing);
        rows.push_back({"SDFGI probes (" + std::to_string(probes) + ": irradiance, distance moments, state)",
                        uint64_t(probes::fieldStorageBytes(s.probeField(), probes))});
        rows.push_back({"SDFGI probe rays", uint64_t(probes::fieldRayBytes(s.probeField(), probes))});
        rows.push_back({"SDFGI reflection (means, specular)", uint64_t(probes::ScreenReflection::bytes(settings.width, settings.height))});
    }
    return rows;
}

SdfGiPass::SdfGiPass(SceneServices& services, const RenderSettings& settings)
    : VolumePass(services.volume(sdfVolumeRequest(sdfParams().read("sdf", settings.params)))),
      built_(sdfParams().read("sdf", settings.params)), scope_{&services.ledger, name()}, march_(scope_), debug_(scope_),
      traceBlock_(scope_), temporalBlock_(scope_) {
    sceneBounds_ = services.bounds();
    if (built_.probeGather()) {
        probes::checkFieldSettings(built_.probeField(), "sdf.probe-ray-budget", "sdf.probe-rays");
        field_ = std::make_unique<probes::ProbeField>(
            scope_, *volume_, probes::cascadeProbeGrids(*volume_, sceneBounds_, built_.probeSpacing), built_.probeField());
        screenReflection_ = std::make_unique<probes::ScreenReflection>(scope_, settings.width, settings.height, field_->tracer());
    }
    scale_ = built_.tracePixels();
    const int tw = tracedSize(settings.width, scale_), th = tracedSize(settings.height, scale_);
    raw_ = gl::createTexture2D(scope_, GL_RGBA16F, tw, th);
    reflection_ = gl::createTexture2D(scope_, GL_RGBA16F, tw, th);
    occlusion_ = gl::createTexture2D(scope_, GL_R16F, tw, th);
    info_ = gl::createTexture2D(scope_, GL_RGBA16F, tw, th);
    for (int i = 0; i < 2; ++i) {
        history_[i] = gl::createTexture2D(scope_, GL_RGBA16F, tw, th);
        historyDistance_[i] = gl::createTexture2D(scope_, GL_R32F, tw, th);
    }
    diffuse_ = gl::createTexture2D(scope_, GL_RGBA16F, settings.width, settings.height);
    specular_ = gl::createTexture2D(scope_, GL_RGBA16F, settings.width, settings.height);
    ao_ = gl::createTexture2D(scope_, GL_R16F, settings.width, settings.height);
    // Filtered lookups (the lighting pass reads the contract's terms with texture()).
    for (const gl::Texture* t : {&diffuse_, &specular_, &ao_}) {
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    traceProgram_ = buildProgram(kTraceProgram);
    temporalProgram_ = buildProgram(kTemporalProgram);
    filterProgram_ = buildProgram(kFilterProgram);
    debugProgram_ = buildProgram(kDebugProgram);
}

// The volume rebuilds what the change touched; the camera is handled by reprojection, and
// anything that changes what a ray sees starts the history over.
void SdfGiPass::invalidate(Changes c) {
    if (c & (ChangeGeometry | ChangeMaterials | ChangeLights | ChangeLiveParams)) hasHistory_ = false;
    if (field_) field_->invalidate(c);
    changed_ = true;
}

// Probes: converged. Rays: the history has had its frames to converge (framesToConverge).
bool SdfGiPass::settled() const {
    if (changed_) return false;
    if (field_) return field_->converged() && screenReflection_->settled();
    return temporal_ > 0.0f && historyFrames_ >= sdfFramesToConverge(temporal_);
}

Pass::Progress SdfGiPass::progress() const {
    return field_ ? screenReflection_->progress(field_->progress(), field_->converged()) : Progress{};
}

std::optional<RayCounts> SdfGiPass::raysTraced() const {
    if (!field_) return std::nullopt;
    return field_->raysTraced();
}

void SdfGiPass::setCommonUniforms(GLuint p, const Frame& frame) const {
    glProgramUniformMatrix4fv(p, UG_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UG_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, UG_SCALE, scale_);
    glBindSamplers(TG_DEPTH, TG_DEBUG_INFO + 1 - TG_DEPTH, nullptr);  // every unit of the method's programs
    gl::bindTextures({{TG_DEPTH, frame.texture(resource::kGbufferDepth)}, {TG_NORMAL, frame.texture(resource::kGbufferNormal)},
                      {TG_MATERIAL, frame.texture(resource::kGbufferMaterial)}});
}

void SdfGiPass::trace(const Frame& frame, const SdfGiSettings& s) {
    const GLuint p = traceProgram_.id();
    glUseProgram(p);
    setCommonUniforms(p, frame);
    frame.bindEnvironment();
    sdf::SdfMarchBlock march;
    march.hitThreshold = s.hitThreshold;
    march.relaxation = s.relaxation;
    march.maxSteps = s.maxSteps;
    march.offset = s.offset;
    march_.set(march);
    // With probes, the rays of a pixel whose gather sees none of them (the shader's fallback).
    glProgramUniform1i(p, UG_RAYS, s.rays);
    glProgramUniform1ui(p, UG_FRAME, GLuint(frame.index * 7919u + frame.settings.seed));
    SdfTraceBlock trace;
    // With the probes the screen reflection gives indirect.specular: no mirror ray here.
    trace.specular = !field_ && s.mode() == probes::Reflection::Rays ? 1 : 0;
    trace.specularRoughness = s.reflectionRoughness;
    trace.probeGather = field_ ? 1 : 0;
    trace.probeVisibility = probes::visibilityMode(true, built_.probeField().pathTest);
    trace.gatherBias = built_.probeField().normalBias;
    traceBlock_.set(trace);
    glProgramUniform1f(p, UG_AO, s.aoStrength);
    if (field_) field_->bindForGather(p);
    std::vector<glm::vec4> volumes;
    const DistanceField& field = volume_->field();
    for (int i = 0; i < field.layers(); ++i) {
        const SdfVolume& v = field.volume(i);
        volumes.emplace_back(v.origin, v.size);
    }
    glProgramUniform4fv(p, UG_CASCADES, GLsizei(volumes.size()), &volumes[0][0]);
    glProgramUniform1i(p, UG_CASCADE_COUNT, field.layers());
    glProgramUniform1i(p, UG_RESOLUTION, volume_->layout().resolution());
    volume_->bind();
    glBindImageTexture(IG_TRACE_DIFFUSE, raw_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IG_TRACE_REFLECTION, reflection_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IG_TRACE_AO, occlusion_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    glBindImageTexture(IG_TRACE_INFO, info_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch2D(raw_.width, raw_.height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void SdfGiPass::accumulate(const Frame& frame, const SdfGiSettings& s) {
    const GLuint p = temporalProgram_.id();
    glUseProgram(p);
    setCommonUniforms(p, frame);
    glProgramUniformMatrix4fv(p, UG_PREV_VIEW_PROJ, 1, GL_FALSE, &prevViewProj_[0][0]);
    glProgramUniform3fv(p, UG_PREV_CAMERA_POS, 1, &prevCameraPos_[0]);
    const bool moved = frame.camera.viewProj != prevViewProj_;
    SdfTemporalBlock temporal;
    temporal.maxWeight = s.temporal;
    temporal.hasHistory = hasHistory_ ? 1 : 0;
    temporal.cameraMoved = moved ? 1 : 0;
    temporalBlock_.set(temporal);
    gl::bindTextures({{TG_TEMPORAL_CURRENT, raw_.id()}, {TG_TEMPORAL_HISTORY, history_[current_].id()},
                      {TG_TEMPORAL_HISTORY_DISTANCE, historyDistance_[current_].id()}});
    const int next = 1 - current_;
    glBindImageTexture(IG_TEMPORAL_HISTORY, history_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IG_TEMPORAL_HISTORY_DISTANCE, historyDistance_[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    dispatch2D(raw_.width, raw_.height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    current_ = next;
}

void SdfGiPass::filter(const Frame& frame, const SdfGiSettings& s) {
    const GLuint p = filterProgram_.id();
    glUseProgram(p);
    setCommonUniforms(p, frame);
    glProgramUniform1i(p, UG_FILTER, s.filterRadius);
    glProgramUniform1f(p, UG_INTENSITY, s.intensity);
    // SDFGI's gathered diffuse needs no history: it is not noisy.
    gl::bindTextures({{TG_FILTER_DIFFUSE, field_ ? raw_.id() : history_[current_].id()},
                      {TG_FILTER_REFLECTION, reflection_.id()}, {TG_FILTER_OCCLUSION, occlusion_.id()}});
    glBindImageTexture(IG_FILTER_DIFFUSE, diffuse_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IG_FILTER_SPECULAR, specular_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IG_FILTER_AO, ao_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatch2D(diffuse_.width, diffuse_.height);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void SdfGiPass::run(Frame& frame) {
    const SdfGiSettings live = sdfParams().read("sdf", frame.settings.params);
    if (field_) {
        probes::followCascades(*field_, *volume_, sceneBounds_, built_.probeSpacing);
        field_->update(frame, built_.probeField());
    }
    {
        auto t = frame.step("trace");
        trace(frame, live);
    }
    if (!field_) {
        auto t = frame.step("temporal");
        accumulate(frame, live);
    }
    {
        auto t = frame.step("filter");
        filter(frame, live);
    }
    if (field_) {
        auto t = frame.step("reflection");
        // SDF GI's gather lights a pixel no probe sees with rays of its own (sdf.rays).
        screenReflection_->run(frame, *field_, built_.probeField(), diffuse_, live, changed_, 0.0f);
    }
    prevViewProj_ = frame.camera.viewProj;
    prevCameraPos_ = frame.camera.position;
    temporal_ = live.temporal;
    historyFrames_ = hasHistory_ ? historyFrames_ + 1 : 1;
    hasHistory_ = true;
    changed_ = false;
    frame.put(resource::kIndirectDiffuse, diffuse_);
    frame.put(resource::kIndirectSpecular, field_ ? screenReflection_->result() : specular_);
    frame.put(resource::kAo, ao_);
}

std::vector<std::string> SdfGiPass::stats() const {
    const CascadeLayout& layout = volume_->layout();
    char line[200];
    const char* from = built_.cascades > 0 ? "sdf.cascades" : built_.cascadeExtent > 0.0f ? "sdf.cascade-extent" : "the view depth";
    std::snprintf(line, sizeof line, "%d cascade%s (from %s; scene cube %.4g world units, the finest %.4g)", layout.count,
                  layout.count > 1 ? "s" : "", from, double(layout.scene.size), double(layout.extent(0)));
    std::vector<std::string> out = {line};
    if (field_) out.push_back("SDFGI " + field_->describe());
    if (field_) out.push_back(screenReflection_->describe());
    for (int i = 0; i < layout.count; ++i) out.push_back(volume_->describeCascade(i));
    return out;
}

std::vector<DebugViewDesc> SdfGiPass::debugViews() const {
    std::vector<DebugViewDesc> views = {{"sdf.slice", "one slice of the signed distance field (sdf.slice-axis, sdf.slice-position): blue outside, "
                          "red inside, a band per cell, black on the surface"},
            {"sdf.steps", "sphere-tracing steps per diffuse ray (sdf.diffuse=rays), black 0 to white sdf.max-steps"},
            {"sdf.normals", "the normal at the first diffuse ray's hit (sdf.diffuse=rays; x 0.5 + 0.5), black where it "
                            "missed"},
            {"ao", "the near-field soft occlusion written to \"ao\" (1 = open)"}};
    if (field_)
        for (const DebugViewDesc& d : field_->debugViews("sdf.probes", "the middle probe of the finest grid"))
            views.push_back(d);
    return views;
}

void SdfGiPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    if (view == "ao") {
        drawChannel(DisplayChannel::Grey, ao_.id(), frame, target);
        return;
    }
    const std::string probeViews = "sdf.probes.";
    if (field_ && view.compare(0, probeViews.size(), probeViews) == 0) {
        field_->drawDebugView(view.substr(probeViews.size()), frame, target, built_.probeField());
        return;
    }
    const SdfGiSettings live = sdfParams().read("sdf", frame.settings.params);
    const GLuint p = debugProgram_.id();
    const int cascade = std::min(live.sliceCascade, volume_->cascadeCount() - 1);
    const SdfVolume& v = volume_->field().volume(cascade);
    glUseProgram(p);
    glProgramUniform4f(p, UG_VOLUME, v.origin.x, v.origin.y, v.origin.z, v.size);
    glProgramUniform1i(p, UG_RESOLUTION, v.resolution);
    glProgramUniform1i(p, UG_SLICE_CASCADE, cascade);
    glProgramUniform1i(p, UG_SCALE, scale_);
    SdfDebugBlock debug;
    debug.view = view == "sdf.slice" ? 0 : view == "sdf.steps" ? 1 : 2;
    debug.sliceAxis = live.sliceAxis;
    debug.slicePosition = live.slicePosition;
    debug.maxSteps = live.maxSteps;
    debug_.set(debug);
    glBindSamplers(TG_DEPTH, TG_DEBUG_INFO + 1 - TG_DEPTH, nullptr);
    volume_->bind();
    glBindTextureUnit(TG_DEBUG_INFO, info_.id());
    glBindImageTexture(IG_DEBUG_TARGET, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch2D(diffuse_.width, diffuse_.height);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

GiMethod sdfMethod() {
    GiMethod m;
    m.name = "sdf";
    m.summary = "SDF GI: jump-flooded distance field, sphere-traced rays shaded from voxel radiance, temporal + "
                "edge-aware filter";
    m.environmentLightByDefault = true;
    m.params = sdfParams().rows;
    m.shaderTables.uniforms = tableRows(sdfgi::kSdfGiUniforms);
    m.shaderTables.bindings = tableRows(sdfgi::kSdfGiBindings);
    m.shaderTables.blocks = {sdfgi::SdfDebugBlock::desc(), sdfgi::SdfTraceBlock::desc(), sdfgi::SdfTemporalBlock::desc()};
    m.presets = {
        {"low", "32^3, one volume, plain JFA, probes every 1/3 with 64 rays, 32 steps",
         {{"sdf.resolution", {32.0}},
          {"sdf.cascades", {1.0}},
          {"sdf.jfa", ParamValue::choice("plain")},
          {"sdf.probe-spacing", {0.34}},
          {"sdf.probe-rays", {64.0}},
          {"sdf.max-steps", {32.0}}}},
        {"medium", "64^3, JFA+2, probes every 1/8 with 32 rays, gathered and mirror rays at half resolution, 64 steps", {}},
        {"high", "128^3, JFA+2, probes every 1/8 with 128 rays, mirror rays at full resolution, 128 steps",
         {{"sdf.resolution", {128.0}},
          {"sdf.probe-rays", {128.0}},
          {"sdf.trace-scale", ParamValue::choice("1")},
          {"sdf.max-steps", {128.0}}}},
        {"realtime",
         "medium's probes within a budget of 8192 rays per frame (256 probes), gathered, mirror rays and occlusion every "
         "4x4 pixels and upsampled, the sky through its own rays (no environment light in the direct pass)",
         {{"sdf.probe-ray-budget", {8192.0}},
          {"sdf.trace-scale", ParamValue::choice("4")},
          {"sdf.filter-radius", {0.0}},
          {"emitters.environment", ParamValue::choice("false")}}},
    };
    m.programs = &SdfGiPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) { return SdfGiPass::estimateMemory(scene, s); };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<SdfGiPass>(b.services, b.settings)); };
    m.framesToConverge = [](const RenderSettings& s) {
        const SdfGiSettings g = sdfParams().read("sdf", s.params);
        // Probes: until none is due (render stops there: progress()), at most max-updates each.
        return g.probeGather() ? std::min(g.probeField().maxUpdates, 200) : sdfFramesToConverge(g.temporal);
    };
    return m;
}

}  // namespace gis
