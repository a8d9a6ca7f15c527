#include "gi/lightmap/lightmap_pass.h"

#include <chrono>
#include <iterator>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "emitter_settings.h"
#include "error.h"
#include "gi/lightmap/lightmap_uniforms.h"
#include "gi/method.h"
#include "lightmap/content_id.h"
#include "scene/atomic_file.h"
#include "services/scene_services.h"
#include "uniforms.h"

namespace gis {

using namespace lightmap;  // its uniform and binding names

namespace {
// The lookup (apply.frag): every pixel of the opaque surfaces without rays, then their pixels beside
// a wall's foot with them; then the alpha-masked surfaces, every pixel, their holes left out.
const ProgramDesc kApplyPrograms[3] = {
    {"lightmap-apply", {"gi/lightmap/apply.vert", "gi/lightmap/apply.frag"}, {{"RAY_FALLBACK", "0"}, {"CUTOUTS", "0"}}},
    {"lightmap-apply-rays", {"gi/lightmap/apply.vert", "gi/lightmap/apply.frag"}, {{"RAY_FALLBACK", "1"}, {"CUTOUTS", "0"}}},
    {"lightmap-apply-cutouts", {"gi/lightmap/apply.vert", "gi/lightmap/apply.frag"}, {{"RAY_FALLBACK", "1"}, {"CUTOUTS", "1"}}}};
constexpr size_t kCutoutProgram = 2;
// lightmap.atlas: the atlas's texels across the image.
const ProgramDesc kAtlasProgram = {"lightmap-atlas", {"fullscreen.vert", "gi/lightmap/atlas.frag"}, {}};
// path_tracer.glsl's u_term: the indirect term, or everything (emitters' direct light included).
constexpr int kTermAll = 0, kTermIndirect = 3;
// apply.frag's u_mode: the lightmap, the texels view's checker, or the seams view's chart edges.
constexpr int kShowLight = 0, kShowTexels = 1, kShowSeams = 2;
// The cache file's first line, also in the key: a change of the file format or of the bake's C++
// (its shaders are in the key themselves) bumps it, and old files are then never read.
constexpr char kCacheMagic[] = "gisandbox lightmap 3\n";

std::string describeBytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1024.0 * 1024.0));
    return text;
}

std::string cacheFolder() {
    if (const char* dir = std::getenv("GIS_LIGHTMAP_CACHE"); dir && *dir) return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/gisandbox/lightmaps";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/gisandbox/lightmaps";
    return "";
}

}  // namespace

std::vector<ProgramDesc> LightmapPass::programs() {
    std::vector<ProgramDesc> out = lightmapBakePrograms();
    out.insert(out.end(), std::begin(kApplyPrograms), std::end(kApplyPrograms));
    out.push_back(kAtlasProgram);
    return out;
}

std::vector<std::pair<std::string, uint64_t>> LightmapPass::estimateMemory(const Scene& scene, const RenderSettings& s) {
    const LightmapSettings p = lightmapParams().read("lightmap", s.params);
    const LightmapMesh mesh = lightmapMesh(scene, lightmapAtlas(scene, p));
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    return {{"lightmap atlas, texels and bake (" + std::to_string(mesh.layers) + " x " + std::to_string(mesh.side) + "^2)",
             uint64_t(LightmapBake::bytes(mesh, p.directional))},
            {"lightmap lookup (RGBA16F + depth)", pixels * (8 + 4)}};
}

LightmapPass::LightmapPass(const Scene& scene, RayScene& rays, const RenderSettings& settings, gl::MemoryLedger& ledger)
    : scene_(scene), rays_(rays), params_(lightmapParams().read("lightmap", settings.params)),
      atlas_(lightmapAtlas(scene, params_)) {
    const gl::MemoryScope scope{&ledger, kName};
    const float texelSize = atlas_.atlasSizes.empty() ? 0.0f : 1.0f / atlas_.params.texelsPerMetre;
    bake_ = std::make_unique<LightmapBake>(lightmapMesh(scene, atlas_), texelSize, params_.directional, scope);
    indirect_ = gl::createTexture2D(scope, GL_RGBA16F, settings.width, settings.height);
    depth_ = gl::createTexture2D(scope, GL_DEPTH_COMPONENT32F, settings.width, settings.height);
    fbo_ = gl::createFramebuffer();
    gbufferFbo_ = gl::createFramebuffer();
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    for (const ProgramDesc& program : kApplyPrograms)
        if (&program != &kApplyPrograms[kCutoutProgram] || bake_->hasCutouts()) applyPrograms_.push_back(buildProgram(program));
    atlasProgram_ = buildProgram(kAtlasProgram);
    atlasVao_ = gl::createVertexArray();
    rayCounts_ = createRayCounts({&ledger, kName});
}

void LightmapPass::invalidate(Changes c) {
    changed_ = true;
    // What the light depends on: the bake is stale and starts over; a lightmap already drawn stays
    // on show (marked stale) until the new one is done, not replaced by the new bake's first paths.
    if (c & (ChangeLights | ChangeGeometry | ChangeMaterials | ChangeBrdfModels)) {
        done_ = read_ = 0, cacheTried_ = false;
        stale_ = shown_;
    }
}

void LightmapPass::execute(Frame& frame) {
    const LightmapSettings now = lightmapParams().read("lightmap", frame.settings.params);
    if (now.denoise != params_.denoise || now.stitch != params_.stitch) resolved_ = false;
    if (now.samples < done_) done_ = read_ = 0;  // fewer samples asked than are in: start over
    if (now.samples != params_.samples) cacheTried_ = false;  // another bake: its own cache file
    params_ = now;
    if (!bake_->classified()) rays_.bind(), bake_->classify();
    if (!cacheTried_ && !held()) readCache(frame);
    if (done_ < params_.samples && !held()) bake(frame);
    if (stale_ && done_ >= params_.samples) stale_ = false;
    // Seams are stitched once the bake is done (a solve over every seam: not each partial mean).
    if (!resolved_ && !stale_) {
        const bool complete = done_ >= params_.samples;
        bake_->resolve(done_, params_.denoise, params_.stitch && complete);
        resolved_ = true;
        shown_ = shown_ || complete;  // a partial first bake is no result to keep through an edit
    }
    draw(frame, indirect_.id(), kShowLight);
    frame.put(resource::kIndirectDiffuse, indirect_);
    changed_ = false;
}

void LightmapPass::bake(Frame& frame) {
    if (done_ == 0) bakeStarted_ = std::chrono::steady_clock::now(), bakeSeconds_ = 0.0;
    const GLuint p = bake_->traceProgram();
    const RenderSettings& s = frame.settings;
    auto step = frame.step("trace");
    rays_.bind();
    frame.bindEnvironment();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRayCountsBinding, rayCounts_.id());
    glProgramUniform1i(p, U_LIGHT_COUNT, int(frame.scene.cpu.lights.size()));
    glProgramUniform2i(p, U_BRDF_MODELS, int(s.diffuse), int(s.specular));
    glProgramUniform1i(p, U_MAX_BOUNCES, params_.bounces);
    glProgramUniform1i(p, U_EMITTER_COUNT, int(rays_.emitterCount));
    glProgramUniform1i(p, U_RR_START, 3);
    glProgramUniform1i(p, U_CAUSTICS, 1);
    glProgramUniform1i(p, U_ENV_SAMPLING, params_.environmentSampling ? 1 : 0);
    glProgramUniform1ui(p, U_SEED, s.seed);
    // The emitters and environment the direct pass lights with are its light; otherwise the bake
    // carries theirs. A bake of all the light carries every light's (the frame draws none).
    const bool all = params_.mode == kLightmapAll;
    glProgramUniform1i(p, U_PT_TERM, !all && directPassHasLights(scene_, s) ? kTermIndirect : kTermAll);
    glProgramUniform1i(p, UL_BAKE_DIRECT, all ? 1 : 0);
    const int batch = std::min(s.samplesPerFrame, params_.samples - done_);
    bake_->trace(done_, batch);
    done_ += batch;
    resolved_ = false;
    if (done_ < params_.samples) return;
    glFinish();  // the bake's end, for its wall time
    bakeSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - bakeStarted_).count();
    writeCache();
}

void LightmapPass::draw(const Frame& frame, GLuint target, int mode) {
    const GLuint f = fbo_.id();
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0, target, 0);
    glNamedFramebufferDrawBuffer(f, GL_COLOR_ATTACHMENT0);
    gl::checkFramebuffer(f, "lightmap lookup");
    const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(f, GL_COLOR, 0, none);
    if (bake_->empty()) return;
    // A copy of the G-buffer's depth: fragments behind the surface it kept fail before shading (a
    // cleared depth cost 2.6x --gi none's frame on cornell_point in overdraw), and of those the
    // offset lets through (the last bits by which the pre-transformed positions differ), the
    // nearest wins, as depth writes stay on: the floor under a wall's foot never shades its pixel.
    const int w = frame.settings.width, h = frame.settings.height;
    glNamedFramebufferTexture(gbufferFbo_.id(), GL_DEPTH_ATTACHMENT, frame.texture(resource::kGbufferDepth), 0);
    glBlitNamedFramebuffer(gbufferFbo_.id(), f, 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    glViewport(0, 0, w, h);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, -16.0f);  // no slope term: a grazing floor must not pass a wall in front of it
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    rays_.bind();  // the second program's rays beside a wall's foot
    glBindTextureUnit(TL_LIGHTMAP, bake_->result().id());
    glBindTextureUnit(TL_TEXELS, bake_->positions().id());
    if (bake_->directional()) {
        glBindTextureUnit(TL_DIRECTION, bake_->direction().id());
        glBindTextureUnit(TL_SHADING_NORMAL, frame.texture(resource::kGbufferNormal));
    }
    glBindTextureUnit(TL_GBUFFER_DEPTH, frame.texture(resource::kGbufferDepth));
    for (size_t i = 0; i < applyPrograms_.size(); ++i) {
        const GLuint p = applyPrograms_[i].id();
        glUseProgram(p);
        glProgramUniform1i(p, UL_DIRECTIONAL, bake_->directional() ? 1 : 0);
        glProgramUniformMatrix4fv(p, UL_VIEW_PROJ, 1, GL_FALSE, &frame.camera.viewProj[0][0]);
        glProgramUniform1i(p, UL_MODE, mode);
        glProgramUniform1i(p, UL_STEP, bake_->mesh().side);
        glProgramUniform1f(p, UL_TEXEL_SIZE, bake_->texelSize());
        if (i == kCutoutProgram) glProgramUniformMatrix4fv(p, UL_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
        bake_->drawSurfaces(i == kCutoutProgram);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// The atlas's texels across the target (atlas.frag), drawn without the G-buffer.
void LightmapPass::drawAtlas(const Frame& frame, GLuint target) {
    const GLuint f = fbo_.id();
    glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0, target, 0);
    glNamedFramebufferDrawBuffer(f, GL_COLOR_ATTACHMENT0);
    const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearNamedFramebufferfv(f, GL_COLOR, 0, black);
    if (bake_->empty()) return;
    glBindFramebuffer(GL_FRAMEBUFFER, f);
    glViewport(0, 0, frame.settings.width, frame.settings.height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    const GLuint p = atlasProgram_.id();
    glUseProgram(p);
    glProgramUniform1i(p, UL_STEP, bake_->mesh().side);
    glProgramUniform1i(p, UL_LAYERS, bake_->mesh().layers);
    glProgramUniform2f(p, UL_TARGET_SIZE, float(frame.settings.width), float(frame.settings.height));
    glBindTextureUnit(TL_LIGHTMAP, bake_->result().id());
    glBindTextureUnit(TL_TEXELS, bake_->positions().id());
    glBindVertexArray(atlasVao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<DebugViewDesc> LightmapPass::debugViews() const {
    return {{"lightmap.texels", "the lightmap's texels on the surfaces as a checker (one square per texel), tinted "
                                "by the baked light: the density each surface got"},
            {"lightmap.seams", "the charts' edges in magenta on the surfaces (grey): where two charts of one "
                               "surface meet, a seam would show"},
            {"lightmap.atlas", "the atlas itself, its layers side by side: each texel's baked light (normalised), "
                               "chart borders magenta, texels inside geometry cyan, the dilated gutter dimmed"}};
}

void LightmapPass::drawDebugView(const std::string& view, const Frame& frame, GLuint target) {
    if (view == "lightmap.atlas") return drawAtlas(frame, target);
    draw(frame, target, view == "lightmap.seams" ? kShowSeams : kShowTexels);
}

std::string LightmapPass::cacheKey(const Frame& frame) const {
    ContentId id;
    id.add(kCacheMagic);
    // The bake's own code: a changed shader (the paths, the texels, their classification) bakes anew.
    for (const ProgramDesc& program : lightmapBakePrograms())
        for (const std::string& stage : program.stages) id.add(preprocessShader(stage, program.defines).source);
    const GltfBytes bytes = serializeGltf(scene_, "scene.bin");
    id.add(bytes.json), id.add(bytes.bin);
    const RenderSettings& s = frame.settings;
    id.add(s.environment);
    if (!s.environment.empty()) {
        std::ifstream in(s.environment, std::ios::binary);
        std::ostringstream content;
        content << in.rdbuf();
        id.add(content.str());
    }
    id.value(s.environmentRotation), id.value(frame.background());
    id.value(int(s.diffuse)), id.value(int(s.specular)), id.value(s.seed);
    id.value(emittersAreLights(scene_, s)), id.value(environmentIsLight(scene_, s));
    id.add(atlas_.hash);
    id.value(params_.samples), id.value(params_.bounces), id.value(params_.environmentSampling), id.value(params_.mode);
    id.value(params_.directional);
    return id.hex();
}

void LightmapPass::readCache(const Frame& frame) {
    cacheTried_ = true;
    cachePath_.clear();
    if (!params_.cache || bake_->empty()) return void(cacheState_ = params_.cache ? "nothing to bake" : "off");
    const std::string folder = cacheFolder();
    if (folder.empty()) return void(cacheState_ = "no folder (set GIS_LIGHTMAP_CACHE)");
    cachePath_ = folder + "/" + cacheKey(frame) + ".lightmap";
    std::ifstream in(cachePath_, std::ios::binary);
    if (!in) return void(cacheState_ = "miss " + cachePath_);
    std::string magic(sizeof kCacheMagic - 1, '\0');
    int32_t header[3] = {};
    in.read(magic.data(), std::streamsize(magic.size()));
    in.read(reinterpret_cast<char*>(header), sizeof header);
    const LightmapMesh& m = bake_->mesh();
    if (!in || magic != kCacheMagic || header[0] != m.side || header[1] != m.layers || header[2] != params_.samples)
        return void(cacheState_ = "unreadable " + cachePath_ + " (baking again)");
    std::vector<float> texels(size_t(bake_->meanFloats()));
    in.read(reinterpret_cast<char*>(texels.data()), std::streamsize(texels.size() * sizeof(float)));
    if (!in) return void(cacheState_ = "truncated " + cachePath_ + " (baking again)");
    bake_->loadMean(texels);
    done_ = read_ = params_.samples;
    resolved_ = false;
    cacheState_ = "read " + cachePath_;
}

// A failed write costs the next run a bake, nothing else: it is said, not thrown.
void LightmapPass::writeCache() {
    if (!params_.cache || cachePath_.empty()) return;
    try {
        std::filesystem::create_directories(std::filesystem::path(cachePath_).parent_path());
        const LightmapMesh& m = bake_->mesh();
        const int32_t header[3] = {m.side, m.layers, params_.samples};
        const std::vector<float> texels = bake_->readMean();
        AtomicFile file(cachePath_);
        file.write(kCacheMagic, sizeof kCacheMagic - 1);
        file.write(header, sizeof header);
        file.write(texels.data(), texels.size() * sizeof(float));
        file.commit();
        cacheState_ = "written " + cachePath_;
    } catch (const std::exception& e) {
        cacheState_ = std::string("not written: ") + e.what();
        std::fprintf(stderr, "warning: lightmap cache %s\n", cacheState_.c_str());
    }
}

std::optional<int64_t> LightmapPass::atlasTexels() const {
    if (bake_->empty()) return int64_t(0);
    const LightmapMesh& m = bake_->mesh();
    return int64_t(m.layers) * m.side * m.side;
}

std::vector<std::string> LightmapPass::stats() const {
    if (bake_->empty()) return {"lightmap: no surfaces to bake"};
    const LightmapMesh& m = bake_->mesh();
    char line[320];
    std::snprintf(line, sizeof line,
                  "lightmap %d atlas%s of %d^2, %d texels on surfaces (fill %.2f), %d inside geometry, %d steps "
                  "blocked, %d charts in %d regions, %.4g texels per unit, %s",
                  m.layers, m.layers == 1 ? "" : "es", m.side, bake_->validTexels(), atlas_.fill(), bake_->insideTexels(),
                  bake_->blockedLinks(), int(atlas_.charts.size()), bake_->regions(),
                  double(atlas_.params.texelsPerMetre),
                  describeBytes(double(LightmapBake::bytes(m, bake_->directional()))).c_str());
    std::vector<std::string> out{line};
    std::snprintf(line, sizeof line, "lightmap bake %d / %d paths per texel, %d bounces, %s%s", done_, params_.samples,
                  params_.bounces, params_.mode == kLightmapAll ? "all the light (the frame draws none)" : "indirect light",
                  done_ >= params_.samples && bakeSeconds_ > 0.0
                                       ? (", " + std::to_string(bakeSeconds_).substr(0, 6) + " s").c_str() : "");
    out.push_back(line);
    if (bake_->seamPoints() == 0)
        out.push_back("lightmap seams: none to stitch (chart borders are creases or on charts too narrow to carry light)");
    else {
        std::snprintf(line, sizeof line, "lightmap seams: %d points where a smooth surface's charts meet, %s",
                      bake_->seamPoints(), params_.stitch ? "stitched" : "not stitched (lightmap.stitch=false)");
        out.push_back(line + (params_.stitch ? " (largest gap " + std::to_string(bake_->seamGapBefore()) + " of the seams' mean "
                                                   "light before, " + std::to_string(bake_->seamGap()) + " after)"
                                             : ""));
    }
    out.push_back("lightmap cache: " + cacheState_);
    return out;
}

std::optional<RayCounts> LightmapPass::raysTraced() const { return readRayCounts(rayCounts_); }

GiMethod lightmapMethod() {
    GiMethod m;
    m.name = "lightmap";
    m.summary = "baked lightmaps: the path tracer's light per texel of an atlas, baked once (cached), looked up per frame";
    m.params = lightmapParams().rows;
    // Sized for llvmpipe, where a path per texel costs about 7 us: medium bakes the Cornell box in
    // seconds, high in under two minutes (the README's table).
    m.presets = {{"low", "4k texels, 32 paths each", {{"lightmap.texels", {4096.0}}, {"lightmap.samples", {32.0}}}},
                 {"medium", "16k texels, 64 paths each", {{"lightmap.texels", {16384.0}}, {"lightmap.samples", {64.0}}}},
                 {"high", "64k texels, 256 paths each", {{"lightmap.texels", {65536.0}}, {"lightmap.samples", {256.0}}}}};
    m.bakesDirectLight = [](const RenderSettings& s) {
        return lightmapParams().read("lightmap", s.params).mode == kLightmapAll;
    };
    m.programs = &LightmapPass::programs;
    m.estimateMemory = &LightmapPass::estimateMemory;
    m.addPasses = [](MethodBuild& b) {
        b.add(std::make_unique<LightmapPass>(b.scene, b.services.rays(), b.settings, b.ledger));
    };
    // The bake's frames (render stops at its progress: progress()), capped as the probes' are.
    m.framesToConverge = [](const RenderSettings& s) {
        return std::min(lightmapParams().read("lightmap", s.params).samples / std::max(1, s.samplesPerFrame) + 1, 1024);
    };
    m.shaderTables.uniforms = tableRows(lightmap::kLightmapUniforms);
    m.shaderTables.bindings = tableRows(lightmap::kLightmapBindings);
    return m;
}

}  // namespace gis
