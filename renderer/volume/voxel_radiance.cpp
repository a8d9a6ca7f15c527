#include "volume/voxel_radiance.h"

#include <algorithm>
#include <cmath>

#include "emitter_settings.h"
#include "lights.h"
#include "gl/bind.h"
#include "gl/dispatch.h"
#include "volume/volume_slots.h"
#include "volume/voxel_uniforms.h"

namespace gis {

using namespace voxel;

namespace {
int levelsFor(int n) {
    int levels = 1;
    while ((n >> levels) >= 1) ++levels;
    return levels;
}

void setVolumeSampling(const gl::Texture& t) {
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    // Clamp to the edge, not to a transparent border: cones stop at the volume's boundary, and a
    // border would fade the surfaces that lie in the outermost texels of every coarse level.
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(t.id(), wrap, GL_CLAMP_TO_EDGE);
}

void dispatch3D(int w, int h, int d) {
    gl::dispatchCompute(gl::groupsFor(w, 4), gl::groupsFor(h, 4), gl::groupsFor(d, 4), "voxel radiance");
}

int64_t chainTexels(int n) {
    int64_t sum = 0;
    for (int s = n; s >= 1; s /= 2) sum += int64_t(s) * s * s;
    return sum;
}
}  // namespace

int64_t voxelRadianceBytes(int resolution, bool anisotropic, int bounces, bool unlitOutsides, bool hitLights) {
    // The chain, and level 0's slab sides (and punctual share).
    const int64_t level0 = int64_t(resolution) * resolution * resolution;
    int64_t bytes = 8 * chainTexels(resolution) + (hitLights ? 16 : 8) * level0;
    if (unlitOutsides) bytes += level0 + 4;
    if (anisotropic) bytes += 6 * 8 * chainTexels(resolution / 2);
    if (bounces > 1) bytes += 16 * level0;  // direct light and its sides
    return bytes;
}

int64_t voxelFeedbackBytes(int resolution, bool anisotropic, bool hitLights) {
    return voxelRadianceBytes(resolution, anisotropic, 2, false, hitLights) + 16 * int64_t(resolution) * resolution * resolution;
}

const ProgramDesc kInjectProgram{"voxel_inject", {"volume/inject.comp"}, {}};
// The same injection that also lights each voxel by the direct pass's lights (renderer/emitters:
// the emitters, the environment), sampled through the ray scene.
const ProgramDesc kTracedInjectProgram{"voxel_inject_traced", {"volume/inject.comp"}, {{"TRACED_LIGHT", "1"}}};
const ProgramDesc kMipProgram{"voxel_mip", {"volume/voxel_mip.comp"}, {}};
const ProgramDesc kBounceProgram{"voxel_bounce", {"volume/bounce.comp"}, {}};
// The bounce whose cones cast rays through the ray scene (bounce.comp's BOUNCE_RAYS).
const ProgramDesc kBounceRaysProgram{
    "voxel_bounce_rays", {"volume/bounce.comp"}, {{"BOUNCE_RAYS", "1"}, {"RAY_SCENE_TEXTURE_UNIT", "TV_BOUNCE_RAY_SCENE"}}};
const ProgramDesc kExteriorProgram{"voxel_exterior", {"volume/exterior.comp"}, {}};
const ProgramDesc kExteriorSweepProgram{"voxel_exterior_sweep", {"volume/exterior.comp"}, {{"SWEEP", "1"}}};
constexpr int kExteriorSeed = 0, kExteriorCull = 2;
constexpr int kSweepGroup = 8;          // exterior.comp's SWEEP local size

std::vector<ProgramDesc> VoxelRadiance::programs() {
    return {kInjectProgram, kMipProgram, kBounceProgram, kBounceRaysProgram, kTracedInjectProgram, kExteriorProgram,
            kExteriorSweepProgram};
}

VoxelRadiance::VoxelRadiance(int n, bool anisotropic, int bounces, const gl::MemoryScope& scope, bool cullBackfaces,
                             bool cullUnlitOutsides, bool hitLights)
    : coneBlock_(scope), scope_(scope), anisotropic_(anisotropic && n >= 2), cullBackfaces_(cullBackfaces && anisotropic_), bounces_(bounces) {
    checkVoxelBudget(n, voxelRadianceBytes(n, anisotropic_, bounces, cullUnlitOutsides, hitLights), scope.owner);
    if (cullUnlitOutsides) {
        reach_ = gl::createTexture3D(scope, GL_R8UI, n, n, n);
        changed_ = gl::createBuffer(scope, 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
        exteriorProgram_ = buildProgram(kExteriorProgram);
        sweepProgram_ = buildProgram(kExteriorSweepProgram);
    }
    radiance_ = gl::createTexture3D(scope, GL_RGBA16F, n, n, n, levelsFor(n));
    setVolumeSampling(radiance_);
    sides_ = gl::createTexture3D(scope, GL_RGBA16F, n, n, n);
    const GLfloat none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(sides_.id(), 0, GL_RGBA, GL_FLOAT, none);  // a feedback volume's: never injected
    if (hitLights) {
        punctual_ = gl::createTexture3D(scope, GL_RGBA16F, n, n, n);
        glClearTexImage(punctual_.id(), 0, GL_RGBA, GL_FLOAT, none);
    }
    if (anisotropic_)
        for (gl::Texture& t : directional_) {
            t = gl::createTexture3D(scope, GL_RGBA16F, n / 2, n / 2, n / 2, levelsFor(n / 2));
            setVolumeSampling(t);
        }
    if (bounces_ > 1) {
        direct_ = gl::createTexture3D(scope, GL_RGBA16F, n, n, n);
        directSides_ = gl::createTexture3D(scope, GL_RGBA16F, n, n, n);
        glClearTexImage(directSides_.id(), 0, GL_RGBA, GL_FLOAT, none);
    }
    injectProgram_ = buildProgram(kInjectProgram);
    mipProgram_ = buildProgram(kMipProgram);
    bounceProgram_ = buildProgram(kBounceProgram);
}

void VoxelRadiance::inject(const VoxelGrid& grid, const Lights& lights) {
    const int emitterSamples = lights.rays && lights.rays->emitterCount > 0 ? lights.emitterSamples : 0;
    const int environmentSamples = lights.rays ? lights.environmentSamples : 0;
    const bool traced = emitterSamples > 0 || environmentSamples > 0;
    if (traced && !tracedInjectProgram_.id()) tracedInjectProgram_ = buildProgram(kTracedInjectProgram);
    const GLuint p = traced ? tracedInjectProgram_.id() : injectProgram_.id();
    hitLights_ = lights;
    if (traced) {
        lights.rays->bind(TV_INJECT_RAY_SCENE);  // its storage buffers above the frame's lights (below)
        glProgramUniform2i(p, UV_EMITTER_SAMPLES, int(lights.rays->emitterCount), emitterSamples);
        glProgramUniform1i(p, UV_ENVIRONMENT_SAMPLES, environmentSamples);
    }
    const int n = radiance_.width;
    const glm::mat4 voxelToWorld = grid.fit.voxelToWorldMatrix();
    glUseProgram(p);
    glProgramUniform1i(p, UV_RESOLUTION, n);
    glProgramUniformMatrix4fv(p, UV_VOXEL_TO_WORLD, 1, GL_FALSE, &voxelToWorld[0][0]);
    glProgramUniform1f(p, UV_VOXEL_SIZE, grid.fit.voxelSize());
    glProgramUniform1i(p, UV_LIGHT_COUNT, lights.buffer ? lights.count : 0);
    glProgramUniform1i(p, UV_SHADOWS_ENABLED, lights.shadows ? 1 : 0);
    glProgramUniform1f(p, UV_EMISSION_WEIGHT, lights.emission);
    gl::bindTextures({{TV_INJECT_ALBEDO, grid.albedo.id()}, {TV_INJECT_NORMAL, grid.normal.id()},
                      {TV_INJECT_EMISSION, grid.emission.id()}});
    glBindSamplers(TV_INJECT_ALBEDO, TV_INJECT_RAY_SCENE - TV_INJECT_ALBEDO, nullptr);  // the shadow units' too
    if (lights.shadowMaps) glBindTextureUnit(TV_INJECT_SHADOW_MAPS, lights.shadowMaps);
    if (lights.shadowCubes) glBindTextureUnit(TV_INJECT_SHADOW_CUBES, lights.shadowCubes);
    if (lights.buffer) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightsBinding, lights.buffer);
    const gl::Texture& target = bounces_ > 1 ? direct_ : radiance_;
    glBindImageTexture(IV_INJECT_RADIANCE, target.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IV_INJECT_SIDES, (bounces_ > 1 ? directSides_ : sides_).id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    // No texture without hitLights: the image unit is unbound and the stores have no effect (GL 4.5, 8.26).
    if (punctual_.id()) glBindImageTexture(IV_INJECT_PUNCTUAL, punctual_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    else glBindImageTexture(IV_INJECT_PUNCTUAL, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch3D(n, n, n);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (reach_.id()) cullUnlitOutsides(grid, target, lights.environmentLit);
    if (bounces_ > 1) copyDirectLight();
}

void VoxelRadiance::copyDirectLight() {
    const int n = radiance_.width;
    glCopyImageSubData(direct_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, radiance_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    glCopyImageSubData(directSides_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, sides_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
}

void VoxelRadiance::cullUnlitOutsides(const VoxelGrid& grid, const gl::Texture& target, bool environmentLit) {
    const int n = radiance_.width;
    gl::bindTextures({{TV_EXTERIOR_ALBEDO, grid.albedo.id()}, {TV_EXTERIOR_NORMAL, grid.normal.id()},
                      {TV_EXTERIOR_RADIANCE, target.id()}});
    const GLubyte zero = 0;
    glClearTexImage(reach_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    glBindImageTexture(IV_EXTERIOR_REACH, reach_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R8UI);
    glBindImageTexture(IV_EXTERIOR_RADIANCE, target.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, SV_EXTERIOR_CHANGED, changed_.id());
    const GLuint p = exteriorProgram_.id();
    glUseProgram(p);
    glProgramUniform1i(p, UV_RESOLUTION, n);
    glProgramUniform2i(p, UV_EXTERIOR_STEP, kExteriorSeed, environmentLit ? 1 : 0);
    dispatch3D(n, n, n);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    // Each round floods every straight run of air from what is reached; a path with k turns needs
    // k rounds, and a round that reaches nothing new ends it (at most the grid's voxels).
    const GLuint s = sweepProgram_.id();
    glUseProgram(s);
    glProgramUniform1i(s, UV_RESOLUTION, n);
    for (int64_t round = 0; round < int64_t(n) * n * n; ++round) {
        const GLuint none = 0;
        glNamedBufferSubData(changed_.id(), 0, 4, &none);
        for (int axis = 0; axis < 3; ++axis) {
            glProgramUniform2i(s, UV_EXTERIOR_STEP, axis, 0);
            gl::dispatchCompute(gl::groupsFor(n, kSweepGroup), gl::groupsFor(n, kSweepGroup), 1, "voxel exterior sweep");
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        }
        GLuint added = 0;
        glGetNamedBufferSubData(changed_.id(), 0, 4, &added);
        if (added == 0) break;
    }
    glUseProgram(p);
    glProgramUniform2i(p, UV_EXTERIOR_STEP, kExteriorCull, 0);
    dispatch3D(n, n, n);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VoxelRadiance::downsample(const gl::Texture& source, int sourceLevel, const gl::Texture& target, int targetLevel,
                               int direction, GLuint normals) {
    const GLuint p = mipProgram_.id();
    glProgramUniform1i(p, UV_MIP_LEVEL, sourceLevel);
    glProgramUniform1i(p, UV_DIRECTION, direction);
    glProgramUniform1i(p, UV_NORMAL_WEIGHT, !normals ? 0 : cullBackfaces_ ? 2 : 1);
    glBindTextureUnit(TV_MIP_SOURCE, source.id());
    glBindTextureUnit(TV_MIP_NORMAL, normals ? normals : source.id());
    glBindTextureUnit(TV_MIP_SIDES, sides_.id());
    glBindImageTexture(IV_MIP_TARGET, target.id(), targetLevel, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    const int size = std::max(target.width >> targetLevel, 1);
    dispatch3D(size, size, size);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void VoxelRadiance::buildMips(const VoxelGrid& grid) {
    glUseProgram(mipProgram_.id());
    glBindSamplers(TV_MIP_SOURCE, 3, nullptr);
    for (int level = 1; level < radiance_.levels; ++level) downsample(radiance_, level - 1, radiance_, level, -1);
    if (!anisotropic_) return;
    for (int d = 0; d < 6; ++d) {
        downsample(radiance_, 0, directional_[d], 0, d, grid.normal.id());
        for (int level = 1; level < directional_[d].levels; ++level)
            downsample(directional_[d], level - 1, directional_[d], level, d);
    }
}

GLuint VoxelRadiance::useBounceProgram(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays) {
    const int n = radiance_.width;
    const bool withRays = rays && cones.rays > 0;
    if (withRays && !bounceRaysProgram_.id()) bounceRaysProgram_ = buildProgram(kBounceRaysProgram);
    const GLuint p = withRays ? bounceRaysProgram_.id() : bounceProgram_.id();
    glUseProgram(p);
    if (withRays) {
        rays->bind(TV_BOUNCE_RAY_SCENE);
        const glm::mat4 voxelToWorld = grid.fit.voxelToWorldMatrix();
        glProgramUniformMatrix4fv(p, UV_VOXEL_TO_WORLD, 1, GL_FALSE, &voxelToWorld[0][0]);
        const glm::mat4 worldToVoxel = grid.fit.worldToVoxelMatrix();
        glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    }
    const float maxDistance = cones.maxDistance > 0.0f ? cones.maxDistance : std::sqrt(3.0f) * float(n);
    glProgramUniform1i(p, UV_RESOLUTION, n);
    glProgramUniform1i(p, UV_CONE_SET, cones.coneSet);
    ConeTraceBlock block;
    block.stepFactor = cones.stepFactor;
    block.maxDistance = maxDistance;
    block.offset = cones.offset;
    block.skyRays = withRays ? cones.rays : 0;
    coneBlock_.set(block);
    glProgramUniform1i(p, UV_ANISOTROPIC, mipMode());
    return p;
}

void VoxelRadiance::gatherOnce(const VoxelGrid& grid, const Scratch& scratch, GLuint program) {
    // Cones read the whole chain while the result is written: write to scratch volumes, then
    // copy them over level 0 and the sides.
    const int n = radiance_.width;
    glUseProgram(program);
    gl::bindTextures({{TV_BOUNCE_ALBEDO, grid.albedo.id()}, {TV_BOUNCE_NORMAL, grid.normal.id()},
                      {TV_BOUNCE_DIRECT, direct_.id()}, {TV_BOUNCE_DIRECT_SIDES, directSides_.id()}});
    glBindSamplers(TV_BOUNCE_ALBEDO, 10, nullptr);
    bind();
    glBindImageTexture(IV_BOUNCE_RADIANCE, scratch.radiance.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(IV_BOUNCE_SIDES, scratch.sides.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatch3D(n, n, n);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glCopyImageSubData(scratch.radiance.id(), GL_TEXTURE_3D, 0, 0, 0, 0, radiance_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    glCopyImageSubData(scratch.sides.id(), GL_TEXTURE_3D, 0, 0, 0, 0, sides_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    buildMips(grid);
}

VoxelRadiance::Scratch VoxelRadiance::makeScratch() const {
    const int n = radiance_.width;
    return {gl::createTexture3D(scope_, GL_RGBA16F, n, n, n), gl::createTexture3D(scope_, GL_RGBA16F, n, n, n)};
}

void VoxelRadiance::bounce(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays) {
    const GLuint program = useBounceProgram(grid, cones, rays);
    for (int b = 1; b < bounces_; ++b) gatherOnce(grid, makeScratch(), program);
}

void VoxelRadiance::restartFeedback(const VoxelGrid& grid, const VoxelRadiance& injected) {
    if (!direct_.id()) throw Error("voxel radiance: bounce feedback needs a volume made with bounces > 1");
    const int n = radiance_.width;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glCopyImageSubData(injected.radiance().id(), GL_TEXTURE_3D, 0, 0, 0, 0, direct_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    glCopyImageSubData(injected.sides().id(), GL_TEXTURE_3D, 0, 0, 0, 0, directSides_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    if (punctual_.id() && injected.punctual().id())
        glCopyImageSubData(injected.punctual().id(), GL_TEXTURE_3D, 0, 0, 0, 0, punctual_.id(), GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    hitLights_ = injected.hitLights_;
    copyDirectLight();
    buildMips(grid);
}

void VoxelRadiance::feedbackBounce(const VoxelGrid& grid, const ConeSettings& cones, const RayScene* rays) {
    if (!feedbackScratch_.radiance.id()) feedbackScratch_ = makeScratch();
    gatherOnce(grid, feedbackScratch_, useBounceProgram(grid, cones, rays));
}

void VoxelRadiance::bind() const {
    GLuint textures[kVolumeRadianceUnits];
    textures[0] = radiance_.id();
    for (int d = 0; d < 6; ++d) textures[1 + d] = anisotropic_ ? directional_[d].id() : radiance_.id();
    textures[7] = sides_.id();
    glBindTextures(kVolumeRadianceUnit, kVolumeRadianceUnits, textures);
    glBindSamplers(kVolumeRadianceUnit, kVolumeRadianceUnits, nullptr);
    bindHitLights();
}

void VoxelRadiance::bindHitLights() const {
    const GLuint textures[3] = {punctual_.id(), hitLights_.shadowMaps, hitLights_.shadowCubes};
    glBindTextures(kVolumePunctualUnit, 3, textures);
    glBindSamplers(kVolumePunctualUnit, 3, nullptr);
    // The scene's lights alone (the buffer is padded for the lighting pass's uniform block): the
    // hits' loop runs over u_hitLights.length(). With none, one padding light, which sends nothing.
    if (hitLights_.buffer)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kVolumeHitLightsBinding, hitLights_.buffer, 0,
                          GLsizeiptr(std::max(hitLights_.count, 1) * sizeof(GpuLight)));
}

void voxelizeFrame(Frame& frame, Voxelizer& voxelizer, const std::string& prefix) {
    auto t = frame.step(prefix + "voxelize");
    voxelizer.voxelize(frame.scene);
}

void injectFrameLights(Frame& frame, const VoxelGrid& grid, VoxelRadiance& radiance, const RaySceneSource& rays,
                       const std::string& prefix) {
    VoxelRadiance::Lights lights;
    lights.buffer = frame.buffer(resource::kLights);
    lights.shadowMaps = frame.texture(resource::kShadowMaps);
    lights.shadowCubes = frame.texture(resource::kShadowCubes);
    lights.count = int(frame.scene.cpu.lights.size());
    lights.shadows = frame.settings.shadows;
    lights.environmentLit = environmentSendsLight(frame.scene.cpu, frame.settings);
    const EmitterLightSettings emitters = emitterLightSettings(frame.settings);
    lights.emission = EmitterMode(emitters.mode) == EmitterMode::Gi ? 1.0f : 0.0f;
    if (emittersAreLights(frame.scene.cpu, frame.settings)) {
        lights.rays = &rays();
        lights.emitterSamples = emitters.volumeSamples;
    }
    if (environmentIsLight(frame.scene.cpu, frame.settings)) {
        lights.rays = &rays();
        lights.environmentSamples = emitters.environmentVolumeSamples;
        frame.bindEnvironment();
    }
    auto t = frame.step(prefix + "inject");
    radiance.inject(grid, lights);
}

}  // namespace gis
