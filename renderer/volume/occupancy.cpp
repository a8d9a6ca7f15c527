#include "volume/occupancy.h"

#include <string>

#include "gl/dispatch.h"
#include "volume/voxel_uniforms.h"
#include "volume/voxelizer.h"

namespace gis {

namespace {
const ProgramDesc kBuildProgram{"occupancy_build", {"volume/occupancy_build.comp"}, {}};

int64_t blocksPerCascade(int n) {
    const int64_t b = n / kOccupancyBlock;
    return b * b * b;
}
int regionWordsFor(int n) {
    const int64_t r = n / kOccupancyRegion;
    return int((r * r * r + 31) / 32);
}
}  // namespace

int64_t occupancyBytes(int resolution, int cascades) {
    return int64_t(cascades) * (blocksPerCascade(resolution) * 8 + int64_t(regionWordsFor(resolution)) * 4);
}

std::vector<ProgramDesc> OccupancyHierarchy::programs() { return {kBuildProgram}; }

OccupancyHierarchy::OccupancyHierarchy(const gl::MemoryScope& scope, int resolution, int cascades)
    : resolution_(resolution), cascades_(cascades) {
    if (resolution % kOccupancyRegion != 0 || resolution <= 0)
        throw Error("occupancy: " + std::to_string(resolution) + " voxels per edge is not a multiple of " +
                    std::to_string(kOccupancyRegion));
    blocks_ = gl::createStorageBuffer(scope, cascades * blocksPerCascade(resolution) * 8, nullptr);
    regions_ = gl::createStorageBuffer(scope, int64_t(cascades) * regionWords() * 4, nullptr);
    glClearNamedBufferData(blocks_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    glClearNamedBufferData(regions_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
    buildProgram_ = buildProgram(kBuildProgram);
}

int OccupancyHierarchy::regionWords() const { return regionWordsFor(resolution_); }

void OccupancyHierarchy::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOccupancyBlocksBinding, blocks_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOccupancyRegionsBinding, regions_.id());
}

// One invocation per block: its 64 voxels into a mask, and the region's bit set when any is
// occupied (the region words are cleared first; atomicOr, as 8 blocks share a region).
void OccupancyHierarchy::build(const VoxelGrid& grid, int cascade) {
    const GLuint zero = 0;
    glClearNamedBufferSubData(regions_.id(), GL_R32UI, GLintptr(int64_t(cascade) * regionWords() * 4),
                              GLsizeiptr(int64_t(regionWords()) * 4), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    const GLuint p = buildProgram_.id();
    glUseProgram(p);
    glProgramUniform1i(p, voxel::UV_RESOLUTION, resolution_);
    glProgramUniform1i(p, voxel::UV_CASCADE, cascade);
    glBindTextureUnit(voxel::TV_OCCUPANCY_ALBEDO, grid.albedo.id());
    bind();
    const GLuint b = GLuint(blocksPerEdge());
    gl::dispatchCompute(gl::groupsFor(b, 4), gl::groupsFor(b, 4), gl::groupsFor(b, 4), "occupancy");
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::vector<uint64_t> OccupancyHierarchy::readBlocks(int cascade) const {
    std::vector<uint64_t> out(size_t(blocksPerCascade(resolution_)));
    glGetNamedBufferSubData(blocks_.id(), GLintptr(cascade * blocksPerCascade(resolution_) * 8),
                            GLsizeiptr(out.size() * 8), out.data());
    return out;
}

std::vector<bool> OccupancyHierarchy::readRegions(int cascade) const {
    std::vector<uint32_t> words(static_cast<size_t>(regionWords()));
    glGetNamedBufferSubData(regions_.id(), GLintptr(int64_t(cascade) * regionWords() * 4), GLsizeiptr(words.size() * 4),
                            words.data());
    const int r = regionsPerEdge();
    std::vector<bool> out(size_t(r) * r * r);
    for (size_t i = 0; i < out.size(); ++i) out[i] = (words[i / 32] >> (i % 32)) & 1u;
    return out;
}

}  // namespace gis
