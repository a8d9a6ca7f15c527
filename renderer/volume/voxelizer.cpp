#include "volume/voxelizer.h"

#include <algorithm>
#include <cstdio>

#include "gl/dispatch.h"
#include "scene_draw.h"
#include "volume/voxel_uniforms.h"

namespace gis {

using namespace voxel;

namespace {
bool hasExtension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::string(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) == name) return true;
    return false;
}

// Largest emitted radiance any material can produce (emissive textures are at most 1), so the
// fixed-point sums can hold emission normalised to [0, 1].
float maxEmission(const GpuScene& scene) {
    float m = 0.0f;
    for (const GpuMaterial& g : scene.materials)
        for (int c = 0; c < 3; ++c) m = std::max(m, g.params.emissive[c]);
    return std::min(std::max(m, 1e-6f), gl::kMaxHalfFloat);
}

std::string mib(int64_t bytes) { return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB"; }
}  // namespace

const char* conservativeModeName(ConservativeMode m) {
    return m == ConservativeMode::Hardware ? "hardware" : m == ConservativeMode::Geometry ? "geometry" : "off";
}

int64_t voxelGridBytes(int resolution) {
    const int64_t voxels = int64_t(resolution) * resolution * resolution;
    return voxels * (4 + 4 + 8 + (kVoxelSumChannels + kVoxelPlaceChannels) * 4);
}

void checkVoxelBudget(int resolution, int64_t bytes, const std::string& what) {
    GLint max3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    if (max3d > 0 && resolution > max3d)
        throw Error(what + ": resolution " + std::to_string(resolution) + "^3 exceeds the driver's 3D texture size " +
                    std::to_string(max3d));
    if (bytes > kVoxelBudgetBytes)
        throw Error(what + ": resolution " + std::to_string(resolution) + "^3 would need about " + mib(bytes) +
                    " of GPU memory, more than the " + mib(kVoxelBudgetBytes) + " a voxel method may hold");
}

bool Voxelizer::hardwareConservativeAvailable() { return hasExtension("GL_NV_conservative_raster"); }

const ProgramDesc kVoxelizeProgram{"voxelize", {"scene.vert", "volume/voxelize.geom", "volume/voxelize.frag"}, {}};
const ProgramDesc kResolveProgram{"voxel_resolve", {"volume/voxel_resolve.comp"}, {}};

std::vector<ProgramDesc> Voxelizer::programs() { return {kVoxelizeProgram, kResolveProgram}; }

Voxelizer::Voxelizer(const VolumeFit& fit, ConservativeMode mode, const gl::MemoryScope& scope,
                     const std::string& modeKey)
    : scope_(scope), mode_(mode) {
    const int n = fit.resolution;
    checkVoxelBudget(n, voxelGridBytes(n), scope.owner);
    if (mode_ == ConservativeMode::Hardware && !hardwareConservativeAvailable()) {
        static bool warned = false;  // once per process: a renderer per frame size would repeat it
        if (!warned && !modeKey.empty()) {
            std::fprintf(stderr, "gisandbox: warning: GL_NV_conservative_raster is not available; "
                                 "%s=hardware falls back to geometry\n", modeKey.c_str());
            warned = true;
        }
        mode_ = ConservativeMode::Geometry;
    }
    grid_.fit = fit;
    grid_.albedo = gl::createTexture3D(scope, GL_RGBA8, n, n, n);
    grid_.normal = gl::createTexture3D(scope, GL_RGBA8, n, n, n);
    grid_.emission = gl::createTexture3D(scope, GL_RGBA16F, n, n, n);
    for (const gl::Texture* t : {&grid_.albedo, &grid_.normal, &grid_.emission}) {
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    voxelizeProgram_ = buildProgram(kVoxelizeProgram);
    resolveProgram_ = buildProgram(kResolveProgram);
    fbo_ = gl::createFramebuffer();  // no attachments: only its size matters
    glNamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, n);
    glNamedFramebufferParameteri(fbo_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, n);
}

void Voxelizer::moveTo(const VolumeFit& fit) {
    if (fit.resolution != grid_.fit.resolution)
        throw Error("voxelizer: cannot move a " + std::to_string(grid_.fit.resolution) + "^3 grid to a " +
                    std::to_string(fit.resolution) + "^3 volume");
    grid_.fit = fit;
}

void Voxelizer::voxelize(const GpuScene& scene) { voxelizeAround(scene, glm::ivec3(0), glm::ivec3(0)); }

int64_t Voxelizer::scroll(const VolumeFit& fit, const glm::ivec3& shift, const GpuScene& scene) {
    const int n = grid_.fit.resolution;
    moveTo(fit);
    const glm::ivec3 lo = glm::max(glm::ivec3(0), -shift), hi = glm::min(glm::ivec3(n), glm::ivec3(n) - shift);
    if (glm::any(glm::lessThanEqual(hi, lo))) {
        voxelize(scene);
        return int64_t(n) * n * n;
    }
    // The kept cells, from where they were (lo + shift) to where they are now (lo), through a
    // scratch copy: a copy within one texture must not overlap itself.
    const glm::ivec3 size = hi - lo, from = lo + shift;
    for (const gl::Texture* t : {&grid_.albedo, &grid_.normal, &grid_.emission}) {
        gl::Texture scratch = gl::createTexture3D(scope_, t->format, size.x, size.y, size.z);
        glCopyImageSubData(t->id(), GL_TEXTURE_3D, 0, from.x, from.y, from.z, scratch.id(), GL_TEXTURE_3D, 0, 0, 0, 0,
                           size.x, size.y, size.z);
        glCopyImageSubData(scratch.id(), GL_TEXTURE_3D, 0, 0, 0, 0, t->id(), GL_TEXTURE_3D, 0, lo.x, lo.y, lo.z, size.x,
                           size.y, size.z);
    }
    voxelizeAround(scene, lo, hi);
    return int64_t(n) * n * n - int64_t(size.x) * size.y * size.z;
}

void Voxelizer::voxelizeAround(const GpuScene& scene, const glm::ivec3& keepLo, const glm::ivec3& keepHi) {
    const int n = grid_.fit.resolution;
    // The sums live only while voxelizing: they are most of a grid's bytes, and nothing else needs them.
    const int64_t voxels = int64_t(n) * n * n;
    gl::Buffer sums = gl::createStorageBuffer(scope_, voxels * kVoxelSumChannels * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Buffer places = gl::createStorageBuffer(scope_, voxels * kVoxelPlaceChannels * 4, nullptr, GL_DYNAMIC_STORAGE_BIT);
    const GLuint zero = 0;
    for (const gl::Buffer* b : {&sums, &places}) glClearNamedBufferData(b->id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVoxelSumsBinding, sums.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVoxelPlacesBinding, places.id());

    const float emissionMax = maxEmission(scene);
    const GLuint p = voxelizeProgram_.id();
    const glm::mat4 worldToVoxel = grid_.fit.worldToVoxelMatrix();
    const glm::mat4 identity(1.0f);
    glProgramUniformMatrix4fv(p, UV_WORLD_TO_VOXEL, 1, GL_FALSE, &worldToVoxel[0][0]);
    glProgramUniformMatrix4fv(p, 2 /* U_VIEW_PROJ: unused, the geometry shader projects */, 1, GL_FALSE,
                              &identity[0][0]);
    glProgramUniform1i(p, UV_RESOLUTION, n);
    glProgramUniform1i(p, UV_CONSERVATIVE, mode_ == ConservativeMode::Off ? 0 : mode_ == ConservativeMode::Geometry ? 1 : 2);
    glProgramUniform1f(p, UV_EMISSION_SCALE, 1.0f / emissionMax);
    glProgramUniform3iv(p, UV_KEEP_LO, 1, &keepLo[0]);
    glProgramUniform3iv(p, UV_KEEP_HI, 1, &keepHi[0]);

    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, n, n);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // both faces: a wall seen from behind is still in its voxels
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    if (mode_ == ConservativeMode::Hardware) glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
    glUseProgram(p);
    glBindVertexArray(scene.vao.id());
    for (const GpuDraw& d : scene.draws) {
        drawWithMaterial(scene, p, d);
    }
    if (mode_ == ConservativeMode::Hardware) glDisable(GL_CONSERVATIVE_RASTERIZATION_NV);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    const GLuint r = resolveProgram_.id();
    glUseProgram(r);
    glProgramUniform1i(r, UV_RESOLUTION, n);
    glProgramUniform1f(r, UV_EMISSION_SCALE, 1.0f / emissionMax);
    glProgramUniform3iv(r, UV_KEEP_LO, 1, &keepLo[0]);
    glProgramUniform3iv(r, UV_KEEP_HI, 1, &keepHi[0]);
    glBindImageTexture(IV_RESOLVE_ALBEDO, grid_.albedo.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glBindImageTexture(IV_RESOLVE_NORMAL, grid_.normal.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glBindImageTexture(IV_RESOLVE_EMISSION, grid_.emission.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    const GLuint groups = gl::groupsFor(n, 4);
    gl::dispatchCompute(groups, groups, groups, "voxelizer");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace gis
