#include "gi/probes/probes_pass.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gi/method.h"
#include "gl/dispatch.h"
#include "probes/probe_uniforms.h"
#include "services/scene_services.h"
#include "voxel/voxelizer.h"

namespace gis {

using namespace probes;

namespace {
ParamValue choiceValue(const char* name) {
    ParamValue v;
    v.text = name;
    return v;
}
}  // namespace

const ProgramDesc kShadeProgram{"probe_shade", {"gi/probes/probe_shade.comp"}, {}};
const ProgramDesc kUpsampleProgram{"probe_upsample", {"gi/probes/probe_upsample.comp"}, {}};

std::vector<ProgramDesc> ProbesPass::programs() {
    std::vector<ProgramDesc> all = Voxelizer::programs();
    for (const auto& list : {VoxelRadiance::programs(), DistanceField::programs(), fieldPrograms()})
        all.insert(all.end(), list.begin(), list.end());
    all.push_back(kShadeProgram);
    all.push_back(kUpsampleProgram);
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
    : built_(probeParams().read("probes", settings.params)) {
    checkProbeSettings(built_);
    const gl::MemoryScope scope{&services.ledger, name()};
    volume_ = &services.volume(volumeRequest(built_));
    field_ = std::make_unique<ProbeField>(scope, *volume_, std::vector<ProbeGrid>{fitProbeGrid(services.bounds(), built_.spacing)},
                                          built_.field());
    diffuse_ = gl::createTexture2D(scope, GL_RGBA16F, settings.width, settings.height);
    shadeProgram_ = buildProgram(kShadeProgram);
    const int k = built_.gatherPixels();
    if (k > 1) {
        gathered_ = gl::createTexture2D(scope, GL_RGBA16F, (settings.width + k - 1) / k, (settings.height + k - 1) / k);
        upsampleProgram_ = buildProgram(kUpsampleProgram);
    }
}

// The scene volume rebuilds what the change touched (a light edit relights it alone); the probes
// restart, so the new light is followed at once.
void ProbesPass::invalidate(Changes c) {
    field_->invalidate(c);
    changed_ = true;
}

// The gather (probe_gather.glsl) into indirect.diffuse, or at 1/probes.gather-scale and upsampled.
void ProbesPass::shade(const Frame& frame, const ProbeSettings& s) {
    const int k = built_.gatherPixels();
    const GLuint gbuffer[2] = {frame.texture(resource::kGbufferDepth), frame.texture(resource::kGbufferNormal)};
    auto run = [&](GLuint p, const gl::Texture& out) {
        glUseProgram(p);
        field_->bindForGather(p);
        glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
        glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
        glProgramUniform4f(p, UP_SHADE_PARAMS, s.normalBias, s.intensity, s.visibility ? 1.0f : 0.0f, 0.0f);
        glProgramUniform1i(p, UP_GATHER_SCALE, k);
        glBindTextures(4, 2, gbuffer);
        glBindSamplers(4, 3, nullptr);
        glBindImageTexture(0, out.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        gl::dispatchCompute(gl::groupsFor(out.width, 8), gl::groupsFor(out.height, 8), 1, "probes");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    };
    if (k == 1) {
        run(shadeProgram_.id(), diffuse_);
        return;
    }
    run(shadeProgram_.id(), gathered_);
    glBindTextureUnit(6, gathered_.id());
    run(upsampleProgram_.id(), diffuse_);
}

Pass::Progress ProbesPass::progress() const { return field_->progress(); }

void ProbesPass::execute(Frame& frame) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    volume_->update(frame);
    field_->update(frame, live.field());
    {
        auto t = frame.step("shade");
        shade(frame, live);
    }
    frame.put(resource::kIndirectDiffuse, diffuse_);
    changed_ = false;
}

std::vector<DebugViewDesc> ProbesPass::debugViews() const { return field_->debugViews("probes", "probe probes.debug-probe"); }

void ProbesPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    const ProbeSettings live = probeParams().read("probes", frame.settings.params);
    field_->drawDebugView(view.substr(std::string("probes.").size()), frame, target, live.field());
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
        {"realtime", "high's probes within 16384 rays per frame (64 probes), gathered every 4x4 pixels and upsampled",
         {{"probes.spacing", {0.167}},
          {"probes.rays", {256.0}},
          {"probes.storage", choiceValue("octahedral")},
          {"probes.ray-budget", {16384.0}},
          {"probes.gather-scale", choiceValue("4")}}},
    };
    m.programs = &ProbesPass::programs;
    m.estimateMemory = [](const Scene& scene, const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        const int probes = fitProbeGrid(scene.bounds, p.spacing).count();
        const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
        return std::vector<std::pair<std::string, uint64_t>>{
            {"probe voxels and distance field", uint64_t(sceneVolumeBytes(volumeRequest(p), 1))},
            {"probes (irradiance, distance moments, state)", uint64_t(fieldStorageBytes(p.field(), probes))},
            {"probe rays", uint64_t(fieldRayBytes(p.field(), probes))},
            {"probe screen target", pixels * 8}};
    };
    m.addPasses = [](MethodBuild& b) { b.add(std::make_unique<ProbesPass>(b.services, b.settings)); };
    // Updates stop when converged or after max-updates; the bench renders this many frames first.
    // Capped so that a huge max-updates cannot stall it; with a probes.ray-budget below the probe
    // count a pass over all probes takes several frames, which this cannot know (it sees no
    // scene): such a bench row may be scored before convergence.
    m.framesToConverge = [](const RenderSettings& s) {
        const ProbeSettings p = probeParams().read("probes", s.params);
        return std::min(p.maxUpdates, 200);
    };
    return m;
}

std::vector<std::string> ProbesPass::stats() const {
    return {field_->describe(), describeVolume(volume_->grid().fit, "voxels / distance-field cells")};
}

}  // namespace gis
