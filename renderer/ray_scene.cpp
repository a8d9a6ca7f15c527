#include "ray_scene.h"

#include <stb_image_resize.h>

#include <algorithm>
#include <cmath>

#include "gl/dispatch.h"
#include "lights.h"
#include "uniforms.h"

namespace gis {

gl::Buffer createRayCounts(const gl::MemoryScope& scope) {
    const uint32_t zeros[6] = {};
    return gl::createStorageBuffer(scope, sizeof(zeros), zeros);
}

RayCounts readRayCounts(const gl::Buffer& counts) {
    uint32_t words[6] = {};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(counts.id(), 0, sizeof(words), words);
    auto count = [&](int k) { return uint64_t(words[2 * k]) | uint64_t(words[2 * k + 1]) << 32; };
    return RayCounts{count(0), count(1), count(2)};
}

namespace {

// Path-traced textures share one array, so every image is resampled to one size: the largest
// image's, capped here (no ray differentials are tracked, so finer texels would only alias).
constexpr int kMaxTextureSize = 1024;

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float luminance(glm::vec3 c) { return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f)); }

}  // namespace

RayScene::RayScene(const GpuScene& gpuScene, gl::MemoryLedger& ledger, const std::string& owner)
    : scope_{&ledger, owner} {
    const Scene& scene = gpuScene.cpu;
    const gl::MemoryScope& scope = scope_;
    bvh = buildBvh(scene);

    // Textures: one array layer per scene image.
    int size = 1;
    for (const Image& img : scene.images) size = std::max({size, img.width, img.height});
    size = std::min(size, kMaxTextureSize);
    const int layers = std::max<int>(1, int(scene.images.size()));
    textures = gl::createTexture2DArray(scope, GL_RGBA8, size, size, layers);
    std::vector<glm::vec3> meanLinear(scene.images.size(), glm::vec3(1.0f));
    std::vector<uint8_t> resized(size_t(size) * size * 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t i = 0; i < scene.images.size(); ++i) {
        const Image& img = scene.images[i];
        const bool ok = img.srgb ? stbir_resize_uint8_srgb(img.rgba8.data(), img.width, img.height, 0, resized.data(),
                                                           size, size, 0, 4, 3, 0)
                                 : stbir_resize_uint8(img.rgba8.data(), img.width, img.height, 0, resized.data(), size,
                                                      size, 0, 4);
        if (!ok) throw Error("path tracer: cannot resample texture '" + img.name + "'");
        glTextureSubImage3D(textures.id(), 0, 0, 0, GLint(i), size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, resized.data());
        glm::dvec3 sum(0.0);
        for (size_t p = 0; p < resized.size(); p += 4)
            for (int c = 0; c < 3; ++c) sum[c] += srgbToLinear(resized[p + c] / 255.0f);
        meanLinear[i] = glm::vec3(sum / double(size_t(size) * size));
    }
    sampler = gl::createSampler();
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);

    // Materials (the GpuScene's list, which ends with the default material).
    auto layerOf = [&](int image) { return image >= 0 && image < int(scene.images.size()) ? image : -1; };
    std::vector<rays::RayMaterial> materialData;
    for (const GpuMaterial& gm : gpuScene.materials) {
        const Material& m = gm.params;
        rays::RayMaterial g{};
        g.baseColor = m.baseColorFactor;
        g.emissive = glm::vec4(m.emissive, m.doubleSided ? 1.0f : 0.0f);
        g.params = glm::vec4(m.metallicFactor, m.roughnessFactor, m.specularFactor,
                             m.alphaMode == AlphaMode::Mask ? m.alphaCutoff : -1.0f);
        g.params2 = glm::vec4(m.normalScale, 0.0f, 0.0f, 0.0f);
        g.textures = glm::ivec4(layerOf(m.baseColorTexture), layerOf(m.metallicRoughnessTexture),
                                layerOf(m.normalTexture), layerOf(m.emissiveTexture));
        materialData.push_back(g);
    }

    // Triangles in BVH leaf order, with their shading attributes; emitters weighted by power.
    std::vector<rays::TraceTriangle> tris;
    std::vector<rays::TriangleAttributes> attrs;
    std::vector<double> power;
    std::vector<uint32_t> emitterTriangles;
    tris.reserve(bvh.triangles.size());
    attrs.reserve(bvh.triangles.size());
    for (const TraceTriangle& t : bvh.triangles) {
        const GpuDraw& draw = gpuScene.draws[t.draw];
        const Primitive& prim = scene.primitives[scene.draws[t.draw].primitive];
        // Under a mirroring transform (negative determinant) glTF's front faces wind clockwise
        // (the rasterizer flips glFrontFace). Swapping corners 1 and 2 here, in the positions
        // and the attributes alike, makes counter-clockwise mean front for every ray-traced
        // triangle, so the tracers' front/back tests (culling, one-sided emitters) need no flag.
        const bool mirrored = glm::determinant(glm::mat3(draw.world)) < 0.0f;
        const int corner[3] = {0, mirrored ? 2 : 1, mirrored ? 1 : 2};
        const Vertex* v[3];
        for (int k = 0; k < 3; ++k) v[k] = &prim.vertices[prim.indices[t.primitiveTriangle * 3 + corner[k]]];
        const glm::vec3 corners[3] = {t.p0, t.p1, t.p2};
        tris.push_back({glm::vec4(corners[0], 0.0f), glm::vec4(corners[corner[1]], 0.0f), glm::vec4(corners[corner[2]], 0.0f)});
        rays::TriangleAttributes a{};
        glm::vec4* normals[3] = {&a.n0, &a.n1, &a.n2};
        glm::vec4* tangents[3] = {&a.t0, &a.t1, &a.t2};
        glm::vec4* colors[3] = {&a.c0, &a.c1, &a.c2};
        for (int k = 0; k < 3; ++k) {
            *normals[k] = glm::vec4(draw.normalMatrix * v[k]->normal, 0.0f);
            *tangents[k] = glm::vec4(glm::mat3(draw.world) * glm::vec3(v[k]->tangent), v[k]->tangent.w);
            *colors[k] = v[k]->color;
        }
        a.uv01 = glm::vec4(v[0]->uv, v[1]->uv);
        a.uv2MaterialEmitter = glm::vec4(v[2]->uv, float(draw.material), 0.0f);
        const Material& m = gpuScene.materials[draw.material].params;
        const glm::vec3 meanEmission =
            m.emissive * (layerOf(m.emissiveTexture) >= 0 ? meanLinear[m.emissiveTexture] : glm::vec3(1.0f));
        const float area = 0.5f * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
        const double p = double(area) * luminance(meanEmission) * (m.doubleSided ? 2.0 : 1.0);
        if (p > 0.0 && std::isfinite(p)) {
            emitterTriangles.push_back(uint32_t(attrs.size()));
            power.push_back(p);
        }
        attrs.push_back(a);
    }
    double totalPower = 0.0;
    for (double p : power) totalPower += p;
    std::vector<rays::Emitter> emitterData;
    double running = 0.0;
    for (size_t i = 0; i < power.size(); ++i) {
        running += power[i] / totalPower;
        emitterData.push_back({emitterTriangles[i], float(i + 1 == power.size() ? 1.0 : running), 0.0f, 0.0f});
        const TraceTriangle& t = bvh.triangles[emitterTriangles[i]];
        const float area = 0.5f * glm::length(glm::cross(t.p1 - t.p0, t.p2 - t.p0));
        attrs[emitterTriangles[i]].uv2MaterialEmitter.w = float(power[i] / totalPower / area);
    }
    emitterCount = emitterData.size();

    updateLights(scene);
    nodes = gl::createStorageBuffer(scope, int64_t(bvh.nodes.size() * sizeof(BvhNode)), bvh.nodes.data());
    triangles = gl::createStorageBuffer(scope, int64_t(tris.size() * sizeof(rays::TraceTriangle)), tris.data());
    attributes = gl::createStorageBuffer(scope, int64_t(attrs.size() * sizeof(rays::TriangleAttributes)), attrs.data());
    materials = gl::createStorageBuffer(scope, int64_t(materialData.size() * sizeof(rays::RayMaterial)), materialData.data());
    emitters = gl::createStorageBuffer(scope, int64_t(emitterData.size() * sizeof(rays::Emitter)), emitterData.data());
}

void RayScene::updateLights(const Scene& scene) {
    const std::vector<GpuLight> lightData = makeGpuLights(scene);
    lights = gl::createStorageBuffer(scope_, int64_t(lightData.size() * sizeof(GpuLight)), lightData.data());
}

void RayScene::bind(GLuint textureUnit) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightsBinding, lights.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBvhNodesBinding, nodes.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBvhTrianglesBinding, triangles.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRayAttributesBinding, attributes.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRayMaterialsBinding, materials.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRayEmittersBinding, emitters.id());
    const GLuint tex = textures.id(), smp = sampler.id();
    glBindTextures(textureUnit, 1, &tex);
    glBindSamplers(textureUnit, 1, &smp);
}

SampleAccumulator::SampleAccumulator(const gl::MemoryScope& scope, int width, int height, int target_, int perFrame_)
    : target(target_), perFrame(std::max(1, perFrame_)) {
    sum = gl::createTexture2D(scope, GL_RGBA32F, width, height);
    mean = gl::createTexture2D(scope, GL_RGBA32F, width, height);
}

void SampleAccumulator::runBatch(GLuint program) {
    glBindImageTexture(I_ACCUMULATION_SUM, sum.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(I_ACCUMULATION_MEAN, mean.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const int batch = std::min(perFrame, target - done);
    for (int i = 0; i < batch; ++i) {
        glProgramUniform1ui(program, U_SAMPLE_INDEX, GLuint(done));
        gl::dispatchCompute(gl::groupsFor(mean.width, 8), gl::groupsFor(mean.height, 8), 1, "ray tracer");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        ++done;
    }
}

}  // namespace gis
