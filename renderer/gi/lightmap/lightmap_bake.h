// The lightmap's bake on the GPU (issue #41): the atlas's texels rasterized in UV space (world
// position, texel size, normal, chart), then paths traced from each texel by the path tracer's
// own code (shaders/path_tracer.glsl), their running mean per texel; a finished or partial mean is
// filtered within its charts and dilated into the gutters for bilinear lookups. Holds its GPU
// images under its pass's name in the memory ledger.
#pragma once

#include <string>
#include <vector>

#include "gl/gl.h"
#include "gl/shader.h"
#include "lightmap/atlas.h"
#include "lightmap/seams.h"

namespace gis {

struct Scene;

// The atlas's triangles as the GPU draws them, in world space: grouped by atlas (one draw range
// each), their UVs in the array's layer (an atlas smaller than the largest fills its corner).
struct LightmapMesh {
    struct Vertex {
        float position[3];
        float normal[3];
        float uv[2];
        float layer, chart, doubleSided;
    };
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<std::pair<uint32_t, uint32_t>> ranges;  // per atlas: first index, index count
    // The same triangles as the lookup draws them: the opaque ones, then from cutoutFirst on
    // those of alpha-masked materials (whose holes the G-buffer saw through).
    std::vector<uint32_t> surfaceIndices;
    uint32_t cutoutFirst = 0;
    std::vector<int> chartTexels;  // per chart: its rectangle's shorter side, texels
    int side = 0;                                        // the array's side, texels
    int layers = 0;
};
LightmapMesh lightmapMesh(const Scene& scene, const lightmap::Atlas& atlas);
std::vector<ProgramDesc> lightmapBakePrograms();

class LightmapBake {
public:
    // Images of one texel: position, normal, the paths' mean and two filter targets; directional,
    // the mean direction and its two filter targets too.
    static constexpr int64_t kBytesPerTexel = 16 + 16 + 16 + 8 + 8;
    static constexpr int64_t kDirectionalBytesPerTexel = 16 + 8 + 8;
    // GPU bytes at the peak, while the texels are rasterized (the atlas's index buffer is then held too).
    static int64_t bytes(const LightmapMesh& mesh, bool directional);

    // `texelSize`: world units per texel (the atlas's 1 / texels per metre). `directional`: the
    // paths' luminance-weighted mean direction is kept too (lightmap.directional).
    LightmapBake(const LightmapMesh& mesh, float texelSize, bool directional, const gl::MemoryScope& scope);
    LightmapBake(const LightmapBake&) = delete;  // result_ points into the bake's own images
    LightmapBake& operator=(const LightmapBake&) = delete;
    bool empty() const { return mesh_.layers == 0; }
    // Paths sample `done` onwards of every texel, `count` of them: the ray scene, the environment
    // and the path tracer's uniforms are bound by the caller on traceProgram(), after classify().
    void trace(int done, int count);
    // Which texels are inside geometry and which neighbours a wall parts (classify.comp): once,
    // with the ray scene bound, before the first trace or resolve.
    void classify();
    bool classified() const { return classified_; }
    int regions() const { return regions_; }  // charts split where walls part their texels
    int insideTexels() const { return insideTexels_; }  // texels whose centre is behind a surface
    int blockedLinks() const { return blockedLinks_; }  // texel-to-neighbour steps a surface blocks
    GLuint traceProgram() const { return trace_.id(); }
    // The lightmap from the mean of `samples` paths: denoised or not, its seams stitched or not
    // (lightmap/seams.h: on the CPU, between the denoiser and the dilation), dilated into the gutters.
    void resolve(int samples, bool denoise, bool stitch);
    int seamPoints() const { return int(seams_.size()); }
    // The largest difference between a seam's two sides over the mean light along the seams,
    // before and after the last stitch.
    float seamGapBefore() const { return seamGapBefore_; }
    float seamGap() const { return seamGap_; }
    const gl::Texture& result() const { return *result_; }
    bool directional() const { return directional_; }
    // Directional: the light's mean direction (xyz, |xyz| <= 1) per texel, filtered as the result.
    const gl::Texture& direction() const { return *directionResult_; }
    // Draws the opaque atlas triangles or those of alpha-masked materials (apply.vert's attributes)
    // with the bound program.
    void drawSurfaces(bool cutouts) const;
    bool hasCutouts() const { return mesh_.cutoutFirst < mesh_.surfaceIndices.size(); }
    const gl::Texture& positions() const { return position_; }  // w: 1 + classify.comp's flags
    // The paths' mean as it is stored (RGBA32F per texel: rgb, the luminance's second moment;
    // directional, then the mean direction's), for the cache; loadMean() puts a read one back.
    std::vector<float> readMean() const;
    void loadMean(const std::vector<float>& texels);
    int64_t meanFloats() const { return int64_t(mesh_.side) * mesh_.side * mesh_.layers * 4 * (directional_ ? 2 : 1); }
    const LightmapMesh& mesh() const { return mesh_; }
    int validTexels() const { return validTexels_; }  // texels on a surface, counted by classify()
    float texelSize() const { return texelSize_; }

private:
    void rasterizeTexels(const gl::MemoryScope& scope);
    void splitChartsAtWalls();
    void filterStep(const gl::Texture& from, const gl::Texture& to, int mode, int step, int samples);
    void stitch(const gl::Texture& image, bool light);  // light: its gaps are reported (else the direction)
    const gl::Texture* filterImages(const gl::Texture& source, gl::Texture& ping, gl::Texture& pong, bool denoise,
                                    bool stitchSeams, int samples);

    LightmapMesh mesh_;
    float texelSize_ = 0.0f;
    gl::Buffer vertices_, surfaceIndices_;
    gl::Object vao_, classify_, trace_, filter_;
    bool classified_ = false;  // classify.comp ran (it needs the ray scene, bound at the first trace)
    bool directional_ = false;
    gl::Texture position_, normal_, mean_, ping_, pong_;
    gl::Texture direction_, directionPing_, directionPong_;  // directional only
    const gl::Texture* result_ = nullptr;
    const gl::Texture* directionResult_ = nullptr;
    int validTexels_ = 0;
    int regions_ = 0, insideTexels_ = 0, blockedLinks_ = 0;
    std::vector<lightmap::SeamPoint> seams_;
    float seamGapBefore_ = 0.0f, seamGap_ = 0.0f;
};

}  // namespace gis
