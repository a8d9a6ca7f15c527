#include "passes/shadow_pass.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_draw.h"
#include "uniforms.h"

namespace gis {

namespace {

std::array<glm::vec3, 8> corners(const Aabb& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[i] = glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
    return c;
}

glm::vec3 anyPerpendicularUp(const glm::vec3& dir) {
    return std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

// Near plane for perspective shadow views: a small fraction of the scene, never zero.
// Relative to the scene, with floors far below any modelled size: an absolute 1e-5 put the near
// plane beyond a scene modelled at 1e-6 units, and its shadows vanished.
float shadowNear(float sceneRadius) { return std::max(sceneRadius * 1e-3f, 1e-30f); }

// How far along the view a directional light's map around the camera reaches, as a share of the
// scene's diameter: what the camera sees near it, where its pixels are finer than the scene map's
// texels (a corridor's sun patches); beyond, the scene's map.
constexpr float kCameraMapReach = 0.25f;
// The camera's map's edge is the scene map's shortened by whole quarter octaves (a small zoom
// renders nothing again), by at least this many: where the view's box is no smaller than that the
// camera's map would be hardly finer, and the scene's alone is read.
constexpr int kCameraMapMinQuarterOctaves = 2;

// The camera's view up to `reach`, in a directional light's space: the box (x, y) around it.
void viewBox(const CameraMatrices& camera, const glm::mat4& lightView, float reach, glm::vec2& lo, glm::vec2& hi) {
    const glm::vec4 farClip = camera.proj * glm::vec4(0.0f, 0.0f, -std::min(reach, camera.zfar), 1.0f);
    const float farNdc = std::clamp(farClip.z / std::max(farClip.w, 1e-30f), -1.0f, 1.0f);
    lo = glm::vec2(1e30f);
    hi = glm::vec2(-1e30f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 ndc(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? farNdc : -1.0f, 1.0f);
        const glm::vec4 world = camera.invViewProj * ndc;
        const glm::vec2 p = glm::vec2(lightView * glm::vec4(glm::vec3(world) / world.w, 1.0f));
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
}

// viewCascade (shadows.glsl: the scale and offset that take the scene map's clip x, y to the
// camera map's) for a camera map whose square from `lo` has edge `size`, inside the scene map's
// box [sceneLo, sceneHi].
glm::vec4 viewCascade(glm::vec2 sceneLo, glm::vec2 sceneHi, glm::vec2 lo, float size) {
    const glm::vec2 scale = (sceneHi - sceneLo) / size;
    const glm::vec2 offset = scale + 2.0f * (sceneLo - lo) / size - 1.0f;
    return glm::vec4(scale, offset);
}

// Past the driver's layer count allocation fails with an error that names no cause, so the
// scene is refused first with the limit and the way around it.
void checkLayerLimits(const Scene& scene) {
    GLint maxLayers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    checkShadowLayers(scene.lights, maxLayers > 0 ? maxLayers : kMinArrayTextureLayers, "render with --no-shadows");
}

}  // namespace

std::vector<ProgramDesc> ShadowPass::programs() { return {{"shadow", {"scene.vert", "shadow.frag"}, {}}}; }

ShadowPass::ShadowPass(const GpuScene& scene, const RenderSettings& settings, bool lit, gl::MemoryLedger& ledger)
    : scene_(scene), ledger_(ledger), mapSize_(settings.shadowMapSize), cubeSize_(settings.shadowCubeSize),
      shadows_(settings.shadows && lit) {
    layoutLights();
    fbo_ = gl::createFramebuffer();
    glNamedFramebufferDrawBuffer(fbo_.id(), GL_NONE);
    program_ = buildProgram(programs()[0]);
}

void ShadowPass::invalidate(Changes changes) {
    if (changes & ChangeLights) layoutLights();  // lights moved, appeared or went: new views and maps
    if (changes & ChangeCamera) fitPending_ = !cameraMaps_.empty();
    if (changes & (ChangeLights | ChangeGeometry | ChangeMaterials)) valid_ = false;
}

void ShadowPass::layoutLights() {
    const Scene& cpu = scene_.cpu;
    views_.clear();
    cameraMaps_.clear();
    const Aabb bounds = cpu.bounds.empty() ? Aabb{glm::vec3(-1), glm::vec3(1)} : cpu.bounds;
    const glm::vec3 center = bounds.center();
    const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-30f);
    int layers = 0, cubes = 0;
    lights_ = makeGpuLights(cpu);
    const bool castsShadow = shadows_ && !cpu.draws.empty();
    if (castsShadow) checkLayerLimits(cpu);
    for (size_t i = 0; i < cpu.lights.size() && castsShadow; ++i) {
        const Light& l = cpu.lights[i];
        GpuLight& g = lights_[i];
        const glm::vec3 dir = glm::vec3(g.directionRange);
        if (l.type == LightType::Directional) {
            // Orthographic box around the scene bounds, as seen along the light.
            glm::mat4 view = glm::lookAt(center - dir * radius * 2.0f, center, anyPerpendicularUp(dir));
            glm::vec3 lo(1e30f), hi(-1e30f);
            for (const glm::vec3& c : corners(bounds)) {
                glm::vec3 v = glm::vec3(view * glm::vec4(c, 1.0f));
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
            const float pad = radius * 0.01f;
            lo -= pad;
            hi += pad;
            glm::mat4 proj = glm::ortho(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z);
            g.shadowMatrix = proj * view;
            g.cone.z = float(layers);
            g.shadowParams = glm::vec4(std::max(hi.x - lo.x, hi.y - lo.y) / mapSize_, 0.0f, 0.0f, 0.0f);
            views_.push_back({g.shadowMatrix, layers++, false});
            cameraMaps_.push_back({i, layers, view, glm::vec2(lo), glm::vec2(hi), -hi.z, -lo.z, 2.0f * radius});
            layers += kDirectionalShadowLayers - 1;
            continue;
        }
        float farthest = 0.0f;
        for (const glm::vec3& c : corners(bounds)) farthest = std::max(farthest, glm::length(c - l.position));
        const float zfar = std::max(farthest * 1.01f, radius * 1e-3f);
        const float znear = std::min(shadowNear(radius), zfar * 0.5f);
        if (l.type == LightType::Spot) {
            const float fov = std::min(2.0f * l.outerConeAngle + 0.05f, glm::radians(170.0f));
            glm::mat4 view = glm::lookAt(l.position, l.position + dir, anyPerpendicularUp(dir));
            g.shadowMatrix = glm::perspective(fov, 1.0f, znear, zfar) * view;
            g.cone.z = float(layers);
            g.shadowParams = glm::vec4(0.0f, 2.0f * std::tan(0.5f * fov) / mapSize_, znear, zfar);
            views_.push_back({g.shadowMatrix, layers++, false});
        } else {
            // Cube faces in GL's order (+X -X +Y -Y +Z -Z) with the conventional up vectors.
            static const glm::vec3 targets[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
            static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
            const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, znear, zfar);
            for (int f = 0; f < 6; ++f)
                views_.push_back({proj * glm::lookAt(l.position, l.position + targets[f], ups[f]), cubes * 6 + f, true});
            g.cone.z = float(cubes++);
            g.shadowParams = glm::vec4(0.0f, 2.0f / cubeSize_, znear, zfar);
        }
    }

    const gl::MemoryScope scope{&ledger_, name()};
    std::vector<GpuLight> padded = lights_;  // backs the lighting pass's uniform block (lights.h)
    padded.resize(std::max(padded.size(), size_t(kUniformBlockLights)));
    lightBuffer_ = gl::createStorageBuffer(scope, int64_t(padded.size() * sizeof(GpuLight)), padded.data(),
                                           GL_DYNAMIC_STORAGE_BIT);  // a camera map's fit (fitCameraMaps)
    // Only what the scene needs; a 1-texel placeholder keeps the lighting pass's samplers valid.
    maps_ = layers ? gl::createTexture2DArray(scope, GL_DEPTH_COMPONENT32F, mapSize_, mapSize_, layers)
                   : gl::createTexture2DArray(scope, GL_DEPTH_COMPONENT32F, 1, 1, 1);
    cubes_ = cubes ? gl::createTextureCubeArray(scope, GL_DEPTH_COMPONENT32F, cubeSize_, cubes)
                   : gl::createTextureCubeArray(scope, GL_DEPTH_COMPONENT32F, 1, 1);
    // The lookups read the cube faces as 2D layers (shadows.glsl): sampling the cube map array
    // itself cost the lighting pass more on llvmpipe for the same texels.
    cubeFaces_ = gl::createTextureView(cubes_, GL_TEXTURE_2D_ARRAY);
    for (const gl::Texture* t : {&maps_, &cubeFaces_}) {
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t->id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(t->id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    if (!layers || !cubes) {  // placeholders read as "lit"
        const float one = 1.0f;
        if (!layers) glClearTexImage(maps_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
        if (!cubes) glClearTexImage(cubes_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
    }
    valid_ = false;
}

void ShadowPass::fitCameraMaps(const CameraMatrices& camera, bool all, std::vector<View>& render) {
    for (const CameraMap& m : cameraMaps_) {
        GpuLight& g = lights_[m.light];
        glm::vec2 lo, hi;
        viewBox(camera, m.lightView, kCameraMapReach * m.sceneDiameter, lo, hi);
        lo = glm::max(lo, m.lo);
        hi = glm::min(hi, m.hi);
        const float sceneEdge = std::max(m.hi.x - m.lo.x, m.hi.y - m.lo.y);
        const float need = std::max(hi.x - lo.x, hi.y - lo.y);
        // Quarter octaves the view's box is below the scene's edge (none where it is empty).
        const int quarters = need > 0.0f ? int(std::floor(-4.0 * std::log2(double(need) / double(sceneEdge)))) : 0;
        glm::vec4 fit(0.0f);
        glm::mat4 viewProj(1.0f);
        if (quarters >= kCameraMapMinQuarterOctaves) {
            const float size = sceneEdge * std::exp2(-0.25f * float(std::min(quarters, 64)));
            const float texel = size / float(mapSize_);
            // On the grid of its own texels from the scene box's corner: a move within a texel
            // renders nothing again.
            const glm::vec2 corner = m.lo + glm::floor((0.5f * (lo + hi - size) - m.lo) / texel) * texel;
            fit = viewCascade(m.lo, m.hi, corner, size);
            viewProj = glm::ortho(corner.x, corner.x + size, corner.y, corner.y + size, m.zNear, m.zFar) * m.lightView;
        }
        if (fit == g.viewCascade && !all) continue;
        g.viewCascade = fit;
        glNamedBufferSubData(lightBuffer_.id(), GLintptr(m.light * sizeof(GpuLight)), GLsizeiptr(sizeof(GpuLight)), &g);
        if (fit.x > 0.0f) render.push_back({viewProj, m.layer, false});
    }
}

void ShadowPass::execute(Frame& frame) {
    frame.put(resource::kLights, lightBuffer_);
    frame.put(resource::kShadowMaps, maps_);
    frame.put(resource::kShadowCubes, cubeFaces_);
    std::vector<View> render = valid_ ? std::vector<View>{} : views_;
    fitCameraMaps(frame.camera, !valid_, render);
    valid_ = true;
    fitPending_ = false;
    reused_ = render.empty();
    if (!reused_) renderViews(render);
}

void ShadowPass::renderViews(const std::vector<View>& views) {
    const GpuScene& scene = scene_;
    glUseProgram(program_.id());
    glBindVertexArray(scene.vao.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // single-sided walls still block light
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 2.0f);  // slope-scaled bias: more offset where depth changes fast
    for (const View& v : views) {
        const gl::Texture& target = v.cube ? cubes_ : maps_;
        glNamedFramebufferTextureLayer(fbo_.id(), GL_DEPTH_ATTACHMENT, target.id(), 0, v.layer);
        gl::checkFramebuffer(fbo_.id(), "shadow map");
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
        glViewport(0, 0, target.width, target.height);
        glClear(GL_DEPTH_BUFFER_BIT);
        glProgramUniformMatrix4fv(program_.id(), U_VIEW_PROJ, 1, GL_FALSE, &v.viewProj[0][0]);
        for (const GpuDraw& d : scene.draws) drawWithMaterial(scene, program_.id(), d);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace gis
