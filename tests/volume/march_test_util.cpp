#include "march_test_util.h"

#include "gl/shader.h"
#include "volume/sdf_uniforms.h"

namespace gis::test {

std::vector<Hit> march(const DistanceField& field, const std::vector<Ray>& rays, const MarchSettings& m) {
    static gl::Object program = buildProgram({"sdf_march_probe", {"volume/sdf_march_probe.comp"}, {}});
    gl::MemoryLedger ledger;
    const gl::MemoryScope scope{&ledger, "sdf_test"};
    gl::Buffer in = gl::createBuffer(scope, int64_t(rays.size() * sizeof(Ray)), rays.data());
    gl::Buffer out = gl::createBuffer(scope, int64_t(rays.size() * 32), nullptr);
    const GLuint p = program.id();
    glUseProgram(p);
    const SdfVolume& v = field.volume();
    glProgramUniform1ui(p, 0, GLuint(rays.size()));
    glProgramUniform4f(p, 1, v.origin.x, v.origin.y, v.origin.z, v.size);
    glProgramUniform1i(p, 2, v.resolution);
    sdf::SdfMarchBlock block;
    block.hitThreshold = m.threshold;
    block.relaxation = m.relaxation;
    block.maxSteps = m.maxSteps;
    block.offset = m.startOffset;
    const gl::UniformBuffer<sdf::SdfMarchBlock> marchBlock(scope);
    marchBlock.set(block);
    std::vector<glm::vec4> cascades;
    for (int i = 0; i < field.layers(); ++i) cascades.emplace_back(field.volume(i).origin, field.volume(i).size);
    glProgramUniform1i(p, 4, field.layers() > 1 ? field.layers() : 0);
    glProgramUniform4fv(p, 5, GLsizei(cascades.size()), &cascades[0][0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, sdf::SF_MARCH_PROBE_RAYS, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, sdf::SF_MARCH_PROBE_HITS, out.id());
    field.bind(sdf::TF_MARCH_PROBE_DISTANCE);
    glDispatchCompute(GLuint((rays.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> raw(rays.size() * 2);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(raw.size() * sizeof(glm::vec4)), raw.data());
    std::vector<Hit> hits(rays.size());
    for (size_t i = 0; i < hits.size(); ++i)
        hits[i] = {glm::vec3(raw[2 * i]), raw[2 * i].w > 0.5f, glm::vec3(raw[2 * i + 1]), int(raw[2 * i + 1].w),
                   int(raw[2 * i].w) - 1};
    return hits;
}

}  // namespace gis::test
