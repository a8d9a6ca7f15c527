#include "services/scene_triangles.h"

#include "bvh.h"

namespace gis {

SceneTriangles::SceneTriangles(const GpuScene& scene, gl::MemoryLedger& ledger) {
    const gl::MemoryScope scope{&ledger, "scene.triangles"};
    for (const TraceTriangle& t : worldTriangles(scene.cpu)) {
        const glm::vec3 c = glm::cross(t.p1 - t.p0, t.p2 - t.p0);
        const float len = glm::length(c);
        SceneTriangle s;
        s.p0 = glm::vec4(t.p0, float(scene.draws[t.draw].material));
        s.p1 = glm::vec4(t.p1, float(t.draw));
        s.p2 = glm::vec4(t.p2, float(t.primitiveTriangle));
        s.normal = glm::vec4(len > 0.0f ? c / len : glm::vec3(0.0f), 0.5f * len);
        cpu.push_back(s);
    }
    count = cpu.size();
    std::vector<SceneTriangle> upload = cpu;
    if (upload.empty()) upload.push_back(SceneTriangle{});

    std::vector<SceneTriangleMaterial> mats;
    for (const GpuMaterial& gm : scene.materials) {  // ends with the default material
        const Material& m = gm.params;
        mats.push_back({m.baseColorFactor, glm::vec4(m.emissive, m.doubleSided ? 1.0f : 0.0f),
                        glm::vec4(m.metallicFactor, m.roughnessFactor, m.specularFactor,
                                  m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f)});
    }
    materialCount = mats.size();
    triangles = gl::createBuffer(scope, int64_t(upload.size() * sizeof(SceneTriangle)), upload.data());
    materials = gl::createBuffer(scope, int64_t(mats.size() * sizeof(SceneTriangleMaterial)), mats.data());
}

void SceneTriangles::bind(GLuint triangleBinding, GLuint materialBinding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, triangleBinding, triangles.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, materialBinding, materials.id());
}

}  // namespace gis
