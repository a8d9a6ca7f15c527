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
    if (changes & (ChangeLights | ChangeGeometry | ChangeMaterials)) valid_ = false;
}

void ShadowPass::layoutLights() {
    const Scene& cpu = scene_.cpu;
    views_.clear();
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
            glm::mat4 proj = glm::ortho(lo.x - pad, hi.x + pad, lo.y - pad, hi.y + pad, -hi.z - pad, -lo.z + pad);
            g.shadowMatrix = proj * view;
            g.cone.z = float(layers);
            g.shadowParams = glm::vec4(std::max(hi.x - lo.x, hi.y - lo.y) / mapSize_, 0.0f, 0.0f, 0.0f);
            views_.push_back({g.shadowMatrix, layers++, false});
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
    lightBuffer_ = gl::createStorageBuffer(scope, int64_t(padded.size() * sizeof(GpuLight)), padded.data());
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

void ShadowPass::execute(Frame& frame) {
    frame.put(resource::kLights, lightBuffer_);
    frame.put(resource::kShadowMaps, maps_);
    frame.put(resource::kShadowCubes, cubeFaces_);
    reused_ = valid_;
    if (valid_) return;
    const GpuScene& scene = frame.scene;
    glUseProgram(program_.id());
    glBindVertexArray(scene.vao.id());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // single-sided walls still block light
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 2.0f);  // slope-scaled bias: more offset where depth changes fast
    for (const View& v : views_) {
        const gl::Texture& target = v.cube ? cubes_ : maps_;
        glNamedFramebufferTextureLayer(fbo_.id(), GL_DEPTH_ATTACHMENT, target.id(), 0, v.layer);
        gl::checkFramebuffer(fbo_.id(), "shadow map");
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
        glViewport(0, 0, target.width, target.height);
        glClear(GL_DEPTH_BUFFER_BIT);
        glProgramUniformMatrix4fv(program_.id(), U_VIEW_PROJ, 1, GL_FALSE, &v.viewProj[0][0]);
        for (const GpuDraw& d : scene.draws) {
            drawWithMaterial(scene, program_.id(), d);
        }
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    valid_ = true;
}

}  // namespace gis
