#include "scene_draw.h"

#include "gl/bind.h"
#include "uniforms.h"

namespace gis {

namespace {

void bindMaterialTextures(const GpuMaterial& m, GLuint sampler) {
    gl::bindTextures({{T_MATERIAL_BASE_COLOR, m.baseColor},
                      {T_MATERIAL_METALLIC_ROUGHNESS, m.metallicRoughness},
                      {T_MATERIAL_NORMAL, m.normal},
                      {T_MATERIAL_EMISSIVE, m.emissive},
                      {T_MATERIAL_OCCLUSION, m.occlusion}},
                     sampler);
}

void setDrawUniforms(GLuint program, const GpuDraw& draw, const Material& m) {
    glProgramUniformMatrix4fv(program, U_MODEL, 1, GL_FALSE, &draw.world[0][0]);
    glProgramUniformMatrix3fv(program, U_NORMAL_MATRIX, 1, GL_FALSE, &draw.normalMatrix[0][0]);
    glProgramUniform4fv(program, U_BASE_COLOR_FACTOR, 1, &m.baseColorFactor[0]);
    glProgramUniform1f(program, U_METALLIC, m.metallicFactor);
    glProgramUniform1f(program, U_ROUGHNESS, m.roughnessFactor);
    glProgramUniform1f(program, U_SPECULAR_FACTOR, m.specularFactor);
    glProgramUniform1f(program, U_OCCLUSION_STRENGTH, m.occlusionStrength);
    glProgramUniform3fv(program, U_EMISSIVE, 1, &m.emissive[0]);
    glProgramUniform1f(program, U_ALPHA_CUTOFF, m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f);
    glProgramUniform1f(program, U_NORMAL_SCALE, m.normalScale);
    glProgramUniform1i(program, U_DOUBLE_SIDED, m.doubleSided ? 1 : 0);
    glProgramUniform2i(program, U_BRDF_OVERRIDE, m.diffuseModel, m.specularModel);
}

}  // namespace

void drawWithMaterial(const GpuScene& scene, GLuint program, const GpuDraw& draw) {
    const GpuMaterial& material = scene.materials[draw.material];
    setDrawUniforms(program, draw, material.params);
    bindMaterialTextures(material, scene.sampler.id());
    glDrawElementsBaseVertex(GL_TRIANGLES, draw.indexCount, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(uintptr_t(draw.firstIndex) * 4), draw.baseVertex);
}

}  // namespace gis
