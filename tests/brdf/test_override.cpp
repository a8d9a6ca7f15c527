// A material's BRDF override travels through the G-buffer to the lighting pass: two white floor
// tiles under one directional light, one forced to Lambert wrap, the other following the render's
// --diffuse; their radiance is checked against the closed forms.
#include "render_test_util.h"

namespace gis::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kRoughness = 0.6f;  // exact in the RGBA8 G-buffer (153/255)
constexpr float kIrradiance = 2.0f;

Scene twoTiles() {
    Scene s;
    s.name = "two tiles";
    Material wrap = lambert(glm::vec3(1.0f));
    wrap.roughnessFactor = kRoughness;
    wrap.diffuseModel = int(DiffuseModel::LambertWrap);
    wrap.specularModel = int(SpecularModel::None);
    Material global = lambert(glm::vec3(1.0f));
    global.roughnessFactor = kRoughness;
    s.materials = {wrap, global};
    addQuad(s, glm::vec3(-1.2f, 0, 0), glm::vec3(0, 1, 0), 2.0f, 0);
    addQuad(s, glm::vec3(1.2f, 0, 0), glm::vec3(0, 1, 0), 2.0f, 1);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(std::sqrt(3.0f), -1.0f, 0.0f));  // N.L = 0.5 on the floor
    sun.intensity = kIrradiance;
    s.lights.push_back(sun);
    s.cameras.push_back(lookAtCamera(glm::vec3(0, 4, 4), glm::vec3(0)));
    finalizeScene(s);
    return s;
}

RenderSettings settings(DiffuseModel diffuse) {
    RenderSettings r;
    r.width = r.height = 96;
    r.ambient = glm::vec3(0.0f);
    r.shadows = false;
    r.diffuse = diffuse;
    r.specular = SpecularModel::None;
    return r;
}

double smoothStep(double lo, double hi, double x) {
    const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

TEST(BrdfOverride, MaterialOverrideWinsAndTheRestFollowTheRenderSetting) {
    const Scene s = twoTiles();
    const double w = kRoughness, cosL = 0.5;
    const double wrap = kIrradiance * (cosL + w) / ((1.0 + w) * (1.0 + w) * kPi);
    const struct {
        DiffuseModel global;
        double expected;  // the tile without an override
    } cases[] = {{DiffuseModel::Lambert, kIrradiance * cosL / kPi},
                 {DiffuseModel::Toon, kIrradiance * smoothStep(-w, w, cosL) / kPi}};
    for (const auto& c : cases) {
        const RenderSettings r = settings(c.global);
        const ImageF img = renderHdr(s, r);
        const glm::ivec2 a = projectToPixel(s, r, glm::vec3(-1.2f, 0, 0)), b = projectToPixel(s, r, glm::vec3(1.2f, 0, 0));
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(meanAround(img, a.x, a.y, 2, ch), wrap, 1e-3 * wrap) << "overridden tile";
            EXPECT_NEAR(meanAround(img, b.x, b.y, 2, ch), c.expected, 1e-3 * c.expected) << "tile that follows --diffuse";
        }
    }
}

TEST(BrdfOverride, OutOfRangeModelIsAnError) {
    Scene s = twoTiles();
    s.materials[0].diffuseModel = kDiffuseModelCount;
    context();
    EXPECT_THROW(Renderer(s, settings(DiffuseModel::Lambert)), Error);
    s.materials[0].diffuseModel = -1;
    s.materials[0].specularModel = -2;
    EXPECT_THROW(Renderer(s, settings(DiffuseModel::Lambert)), Error);
}

}  // namespace
}  // namespace gis::test
