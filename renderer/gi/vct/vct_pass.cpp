#include "gi/vct/vct_pass.h"

#include <cmath>

#include "gl/dispatch.h"
#include "debug_view.h"
#include "gi/method.h"
#include "services/scene_services.h"
#include "voxel/voxel_uniforms.h"

namespace gis {

using namespace voxel;

namespace {
ConeSettings coneSettingsOf(const VctSettings& s) {
    return {s.coneSet, s.stepFactor, s.maxDistance * float(s.resolution), s.offset};
}

ParamValue choiceValue(const char* name) {
    ParamValue v;
    v.text = name;
    return v;
}
}  // namespace

std::vector<ProgramDesc> VctPass::programs() {
    std::vector<ProgramDesc> all = Voxelizer::programs();
    for (const ProgramDesc& p : VoxelRadiance::programs()) all.push_back(p);
    all.push_back({"vct_debug", {"gi/vct/vct_debug.comp"}, {}});
    all.push_back({"vct_trace", {"gi/vct/vct_trace.comp"}, {}});
    return all;
}

VctPass::VctPass(const GpuScene& scene, const RenderSettings& settings, gl::MemoryLedger& ledger)
    : built_(vctParams().read("vct", settings.params)), live_(built_) {
    checkVctSettings(built_);
    // Everything is charged to the pass, so --timings, info and the panel show the method's whole
    // footprint on its row (the README lists it per texture).
    const gl::MemoryScope voxels{&ledger, name()}, radiance{&ledger, name()}, trace{&ledger, name()};
    const int n = built_.resolution;
    // Refuse before allocating anything: the whole method's voxel memory at once.
    checkVoxelBudget(n, voxelGridBytes(n) + voxelRadianceBytes(n, built_.anisotropic, built_.bounces),
                     "vct.resolution");
    // A margin of a whole number and a half voxels: the bounds (a room's walls) then lie mid-voxel
    // instead of on a voxel boundary, where float rounding at another scene scale would flip them
    // between one and two voxel layers (and change the light by a few percent). The margin's empty
    // voxels make coarse texels at the bounds partly transparent, and cones escape through them
    // (the emissive furnace loses 26% at 32^3, 13% at 64^3 with 2.5 voxels and back faces culled;
    // 7% and 3% with 0.5): so half a voxel with culling. The opaque mode keeps 2.5, which its
    // measured tuning (README) was made with: there its cones' own surfaces stand in for the loss.
    const bool cull = built_.backfaces == 1;
    const float margin = cull ? 0.5f : 2.5f;
    voxelizer_ = std::make_unique<Voxelizer>(fitVolume(scene.cpu.bounds, n, margin), built_.conservativeMode(), voxels);
    radiance_ = std::make_unique<VoxelRadiance>(n, built_.anisotropic, built_.bounces, radiance, cull);
    diffuse_ = gl::createTexture2D(trace, GL_RGBA16F, settings.width, settings.height);
    specular_ = gl::createTexture2D(trace, GL_RGBA16F, settings.width, settings.height);
    ao_ = gl::createTexture2D(trace, GL_R16F, settings.width, settings.height);
    const auto all = programs();
    traceProgram_ = buildProgram(all.back());
    debugProgram_ = buildProgram(all[all.size() - 2]);
}

void VctPass::relight(Frame& frame) {
    injectFrameLights(frame, voxelizer_->grid(), *radiance_);
    ++injections_;
    {
        auto t = frame.step("mips");
        radiance_->buildMips(voxelizer_->grid());
    }
    if (built_.bounces > 1) {  // further bounces re-light the voxels: timed as their own step
        auto t = frame.step("bounce");
        VctSettings cones = live_;
        cones.resolution = built_.resolution;
        radiance_->bounce(voxelizer_->grid(), coneSettingsOf(cones),
                          frame.settings.background.value_or(frame.scene.cpu.background));
    }
}

void VctPass::trace(const Frame& frame, const VctSettings& s) {
    const GLuint p = traceProgram_.id();
    const VolumeFit& fit = voxelizer_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    const glm::vec3 environment = frame.settings.background.value_or(frame.scene.cpu.background);
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UV_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, UV_CONE_SET, s.coneSet);
    glProgramUniform4f(p, UV_TRACE_PARAMS, s.stepFactor, s.maxDistance * float(fit.resolution), s.offset,
                       s.specular ? 1.0f : 0.0f);
    glProgramUniform3fv(p, UV_ENVIRONMENT, 1, &environment[0]);
    glProgramUniform1i(p, UV_ANISOTROPIC, radiance_->mipMode());
    glProgramUniform1f(p, UV_INTENSITY, s.intensity);
    const GLuint gbuffer[3] = {frame.texture("gbuffer.depth"), frame.texture("gbuffer.normal"),
                               frame.texture("gbuffer.material")};
    glBindTextures(0, 3, gbuffer);
    glBindSamplers(0, 3, nullptr);
    radiance_->bind(4);
    glBindImageTexture(0, diffuse_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, specular_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(2, ao_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    gl::dispatchCompute(gl::groupsFor(diffuse_.width, 8), gl::groupsFor(diffuse_.height, 8), 1, "vct");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

std::vector<DebugViewDesc> VctPass::debugViews() const {
    return {{"vct.voxels", "the voxel grid ray-marched from the camera (vct.debug-channel, vct.debug-level)"},
            {"vct.slice", "one slice of the voxel grid (vct.slice-axis, vct.slice-position, vct.debug-channel)"},
            {"vct.ao", "the diffuse cones' occlusion (1 = open), already part of indirect.diffuse"}};
}

void VctPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    if (view == "vct.ao") {
        drawChannel(DisplayChannel::Grey, ao_.id(), frame, target);
        return;
    }
    const VctSettings live = vctParams().read("vct", frame.settings.params);
    const GLuint p = debugProgram_.id();
    const VolumeFit& fit = voxelizer_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    const bool slice = view == "vct.slice";
    glProgramUniform4f(p, UV_DEBUG_PARAMS, float(live.debugChannel), float(live.debugLevel),
                       slice ? float(live.sliceAxis) : -1.0f, live.slicePosition);
    const GLuint textures[3] = {voxelizer_->grid().albedo.id(), voxelizer_->grid().emission.id(),
                                radiance_->radiance().id()};
    glBindTextures(0, 3, textures);
    glBindSamplers(0, 3, nullptr);
    glBindImageTexture(0, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(diffuse_.width, 8), gl::groupsFor(diffuse_.height, 8), 1, "vct");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VctPass::execute(Frame& frame) {
    live_ = vctParams().read("vct", frame.settings.params);
    reused_ = voxelsValid_ && radianceValid_;
    if (!voxelsValid_) {
        voxelizeFrame(frame, *voxelizer_);
        ++voxelizations_;
        voxelsValid_ = true;
        radianceValid_ = false;
    }
    if (!radianceValid_) relight(frame);
    radianceValid_ = true;
    {
        auto t = frame.step("trace");
        trace(frame, live_);
    }
    frame.put("indirect.diffuse", diffuse_);
    frame.put("indirect.specular", specular_);
    frame.put("voxel.radiance", radiance_->radiance());
}

GiMethod vctMethod() {
    GiMethod m;
    m.name = "vct";
    m.summary = "voxel cone tracing: conservative voxelization, shadow-mapped light injection, cone-traced indirect";
    m.params = vctParams().rows;
    m.presets = {
        {"low", "32^3, isotropic mips, four cones, step 1, no specular cone",
         {{"vct.resolution", {32.0}},
          {"vct.anisotropic", {0.0}},
          {"vct.step", {1.0}},
          {"vct.specular", {0.0}},
          {"vct.cones", choiceValue("four")}}},
        {"medium", "64^3, directional mips, six cones", {}},
        {"high", "128^3, directional mips, two bounces, step 0.33",
         {{"vct.resolution", {128.0}}, {"vct.bounces", {2.0}}, {"vct.step", {0.33}}}},
    };
    m.programs = &VctPass::programs;
    m.estimateMemory = [](const Scene&, const RenderSettings& s) {
        const VctSettings v = vctParams().read("vct", s.params);
        const uint64_t n = uint64_t(v.resolution), pixels = uint64_t(s.width) * uint64_t(s.height);
        return std::vector<std::pair<std::string, uint64_t>>{
            {"VCT voxel grid and voxelization sums", uint64_t(voxelGridBytes(int(n)))},
            {"VCT radiance mips", uint64_t(voxelRadianceBytes(int(n), v.anisotropic, v.bounces))},
            {"VCT screen targets", pixels * 18}};
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<VctPass>(b.services.scene, b.settings, b.ledger)); };
    m.framesToConverge = [](const RenderSettings&) { return 1; };
    return m;
}

}  // namespace gis
