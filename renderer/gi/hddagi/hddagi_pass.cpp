#include "gi/hddagi/hddagi_pass.h"

#include <algorithm>
#include <cstdio>

#include "gi/hddagi/hddagi_uniforms.h"
#include "gi/method.h"
#include "gl/dispatch.h"
#include "services/scene_services.h"

namespace gis {

using namespace hddagi;

namespace {
const ProgramDesc kDebugProgram{"hddagi_debug", {"gi/hddagi/hddagi_debug.comp"}, {}};

// What HDDAGI asks of the scene volume: cascades of voxels and their light, the occupancy
// hierarchy instead of a distance field, and cascades that scroll.
VolumeRequest volumeRequest(const HddagiSettings& s) {
    VolumeRequest r;
    r.method = "hddagi";
    r.resolution = s.resolution;
    r.resolutionKey = "hddagi.resolution";
    r.occupancy = true;
    r.albedoAtlas = true;  // the probes' rays light their hits' multi-bounce by it
    r.scroll = true;
    r.cascades = s.cascades;
    r.cascadeExtent = s.cascadeExtent;
    return r;
}

// The settings, once checkHddagiSettings has found them valid (it throws, naming the parameter).
HddagiSettings checkedSettings(const RenderSettings& settings) {
    const HddagiSettings s = hddagiParams().read(HddagiPass::kName, settings.params);
    checkHddagiSettings(s);
    return s;
}

// What is fixed when the pass is built, from valid settings.
probes::ProbeFieldShape shapeOf(const HddagiSettings& s) {
    return {volumeRequest(s), s.probeSpacing, s.field(), s.gatherScale()};
}
}  // namespace

std::vector<ProgramDesc> HddagiPass::programs() {
    std::vector<ProgramDesc> all = ProbeFieldPass::programs(volumeRequest(HddagiSettings{}));
    all.push_back(kDebugProgram);
    return all;
}

std::vector<std::pair<std::string, uint64_t>> HddagiPass::estimateMemory(const Scene& scene, const RenderSettings& settings) {
    return ProbeFieldPass::estimateMemory("HDDAGI", scene, settings, shapeOf(hddagiParams().read(kName, settings.params)));
}

HddagiPass::HddagiPass(SceneServices& services, const RenderSettings& settings)
    : HddagiPass(services, settings, checkedSettings(settings)) {}

HddagiPass::HddagiPass(SceneServices& services, const RenderSettings& settings, const HddagiSettings& valid)
    : ProbeFieldPass(kName, services.volume(volumeRequest(valid)), services.ledger, services.bounds(), settings,
                     shapeOf(valid)),
      built_(valid), slice_({&services.ledger, kName}) {
    debugProgram_ = buildProgram(kDebugProgram);
}

probes::ProbeFieldLive HddagiPass::live(const RenderSettings& settings) const {
    const HddagiSettings s = hddagiParams().read(kName, settings.params);
    return {s.field(), s.gather(), s};
}

std::vector<std::string> HddagiPass::stats() const {
    const SceneVolume::Builds all = volume_->builds();
    char line[240];
    std::snprintf(line, sizeof line, "occupancy %d cascades of %d^3 voxels (%.1f KiB of masks); %d voxelizations, %d scrolls, "
                  "%lld cells voxelized in all",
                  volume_->cascadeCount(), volume_->layout().resolution(),
                  double(occupancyBytes(volume_->layout().resolution(), volume_->cascadeCount())) / 1024.0,
                  all.voxelizations, all.scrolls, static_cast<long long>(all.voxelizedCells));
    return ProbeFieldPass::stats(line);
}

std::vector<DebugViewDesc> HddagiPass::debugViews() const {
    std::vector<DebugViewDesc> views{
        {"hddagi.occupancy", "one slice of the occupancy hierarchy (hddagi.slice-axis, -position, -cascade, -level): "
                             "white where the level's voxel, block or region is occupied, a grid line per block"},
        {"hddagi.steps", "HDDA traversal steps of each pixel's camera ray through the cascades, as a heat map "
                         "(black 0, blue, green, red to white at hddagi.steps-max)"}};
    for (const DebugViewDesc& d : field_->debugViews("hddagi.probes", "the middle probe of the finest grid"))
        views.push_back(d);
    return views;
}

void HddagiPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    const HddagiSettings live = hddagiParams().read(kName, frame.settings.params);
    const std::string probeViews = "hddagi.probes.";
    if (view.compare(0, probeViews.size(), probeViews) == 0) {
        field_->drawDebugView(view.substr(probeViews.size()), frame, target, live.field());
        return;
    }
    const GLuint p = debugProgram_.id();
    glUseProgram(p);
    glm::vec4 cascades[kMaxCascades]{};
    for (int i = 0; i < volume_->cascadeCount(); ++i) {
        const SdfVolume v = volume_->cascadeVolume(i);
        cascades[i] = glm::vec4(v.origin, v.size);
    }
    glProgramUniformMatrix4fv(p, UH_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UH_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform4fv(p, UH_CASCADES, kMaxCascades, &cascades[0][0]);
    glProgramUniform1i(p, UH_CASCADE_COUNT, volume_->cascadeCount());
    glProgramUniform1i(p, UH_RESOLUTION, volume_->layout().resolution());
    glProgramUniform1i(p, UH_VIEW, view == "hddagi.steps" ? 1 : 0);
    const int cascade = std::min(live.sliceCascade, volume_->cascadeCount() - 1);
    HddagiSliceBlock slice;
    slice.axis = live.sliceAxis;
    slice.position = live.slicePosition;
    slice.cascade = cascade;
    slice.level = live.sliceLevel;
    slice_.set(slice);
    glProgramUniform1i(p, UH_STEPS_MAX, live.stepsMax);
    volume_->bind();
    glBindImageTexture(hddagi::IH_DEBUG_TARGET, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    const int w = frame.settings.width, h = frame.settings.height;
    gl::dispatchCompute(gl::groupsFor(w, 8), gl::groupsFor(h, 8), 1, "hddagi debug");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

GiMethod hddagiMethod() {
    GiMethod m;
    m.name = "hddagi";
    m.summary = "HDDAGI: probes traced by hierarchical DDA through voxel occupancy (no distance field), cascades "
                "that scroll, gathered at half resolution";
    m.environmentLightByDefault = true;
    m.params = hddagiParams().rows;
    m.shaderTables.uniforms = tableRows(hddagi::kHddagiUniforms);
    m.shaderTables.bindings = tableRows(hddagi::kHddagiBindings);
    m.shaderTables.blocks = {hddagi::HddagiSliceBlock::desc()};
    m.presets = {
        {"low", "32^3, probes every 1/3 with 64 rays, SH L1",
         {{"hddagi.resolution", {32.0}},
          {"hddagi.spacing", {0.34}},
          {"hddagi.rays", {64.0}},
          {"hddagi.storage", ParamValue::choice("sh1")}}},
        {"medium", "64^3, probes every 1/5 with 128 rays, SH L2, gathered at half resolution", {}},
        {"high", "128^3, probes every 1/6 with 256 rays, octahedral maps, gathered at full resolution",
         {{"hddagi.resolution", {128.0}},
          {"hddagi.spacing", {0.167}},
          {"hddagi.rays", {256.0}},
          {"hddagi.storage", ParamValue::choice("octahedral")},
          {"hddagi.half-res", {0.0}}}},
        {"realtime",
         "medium's probes within a budget of 8192 rays per frame (64 probes), the sky through its own rays (no "
         "environment light in the direct pass)",
         {{"hddagi.ray-budget", {8192.0}}, {"emitters.environment", ParamValue::choice("false")}}},
    };
    m.programs = &HddagiPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) { return HddagiPass::estimateMemory(scene, s); };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<HddagiPass>(b.services, b.settings)); };
    // Until no probe is due (render stops there: progress()), at most max-updates each.
    m.framesToConverge = [](const RenderSettings& s) {
        return std::min(hddagiParams().read("hddagi", s.params).maxUpdates, 200);
    };
    return m;
}

}  // namespace gis
