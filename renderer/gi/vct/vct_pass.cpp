#include "gi/vct/vct_pass.h"

#include <cmath>

#include "voxel/voxel_uniforms.h"

namespace gis {

using namespace voxel;

std::vector<ProgramDesc> VctPass::programs() {
    std::vector<ProgramDesc> all = Voxelizer::programs();
    for (const ProgramDesc& p : VoxelRadiance::programs()) all.push_back(p);
    all.push_back({"vct_debug", {"gi/vct/vct_debug.comp"}, {}});
    all.push_back({"vct_trace", {"gi/vct/vct_trace.comp"}, {}});
    return all;
}

const char* VctPass::stepName(int step) {
    static const char* const names[StepCount] = {"voxelize", "inject", "mips", "trace"};
    return step >= 0 && step < StepCount ? names[step] : "?";
}

VctPass::VctPass(const GpuScene& scene, const VctSettings& settings, int width, int height, gl::MemoryLedger& ledger)
    : settings_(settings) {
    checkVctSettings(settings_);
    const gl::MemoryScope voxels{&ledger, "vct.voxels"}, radiance{&ledger, "vct.radiance"}, trace{&ledger, name()};
    const int n = settings_.resolution;
    // Refuse before allocating anything: the whole method's voxel memory at once.
    checkVoxelBudget(n, voxelGridBytes(n) + voxelRadianceBytes(n, settings_.anisotropic, settings_.bounces),
                     "vct.resolution");
    voxelizer_ = std::make_unique<Voxelizer>(fitVolume(scene.cpu.bounds, n), settings_.conservative, voxels);
    radiance_ = std::make_unique<VoxelRadiance>(n, settings_.anisotropic, settings_.bounces, radiance);
    diffuse_ = gl::createTexture2D(trace, GL_RGBA16F, width, height);
    specular_ = gl::createTexture2D(trace, GL_RGBA16F, width, height);
    ao_ = gl::createTexture2D(trace, GL_R16F, width, height);
    debug_ = gl::createTexture2D(trace, GL_RGBA16F, width, height);
    const auto all = programs();
    traceProgram_ = buildProgram(all.back());
    debugProgram_ = buildProgram(all[all.size() - 2]);
}

void VctPass::setLiveSettings(const VctSettings& s) {
    VctSettings next = settings_;
    next.coneSet = s.coneSet;
    next.stepFactor = s.stepFactor;
    next.maxDistance = s.maxDistance;
    next.offset = s.offset;
    next.intensity = s.intensity;
    next.specular = s.specular;
    next.debugView = s.debugView;
    next.debugChannel = s.debugChannel;
    next.debugLevel = s.debugLevel;
    next.sliceAxis = s.sliceAxis;
    next.slicePosition = s.slicePosition;
    checkVctSettings(next);
    settings_ = next;
}

static ConeSettings coneSettingsOf(const VctSettings& s) {
    return {s.coneSet, s.stepFactor, s.maxDistance * float(s.resolution), s.offset};
}

void VctPass::rebuildVoxels(const Frame& frame) {
    stepTimers_[Voxelize].begin();
    voxelizer_->voxelize(frame.scene);
    stepTimers_[Voxelize].end();

    stepTimers_[Inject].begin();
    VoxelRadiance::Lights lights;
    lights.buffer = frame.buffer("lights");
    lights.shadowMaps = frame.texture("shadow.maps");
    lights.shadowCubes = frame.texture("shadow.cubes");
    lights.count = int(frame.scene.cpu.lights.size());
    lights.shadows = frame.settings.shadows;
    radiance_->inject(voxelizer_->grid(), lights);
    stepTimers_[Inject].end();

    stepTimers_[Mips].begin();
    radiance_->buildMips(voxelizer_->grid());
    stepTimers_[Mips].end();
    if (settings_.bounces > 1) {  // further bounces count as injection: they re-light the voxels
        stepTimers_[Inject].begin();
        radiance_->bounce(voxelizer_->grid(), coneSettingsOf(settings_),
                          frame.settings.background.value_or(frame.scene.cpu.background));
        stepTimers_[Inject].end();
    }
}

void VctPass::trace(const Frame& frame) {
    const GLuint p = traceProgram_.id();
    const VolumeFit& fit = voxelizer_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    const glm::vec3 environment = frame.settings.background.value_or(frame.scene.cpu.background);
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UV_CAMERA_POS, 1, &frame.camera.position[0]);
    glProgramUniform1i(p, UV_CONE_SET, settings_.coneSet);
    glProgramUniform4f(p, UV_TRACE_PARAMS, settings_.stepFactor, settings_.maxDistance * float(fit.resolution),
                       settings_.offset, settings_.specular ? 1.0f : 0.0f);
    glProgramUniform3fv(p, UV_ENVIRONMENT, 1, &environment[0]);
    glProgramUniform1i(p, UV_ANISOTROPIC, radiance_->anisotropic() ? 1 : 0);
    glProgramUniform1f(p, UV_INTENSITY, settings_.intensity);
    const GLuint gbuffer[3] = {frame.texture("gbuffer.depth"), frame.texture("gbuffer.normal"),
                               frame.texture("gbuffer.material")};
    glBindTextures(0, 3, gbuffer);
    glBindSamplers(0, 3, nullptr);
    radiance_->bind(4);
    glBindImageTexture(0, diffuse_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, specular_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(2, ao_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    glDispatchCompute(GLuint((diffuse_.width + 7) / 8), GLuint((diffuse_.height + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VctPass::debugView(Frame& frame) {
    const GLuint p = debugProgram_.id();
    const VolumeFit& fit = voxelizer_->grid().fit;
    const glm::mat4 worldToVoxel = fit.worldToVoxelMatrix();
    glUseProgram(p);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, fit.resolution);
    glProgramUniformMatrix4fv(p, UV_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    const bool slice = settings_.debugView == VctSettings::DebugView::Slice;
    glProgramUniform4f(p, UV_DEBUG_PARAMS, float(settings_.debugChannel), float(settings_.debugLevel),
                       slice ? float(settings_.sliceAxis) : -1.0f, settings_.slicePosition);
    const GLuint textures[3] = {voxelizer_->grid().albedo.id(), voxelizer_->grid().emission.id(),
                                radiance_->radiance().id()};
    glBindTextures(0, 3, textures);
    glBindSamplers(0, 3, nullptr);
    glBindImageTexture(0, debug_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(GLuint((debug_.width + 7) / 8), GLuint((debug_.height + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    frame.textures[slice ? "vct.slice" : "vct.voxels"] = debug_.id();
}

void VctPass::execute(Frame& frame) {
    reused_ = valid_;
    if (!valid_) rebuildVoxels(frame);
    valid_ = true;
    stepTimers_[Trace].begin();
    trace(frame);
    stepTimers_[Trace].end();
    frame.textures["indirect.diffuse"] = diffuse_.id();
    frame.textures["indirect.specular"] = specular_.id();
    frame.textures["ao"] = ao_.id();
    if (settings_.debugView != VctSettings::DebugView::None) debugView(frame);
}

}  // namespace gis
