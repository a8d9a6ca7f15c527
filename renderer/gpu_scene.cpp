#include "gpu_scene.h"

namespace gis {

namespace {
gl::Texture uploadImage(const gl::MemoryScope& scope, const Image& image) {
    const GLenum format = image.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    gl::Texture t = gl::createTexture2D(scope, format, image.width, image.height,
                                        gl::mipLevelsFor(image.width, image.height));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba8.data());
    glGenerateTextureMipmap(t.id());
    return t;
}

gl::Texture solidTexture(const gl::MemoryScope& scope, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    gl::Texture t = gl::createTexture2D(scope, GL_RGBA8, 1, 1, 1);
    const uint8_t texel[4] = {r, g, b, a};
    glTextureSubImage2D(t.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, texel);
    return t;
}
}  // namespace

GpuScene::GpuScene(const Scene& scene, gl::MemoryLedger& ledger) : cpu(scene) {
    const gl::MemoryScope scope{&ledger, "scene"};
    std::vector<Vertex> allVertices;
    std::vector<uint32_t> allIndices;
    std::vector<GLuint> firstIndex, baseVertex;
    for (const Primitive& p : scene.primitives) {
        firstIndex.push_back(static_cast<GLuint>(allIndices.size()));
        baseVertex.push_back(static_cast<GLuint>(allVertices.size()));
        allVertices.insert(allVertices.end(), p.vertices.begin(), p.vertices.end());
        allIndices.insert(allIndices.end(), p.indices.begin(), p.indices.end());
    }
    vertices = gl::createBuffer(scope, int64_t(allVertices.size() * sizeof(Vertex)), allVertices.data());
    indices = gl::createBuffer(scope, int64_t(allIndices.size() * sizeof(uint32_t)), allIndices.data());

    vao = gl::createVertexArray();
    const GLuint v = vao.id();
    glVertexArrayVertexBuffer(v, 0, vertices.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(v, indices.id());
    struct Attrib { GLuint index; GLint size; size_t offset; };
    const Attrib attribs[] = {{0, 3, offsetof(Vertex, position)}, {1, 3, offsetof(Vertex, normal)},
                              {2, 4, offsetof(Vertex, tangent)},  {3, 2, offsetof(Vertex, uv)},
                              {4, 4, offsetof(Vertex, color)}};
    for (const Attrib& a : attribs) {
        glEnableVertexArrayAttrib(v, a.index);
        glVertexArrayAttribFormat(v, a.index, a.size, GL_FLOAT, GL_FALSE, static_cast<GLuint>(a.offset));
        glVertexArrayAttribBinding(v, a.index, 0);
    }

    for (const Image& image : scene.images) textures.push_back(uploadImage(scope, image));
    const size_t whiteIndex = textures.size();
    textures.push_back(solidTexture(scope, 255, 255, 255, 255));
    const GLuint white = textures[whiteIndex].id();

    sampler = gl::createSampler();
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);

    auto tex = [&](int index) { return index >= 0 && index < int(scene.images.size()) ? textures[index].id() : white; };
    std::vector<Material> params = scene.materials;
    params.push_back(Material{});  // the default material, for primitives without one
    params.back().name = "default";
    for (const Material& m : params) {
        GpuMaterial g;
        g.params = m;
        g.baseColor = tex(m.baseColorTexture);
        g.metallicRoughness = tex(m.metallicRoughnessTexture);
        g.normal = tex(m.normalTexture);
        g.emissive = tex(m.emissiveTexture);
        g.occlusion = tex(m.occlusionTexture);
        const int given[5] = {m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture, m.emissiveTexture,
                              m.occlusionTexture};
        for (int bit = 0; bit < 5; ++bit)
            if (given[bit] >= 0 && given[bit] < int(scene.images.size())) g.textures |= 1u << bit;
        materials.push_back(g);
    }
    const int defaultMaterial = int(materials.size()) - 1;

    for (const DrawItem& d : scene.draws) {
        const Primitive& p = scene.primitives[d.primitive];
        GpuDraw g;
        g.indexCount = static_cast<GLsizei>(p.indices.size());
        g.firstIndex = firstIndex[d.primitive];
        g.baseVertex = static_cast<GLint>(baseVertex[d.primitive]);
        g.material = p.material >= 0 && p.material < defaultMaterial ? p.material : defaultMaterial;
        g.world = d.world;
        g.normalMatrix = glm::transpose(glm::inverse(glm::mat3(d.world)));
        draws.push_back(g);
    }
    gl::checkOutOfMemory("uploading the scene");
}

}  // namespace gis
