#include "gi/lightmap/lightmap_bake.h"

#include <algorithm>
#include <cstddef>

#include "error.h"
#include "gi/lightmap/lightmap_uniforms.h"
#include "gl/dispatch.h"
#include "gl/shader.h"
#include "scene/scene.h"
#include "uniforms.h"

namespace gis {

using namespace lightmap;

namespace {
const ProgramDesc kTexelProgram{"lightmap-texels", {"gi/lightmap/texels.vert", "gi/lightmap/texels.frag"}, {{"EDGES", "0"}}};
const ProgramDesc kTexelEdgesProgram{"lightmap-texel-edges",
                                     {"gi/lightmap/texels.vert", "gi/lightmap/texel_edges.geom", "gi/lightmap/texels.frag"},
                                     {{"EDGES", "1"}}};
const ProgramDesc kClassifyProgram{"lightmap-classify", {"gi/lightmap/classify.comp"}, {}};
const ProgramDesc kTraceProgram{"lightmap-trace", {"gi/lightmap/trace.comp"}, {}};
const ProgramDesc kFilterProgram{"lightmap-filter", {"gi/lightmap/filter.comp"}, {}};
constexpr int kGroup = 8;           // trace.comp's and filter.comp's local size (x and y)
enum FilterMode { kCopy = 0, kDenoise = 1, kDilate = 2, kCopyDirection = 3 };  // filter.comp's u_mode
// Charts narrower than this many texels are not stitched: a column cut into charts a texel wide
// has no texels between its seams to carry the light's change around it, and making every seam
// agree smoothed its sunlit side into its shaded one (the atrium's columns: README).
constexpr int kStitchedChartTexels = 4;
// The a-trous steps (Dammertz et al. 2010): 1, 2, 4 texels, a 5x5 kernel each, 29 texels across.
constexpr int kDenoiseSteps[] = {1, 2, 4};
}  // namespace

std::vector<ProgramDesc> lightmapBakePrograms() { return {kTexelProgram, kTexelEdgesProgram, kClassifyProgram, kTraceProgram, kFilterProgram}; }

LightmapMesh lightmapMesh(const Scene& scene, const Atlas& atlas) {
    LightmapMesh out;
    out.layers = int(atlas.atlasSizes.size());
    for (int side : atlas.atlasSizes) out.side = std::max(out.side, side);
    std::vector<std::vector<uint32_t>> byAtlas(size_t(out.layers));
    std::vector<uint32_t> cutouts;
    for (size_t m = 0; m < atlas.meshes.size(); ++m) {
        const MeshAtlas& ma = atlas.meshes[m];
        const DrawItem& draw = scene.draws[m];  // meshesFromScene: one mesh per draw
        const Primitive& p = scene.primitives[size_t(draw.primitive)];
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(draw.world)));
        const bool doubleSided = p.material >= 0 && scene.materials[size_t(p.material)].doubleSided;
        const uint32_t base = uint32_t(out.vertices.size());
        for (size_t v = 0; v < ma.sourceVertex.size(); ++v) {
            const Vertex& src = p.vertices[ma.sourceVertex[v]];
            const glm::vec3 pos = glm::vec3(draw.world * glm::vec4(src.position, 1.0f));
            glm::vec3 n = normalMatrix * src.normal;
            n = glm::dot(n, n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 1.0f, 0.0f);
            const int a = atlas.atlasOf(m, v);
            const float scale = float(atlas.atlasSizes[size_t(a)]) / float(out.side);
            out.vertices.push_back({{pos.x, pos.y, pos.z}, {n.x, n.y, n.z}, {ma.uv[v].x * scale, ma.uv[v].y * scale},
                                    float(a), float(ma.chart[v]), doubleSided ? 1.0f : 0.0f});
        }
        const bool masked = p.material >= 0 && scene.materials[size_t(p.material)].alphaMode == AlphaMode::Mask;
        for (size_t t = 0; t + 2 < ma.indices.size(); t += 3) {
            auto& list = byAtlas[size_t(atlas.atlasOf(m, ma.indices[t]))];
            for (int k = 0; k < 3; ++k) {
                list.push_back(base + ma.indices[t + size_t(k)]);
                (masked ? cutouts : out.surfaceIndices).push_back(base + ma.indices[t + size_t(k)]);
            }
        }
    }
    for (const std::vector<uint32_t>& list : byAtlas) {
        out.ranges.emplace_back(uint32_t(out.indices.size()), uint32_t(list.size()));
        out.indices.insert(out.indices.end(), list.begin(), list.end());
    }
    for (const Chart& c : atlas.charts) out.chartTexels.push_back(std::min(c.width, c.height));
    out.cutoutFirst = uint32_t(out.surfaceIndices.size());
    out.surfaceIndices.insert(out.surfaceIndices.end(), cutouts.begin(), cutouts.end());
    return out;
}

int64_t LightmapBake::bytes(const LightmapMesh& mesh, bool directional) {
    return int64_t(mesh.side) * mesh.side * mesh.layers * (kBytesPerTexel + (directional ? kDirectionalBytesPerTexel : 0)) +
           int64_t(mesh.vertices.size() * sizeof(LightmapMesh::Vertex)) + int64_t(mesh.indices.size() * 4) +
           int64_t(mesh.surfaceIndices.size() * 4);
}

LightmapBake::LightmapBake(const LightmapMesh& mesh, float texelSize, bool directional, const gl::MemoryScope& scope)
    : mesh_(mesh), texelSize_(texelSize), directional_(directional) {
    if (empty()) return;
    const int s = mesh_.side, n = mesh_.layers;
    position_ = gl::createTexture2DArray(scope, GL_RGBA32F, s, s, n);
    normal_ = gl::createTexture2DArray(scope, GL_RGBA32F, s, s, n);
    mean_ = gl::createTexture2DArray(scope, GL_RGBA32F, s, s, n);
    ping_ = gl::createTexture2DArray(scope, GL_RGBA16F, s, s, n);
    pong_ = gl::createTexture2DArray(scope, GL_RGBA16F, s, s, n);
    if (directional_) {
        direction_ = gl::createTexture2DArray(scope, GL_RGBA32F, s, s, n);
        directionPing_ = gl::createTexture2DArray(scope, GL_RGBA16F, s, s, n);
        directionPong_ = gl::createTexture2DArray(scope, GL_RGBA16F, s, s, n);
        directionResult_ = &directionPing_;
    }
    // The lookup filters the result bilinearly where no texel of the four is to be left out.
    for (const gl::Texture* t : {&ping_, &pong_, &directionPing_, &directionPong_})
        if (t->id()) {
            glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
    vertices_ = gl::createBuffer(scope, int64_t(mesh_.vertices.size() * sizeof(LightmapMesh::Vertex)), mesh_.vertices.data());
    surfaceIndices_ = gl::createBuffer(scope, int64_t(mesh_.surfaceIndices.size() * 4), mesh_.surfaceIndices.data());
    classify_ = buildProgram(kClassifyProgram);
    trace_ = buildProgram(kTraceProgram);
    filter_ = buildProgram(kFilterProgram);
    glProgramUniform1f(classify_.id(), UL_TEXEL_SIZE, texelSize_);
    glProgramUniform1f(filter_.id(), UL_TEXEL_SIZE, texelSize_);
    glProgramUniform1i(trace_.id(), UL_DIRECTIONAL, directional_ ? 1 : 0);
    result_ = &ping_;
    rasterizeTexels(scope);
    std::vector<SeamVertex> seamVertices;
    for (const LightmapMesh::Vertex& v : mesh_.vertices)
        seamVertices.push_back({glm::vec3(v.position[0], v.position[1], v.position[2]),
                                glm::vec3(v.normal[0], v.normal[1], v.normal[2]),
                                glm::vec2(v.uv[0], v.uv[1]) * float(mesh_.side), int(v.layer),
                                mesh_.chartTexels[size_t(v.chart)] < kStitchedChartTexels});
    seams_ = findSeams(seamVertices, mesh_.indices);
}

// The atlas triangles' indices and the two texel programs are needed for this draw alone (the
// lookup draws surfaceIndices_).
void LightmapBake::rasterizeTexels(const gl::MemoryScope& scope) {
    const gl::Buffer atlasIndices = gl::createBuffer(scope, int64_t(mesh_.indices.size() * 4), mesh_.indices.data());
    vao_ = gl::createVertexArray();
    const GLuint vao = vao_.id();
    glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, sizeof(LightmapMesh::Vertex));
    glVertexArrayElementBuffer(vao, atlasIndices.id());
    const GLuint offsets[] = {offsetof(LightmapMesh::Vertex, position), offsetof(LightmapMesh::Vertex, normal),
                              offsetof(LightmapMesh::Vertex, uv), offsetof(LightmapMesh::Vertex, layer)};
    const GLint sizes[] = {3, 3, 2, 3};
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    gl::Object fbo = gl::createFramebuffer();
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
    const gl::Object fillProgram = buildProgram(kTexelProgram), edgesProgram = buildProgram(kTexelEdgesProgram);
    glBindVertexArray(vao);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glViewport(0, 0, mesh_.side, mesh_.side);
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int layer = 0; layer < mesh_.layers; ++layer) {
        glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, position_.id(), 0, layer);
        glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT1, normal_.id(), 0, layer);
        gl::checkFramebuffer(fbo.id(), "lightmap texels");
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        for (int i = 0; i < 2; ++i) glClearNamedFramebufferfv(fbo.id(), GL_COLOR, i, clear);
        const auto [first, count] = mesh_.ranges[size_t(layer)];
        // Texels whose centre a triangle covers get its point there. The triangles' outlines are drawn
        // first as lines (texel_edges.geom): a triangle thinner than a texel in the atlas (a sphere's
        // pole) covers no centre, and its pixels would find only gutters within reach of their
        // lookup (black); the texels along its edges get points next to the edges. The fill then
        // wins where both reach.
        const void* offset = reinterpret_cast<const void*>(uintptr_t(first) * 4);
        glUseProgram(edgesProgram.id());
        glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT, offset);
        glUseProgram(fillProgram.id());
        glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT, offset);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glVertexArrayElementBuffer(vao, surfaceIndices_.id());  // from now on the lookup draws the surfaces
}

void LightmapBake::drawSurfaces(bool cutouts) const {
    const uint32_t first = cutouts ? mesh_.cutoutFirst : 0;
    const uint32_t count = cutouts ? uint32_t(mesh_.surfaceIndices.size()) - first : mesh_.cutoutFirst;
    if (count == 0) return;
    glBindVertexArray(vao_.id());
    glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT, reinterpret_cast<const void*>(uintptr_t(first) * 4));
    glBindVertexArray(0);
}

void LightmapBake::classify() {
    if (empty()) return;
    glUseProgram(classify_.id());
    glBindImageTexture(IL_POSITION, position_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    glBindImageTexture(IL_NORMAL, normal_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    gl::dispatchCompute(gl::groupsFor(mesh_.side, kGroup), gl::groupsFor(mesh_.side, kGroup), GLuint(mesh_.layers),
                        "lightmap texel classification");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    splitChartsAtWalls();
    classified_ = true;
}

namespace {
// Union-find over texels, with path halving.
int findRoot(std::vector<int>& parent, int i) {
    while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
    return i;
}
}  // namespace

// The denoiser's a-trous taps jump up to 12 texels, past any one neighbour's flag: it mixes only
// texels of one region, the texels of a chart that reach each other through unblocked neighbours
// (a floor chart running under a wall becomes one region each side). The region replaces the
// chart in the normal's w; found here on the CPU, once per bake.
void LightmapBake::splitChartsAtWalls() {
    const int side = mesh_.side, texels = side * side * mesh_.layers;
    std::vector<float> position(static_cast<size_t>(texels) * 4), normal(static_cast<size_t>(texels) * 4);
    glGetTextureImage(position_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(position.size() * 4), position.data());
    glGetTextureImage(normal_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(normal.size() * 4), normal.data());
    auto flags = [&](int i) { return position[size_t(i) * 4 + 3] > 0.0f ? int(position[size_t(i) * 4 + 3]) - 1 : -1; };
    constexpr int kInside = 16, kPlusX = 1, kMinusX = 2, kPlusY = 4, kMinusY = 8;  // lightmap_texels.glsl
    std::vector<int> parent(static_cast<size_t>(texels));
    for (int i = 0; i < texels; ++i) parent[size_t(i)] = i;
    auto own = [&](int i) { return flags(i) >= 0 && (flags(i) & kInside) == 0; };
    auto link = [&](int a, int b, int bitAB, int bitBA) {
        if (!own(a) || !own(b) || normal[size_t(a) * 4 + 3] != normal[size_t(b) * 4 + 3]) return;
        if ((flags(a) & bitAB) || (flags(b) & bitBA)) return;
        parent[size_t(findRoot(parent, a))] = findRoot(parent, b);
    };
    for (int layer = 0; layer < mesh_.layers; ++layer)
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const int i = (layer * side + y) * side + x;
                if (x + 1 < side) link(i, i + 1, kPlusX, kMinusX);
                if (y + 1 < side) link(i, i + side, kPlusY, kMinusY);
            }
    validTexels_ = insideTexels_ = blockedLinks_ = 0;
    for (int i = 0; i < texels; ++i) {
        if (flags(i) < 0) continue;
        ++validTexels_;
        insideTexels_ += (flags(i) & kInside) ? 1 : 0;
        for (int bit : {kPlusX, kMinusX, kPlusY, kMinusY}) blockedLinks_ += (flags(i) & bit) ? 1 : 0;
    }
    regions_ = 0;
    std::vector<int> region(static_cast<size_t>(texels), -1);
    for (int i = 0; i < texels; ++i) {
        if (!own(i)) continue;
        int& r = region[size_t(findRoot(parent, i))];
        if (r < 0) r = regions_++;
        normal[size_t(i) * 4 + 3] = float(r + 1);
    }
    glTextureSubImage3D(normal_.id(), 0, 0, 0, 0, side, side, mesh_.layers, GL_RGBA, GL_FLOAT, normal.data());
}

void LightmapBake::trace(int done, int count) {
    if (empty()) return;
    const GLuint p = trace_.id();
    glUseProgram(p);
    glBindImageTexture(IL_POSITION, position_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IL_NORMAL, normal_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IL_MEAN, mean_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    if (directional_) glBindImageTexture(IL_DIRECTION, direction_.id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    for (int i = 0; i < count; ++i) {
        glProgramUniform1ui(p, U_SAMPLE_INDEX, GLuint(done + i));
        gl::dispatchCompute(gl::groupsFor(mesh_.side, kGroup), gl::groupsFor(mesh_.side, kGroup), GLuint(mesh_.layers),
                            "lightmap bake");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

void LightmapBake::filterStep(const gl::Texture& from, const gl::Texture& to, int mode, int step, int samples) {
    const GLuint p = filter_.id();
    glBindImageTexture(IL_SOURCE, from.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
    glBindImageTexture(IL_TARGET, to.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glProgramUniform1i(p, UL_MODE, mode);
    glProgramUniform1i(p, UL_STEP, step);
    glProgramUniform1i(p, UL_SAMPLES, samples);
    gl::dispatchCompute(gl::groupsFor(mesh_.side, kGroup), gl::groupsFor(mesh_.side, kGroup), GLuint(mesh_.layers),
                        "lightmap filter");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void LightmapBake::stitch(const gl::Texture& lightmap, bool light) {
    TexelImage image{std::vector<float>(size_t(mesh_.side) * size_t(mesh_.side) * size_t(mesh_.layers) * 4), mesh_.side,
                     mesh_.layers};
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    glGetTextureImage(lightmap.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * 4), image.rgba.data());
    const StitchGaps gaps = stitchSeams(seams_, image, 256, light);
    if (light) seamGapBefore_ = gaps.before, seamGap_ = gaps.after;
    glTextureSubImage3D(lightmap.id(), 0, 0, 0, 0, mesh_.side, mesh_.side, mesh_.layers, GL_RGBA, GL_FLOAT,
                        image.rgba.data());
}

// The mean (or, kCopyDirection, the mean direction over the mean's luminance) copied into `ping`,
// denoised within its regions, stitched, dilated; returns the image holding the result.
const gl::Texture* LightmapBake::filterImages(const gl::Texture& source, gl::Texture& ping, gl::Texture& pong,
                                              bool denoise, bool stitchSeams, int samples) {
    gl::Texture* from = &ping;
    gl::Texture* to = &pong;
    filterStep(*to, *from, &source == &mean_ ? kCopy : kCopyDirection, 0, samples);  // (its source is not read)
    if (denoise)
        for (int step : kDenoiseSteps) filterStep(*from, *to, kDenoise, step, samples), std::swap(from, to);
    if (stitchSeams && !seams_.empty()) stitch(*from, &source == &mean_);
    // Two texels of dilation: the atlas's gutter, so bilinear lookups at a chart's border never
    // read an unlit texel.
    for (int i = 0; i < 2; ++i) filterStep(*from, *to, kDilate, 1, samples), std::swap(from, to);
    return from;
}

void LightmapBake::resolve(int samples, bool denoise, bool stitchSeams) {
    if (empty()) return;
    const GLuint p = filter_.id();
    glUseProgram(p);
    glBindImageTexture(IL_POSITION, position_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IL_NORMAL, normal_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(IL_MEAN, mean_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glProgramUniform1i(p, UL_DIRECTIONAL, 0);
    result_ = filterImages(mean_, ping_, pong_, denoise, stitchSeams, samples);
    if (!directional_) return;
    // The direction: the same denoiser without its luminance edges (a direction has no
    // luminance), stitched and dilated as the light.
    glBindImageTexture(IL_DIRECTION, direction_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32F);
    glProgramUniform1i(p, UL_DIRECTIONAL, 1);
    directionResult_ = filterImages(direction_, directionPing_, directionPong_, denoise, stitchSeams, samples);
}

std::vector<float> LightmapBake::readMean() const {
    std::vector<float> texels(static_cast<size_t>(meanFloats()));
    if (empty()) return texels;
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // the trace's image stores, before the read back
    const size_t half = directional_ ? texels.size() / 2 : texels.size();
    glGetTextureImage(mean_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(half * 4), texels.data());
    if (directional_) glGetTextureImage(direction_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(half * 4), texels.data() + half);
    return texels;
}

void LightmapBake::loadMean(const std::vector<float>& texels) {
    if (empty() || int64_t(texels.size()) != meanFloats())
        throw Error("lightmap: a cached bake of " + std::to_string(texels.size()) + " floats for " +
                    std::to_string(meanFloats()));
    glTextureSubImage3D(mean_.id(), 0, 0, 0, 0, mesh_.side, mesh_.side, mesh_.layers, GL_RGBA, GL_FLOAT, texels.data());
    if (directional_)
        glTextureSubImage3D(direction_.id(), 0, 0, 0, 0, mesh_.side, mesh_.side, mesh_.layers, GL_RGBA, GL_FLOAT,
                            texels.data() + texels.size() / 2);
}

}  // namespace gis
