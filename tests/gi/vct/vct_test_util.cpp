#include "vct_test_util.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "passes/gbuffer_pass.h"
#include "passes/shadow_pass.h"
#include "render_test_util.h"
#include "voxel_test_util.h"

namespace gis::test {

namespace {
double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}
}  // namespace

VctImages renderVct(const Scene& scene, const RenderSettings& settingsIn, const VctSettings& vct, int frames) {
    context();
    RenderSettings settings = settingsIn;
    gl::MemoryLedger ledger;
    GpuScene gpu(scene, ledger);
    ShadowPass shadows(gpu, settings, ledger);
    GBufferPass gbuffer(settings.width, settings.height, ledger);
    VctPass pass(gpu, vct, settings.width, settings.height, ledger);
    const CameraMatrices camera = cameraMatrices(scene, settings.camera, float(settings.width) / float(settings.height));
    VctImages out;
    Frame frame{settings, gpu, camera, {}, {}, 0};
    for (int f = 0; f < std::max(frames, 1); ++f) {
        frame.index = uint64_t(f);
        shadows.execute(frame);
        gbuffer.execute(frame);
        pass.execute(frame);
        if (f == 1) out.cachedSecondFrame = pass.reusedLastFrame();
    }
    glFinish();
    for (int s = 0; s < VctPass::StepCount; ++s) {
        pass.stepTimer(s).collect(true);
        out.stepMs[s] = median(pass.stepTimer(s).samples);
    }
    out.resolution = vct.resolution;
    out.radiance = readVoxelsRgba16f(pass.voxelRadiance().radiance());
    out.albedo = readVoxelsRgba8(pass.voxelizer().grid().albedo);
    out.normal = readVoxelsRgba8(pass.voxelizer().grid().normal);
    const int w = settings.width, h = settings.height;
    out.diffuse = readTextureFloat(frame.texture("indirect.diffuse"), w, h);
    out.specular = readTextureFloat(frame.texture("indirect.specular"), w, h);
    out.ao = readTextureFloat(frame.texture("ao"), w, h);
    for (const char* view : {"vct.voxels", "vct.slice"})
        if (frame.textures.count(view)) out.debug = readTextureFloat(frame.textures.at(view), w, h);
    const ImageF base = readTextureFloat(frame.texture("gbuffer.baseColor"), w, h);
    const ImageF material = readTextureFloat(frame.texture("gbuffer.material"), w, h);
    out.indirect = out.diffuse;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                out.indirect.at(x, y)[c] = base.at(x, y)[c] * (1.0f - material.at(x, y)[0]) * out.diffuse.at(x, y)[c];
    return out;
}

Scene scaledScene(const Scene& in, float scale) {
    Scene s = in;
    const glm::mat4 m = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
    for (DrawItem& d : s.draws) d.world = m * d.world;
    for (Camera& c : s.cameras) {
        c.cameraToWorld[3] = glm::vec4(glm::vec3(c.cameraToWorld[3]) * scale, 1.0f);
        c.znear *= scale;
        c.zfar *= scale;
    }
    for (Light& l : s.lights) {
        l.position *= scale;
        if (l.type != LightType::Directional) l.intensity *= scale * scale;
        l.range *= scale;
    }
    finalizeScene(s);
    return s;
}

ImageF add(const ImageF& a, const ImageF& b) {
    ImageF r = a;
    for (size_t i = 0; i < r.rgba.size(); ++i)
        if (i % 4 != 3) r.rgba[i] += b.rgba[i];
    return r;
}

ImageF subtract(const ImageF& a, const ImageF& b) {
    ImageF r = a;
    for (size_t i = 0; i < r.rgba.size(); ++i)
        if (i % 4 != 3) r.rgba[i] -= b.rgba[i];
    return r;
}

}  // namespace gis::test
