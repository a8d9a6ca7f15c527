#include "vct_test_util.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "render_test_util.h"
#include "tonemap.h"
#include "voxel_test_util.h"

namespace gis::test {

void setVct(RenderSettings& s, const std::string& key, const std::string& text) { setParam(s, "vct." + key, text); }

const VctPass& vctPassOf(const Renderer& r) {
    for (const auto& p : r.passes())
        if (auto* v = dynamic_cast<const VctPass*>(p.get())) return *v;
    throw Error("internal: no VCT pass");
}

VctImages renderVct(const Scene& scene, RenderSettings settings, int frames) {
    context();
    settings.gi = "vct";
    settings.hdr32 = true;
    Renderer renderer(scene, settings);
    VctImages out;
    const VctPass* pass = &vctPassOf(renderer);
    for (int f = 0; f < std::max(frames, 1); ++f) {
        renderer.renderFrame();
        if (f == 1) out.cachedSecondFrame = pass->voxelsReusedLastFrame();
    }
    for (const PassTiming& t : renderer.timings(0))
        if (t.step && t.pass.rfind("vct/", 0) == 0) out.stepMs[t.pass.substr(4)] = t.firstMs;
    const int w = settings.width, h = settings.height;
    out.frame = renderer.readHdr();
    out.diffuse = readTextureFloat(renderer.frameTexture("indirect.diffuse"), w, h);
    out.specular = readTextureFloat(renderer.frameTexture("indirect.specular"), w, h);
    out.resolution = pass->rebuildSettings().resolution;
    out.radiance = readVoxelsRgba16f(pass->volume().radiance().radiance());
    out.albedo = readVoxelsRgba8(pass->volume().grid().albedo);
    out.normal = readVoxelsRgba8(pass->volume().grid().normal);
    // The base colour target is sRGB8: read back, its values are the encoded ones.
    const ImageF base = readTextureFloat(renderer.frameTexture("gbuffer.baseColor"), w, h);
    const ImageF material = readTextureFloat(renderer.frameTexture("gbuffer.material"), w, h);
    out.indirect = out.diffuse;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                out.indirect.at(x, y)[c] =
                    srgbToLinear(base.at(x, y)[c]) * (1.0f - material.at(x, y)[0]) * out.diffuse.at(x, y)[c];
    return out;
}

// A lambertian quad 1 m in front of a wall, an emitter on the quad's back: the wall's indirect
// light is strong where the emitter faces it, the quad's front sees nothing but black sky. Any of
// the wall's light on the quad's front came across the 1 m depth step.
Scene depthStepScene() {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.8f)));
    Material emitter = lambert(glm::vec3(0.0f));
    emitter.emissive = glm::vec3(4.0f);
    s.materials.push_back(emitter);
    addQuad(s, {0, 0, -1}, {0, 0, 1}, 4.0f, 0);     // the wall
    addQuad(s, {0, 0, 0}, {0, 0, 1}, 1.0f, 0);      // the quad's front, facing the camera
    addQuad(s, {0, 0, -0.3f}, {0, 0, -1}, 1.0f, 1); // the emitter, facing the wall, hidden by the quad
    s.cameras.push_back(lookAtCamera({0, 0, 3}, {0, 0, 0}));
    finalizeScene(s);
    return s;
}

}  // namespace gis::test
