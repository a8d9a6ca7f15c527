// Voxel cone tracing against the path tracer on the Cornell box: the indirect term's energy per
// wall, colour bleeding, convergence with resolution, caching on camera moves, extremes, and the
// measured PSNR/timing table of the README (printed, "VCT-TABLE" lines).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "metrics.h"
#include "tonemap.h"
#include "gi/method.h"
#include "gi/vct/vct_settings.h"
#include "render_test_util.h"
#include "vct_test_util.h"
#include "voxel_test_util.h"

namespace gis::test {
namespace {

constexpr int kSize = 128;
constexpr int kSpp = 64;

constexpr ReferenceSpec kSpec{kSize, kSpp, false};

// The bounces vct sums at its defaults: the path tracer it is held against traces as many.
const int kBounces = VctSettings{}.bounces;

// Issue 11's checks hold one cone gather against the path tracer's one bounce: a second gather
// compounds the cones' errors (the README's energy table has both).
RenderSettings oneBounce(RenderSettings r) {
    if (!std::getenv("VCT_BOUNCES")) setVct(r, "bounces", "1");
    return r;
}

// The frame VCT and its references are rendered at: direct light only (the indirect term is VCT's).
RenderSettings baseSettings(const std::string& gi) { return referenceSettings(gi, kSpec); }

// The Cornell references at this file's size and sample count (tests/gi/gi_reference.h).
const GiReference& reference(const std::string& name) { return giReference(name, kSpec); }

// RMSE of the indirect term over the interior pixels of the room.
double indirectRmse(const ImageF& test, const ImageF& ref, const GiReference& r) {
    return interiorRmse(test, ref, r.interior());
}

// --gi vct at the defaults (64^3), VCT_RES / VCT_BOUNCES / VCT_BACKFACES / VCT_CONES overriding for
// measurements by hand.
RenderSettings vctSettings() {
    RenderSettings r = baseSettings("vct");
    if (const char* e = std::getenv("VCT_RES")) setVct(r, "resolution", e);
    if (const char* e = std::getenv("VCT_BOUNCES")) setVct(r, "bounces", e);
    if (const char* e = std::getenv("VCT_BACKFACES")) setVct(r, "backfaces", e);
    if (const char* e = std::getenv("VCT_CONES")) setVct(r, "cones", e);
    return r;
}

TEST(Vct, CornellIndirectEnergyPerWallAgainstPathTracer) {
    const GiReference& ref = reference("cornell");
    const ImageF pt = ref.ptIndirect();
    const VctImages v = renderVct(makeBuiltinScene("cornell"), oneBounce(vctSettings()));
    // The indirect term as the issue defines it: the VCT frame (lighting pass, contract) minus the
    // `--gi none` frame without ambient, i.e. direct light alone.
    const ImageF indirect = subtract(v.frame, ref.direct());
    ASSERT_TRUE(allFinite(indirect));
    if (const char* dir = std::getenv("VCT_DUMP")) {  // for looking at the two side by side
        DisplaySettings d;
        d.exposureEV = 3.0f;
        writePng(std::string(dir) + "/vct_indirect.png", toLdrImage(indirect, d));
        writePng(std::string(dir) + "/pt_indirect.png", toLdrImage(pt, d));
    }
    // Issue 11: 80-120% of the path tracer's one-bounce indirect on every wall and the floor.
    int withinIssueBand = 0;
    for (const auto& [name, region] : kCornellFaces) {
        const double ours = ref.regionMean(indirect, region), theirs = ref.regionMean(pt, region);
        const double ratio = ours / theirs;
        if (measuring("vct")) {
            const double multi = ref.regionMean(subtract(ref.ptFull(), ref.ptDirect()), region);
            std::printf("VCT-TABLE energy cornell %-10s vs 16-bounce indirect %.5f: %.0f%%\n", name.c_str(), multi,
                        100.0 * ours / multi);
        }
        const bool inBand = ratio >= 0.8 && ratio <= 1.2;
        std::printf("VCT-TABLE energy cornell %-10s vct %.5f pathtrace %.5f ratio %.0f%% %s\n", name.c_str(), ours,
                    theirs, 100.0 * ratio, inBand ? "(in 80-120%)" : "(OUTSIDE 80-120%)");
        if (name == "ceiling") continue;  // the issue asks for the walls and the floor
        withinIssueBand += inBand;
        EXPECT_GE(ratio, 0.8) << name;
        EXPECT_LE(ratio, 1.2) << name;
    }
    std::printf("VCT-TABLE energy: %d of 4 (walls, floor) within the issue's 80-120%%\n", withinIssueBand);
    std::printf("VCT-TABLE psnr cornell one bounce: %.2f dB sRGB vs 1-bounce path tracer\n",
                compareImages(v.frame, ref.ptOneBounce()).psnrSrgb);
}

TEST(Vct, InjectedRadianceMatchesDirectLightPerWall) {
    const GiReference& ref = reference("cornell");
    // With one bounce level 0 holds the injected light alone.
    const VctImages v = renderVct(makeBuiltinScene("cornell"), oneBounce(vctSettings()));
    struct Wall { const char* name; int region; glm::vec3 albedo; glm::vec3 normal; };
    const Wall walls[] = {{"red wall", 8, {0.63f, 0.065f, 0.05f}, {1, 0, 0}},
                          {"green wall", 16, {0.14f, 0.45f, 0.091f}, {-1, 0, 0}},
                          {"back", 2, {0.73f, 0.73f, 0.73f}, {0, 0, 1}},
                          {"floor", 0, {0.73f, 0.73f, 0.73f}, {0, 1, 0}},
                          {"ceiling", 1, {0.73f, 0.73f, 0.73f}, {0, -1, 0}}};
    const int res = v.resolution;
    for (const Wall& w : walls) {
        // The wall's voxels: its colour and orientation, and (so block faces of the same colour
        // and orientation do not count) within two layers of the outermost such voxels.
        std::vector<std::pair<float, double>> found;  // depth along the normal, radiance
        for (size_t i = 0; i < v.albedo.size() / 4; ++i) {
            const glm::vec3 a = glm::vec3(v.albedo[i * 4], v.albedo[i * 4 + 1], v.albedo[i * 4 + 2]) / 255.0f;
            const glm::vec3 nrm = glm::vec3(v.normal[i * 4], v.normal[i * 4 + 1], v.normal[i * 4 + 2]) / 127.5f - 1.0f;
            if (!v.albedo[i * 4 + 3] || glm::length(a - w.albedo) > 0.02f || glm::dot(nrm, w.normal) < 0.95f) continue;
            const glm::vec3 voxel(float(i % res), float(i / res % res), float(i / res / res));
            found.push_back({glm::dot(voxel, w.normal), (v.radiance[i * 4] + v.radiance[i * 4 + 1] + v.radiance[i * 4 + 2]) / 3.0});
        }
        float outermost = 1e30f;
        for (const auto& f : found) outermost = std::min(outermost, f.first);
        double sum = 0.0;
        int n = 0;
        for (const auto& f : found)
            if (f.first <= outermost + 2.0f) {
                sum += f.second;
                ++n;
            }
        const double voxels = n ? sum / n : 0.0, raster = ref.regionMean(ref.direct(), w.region);
        std::printf("VCT-TABLE injection %-10s voxels %.4f (%d) rasterizer direct %.4f ratio %.0f%%\n", w.name, voxels, n,
                    raster, 100.0 * voxels / raster);
        // The back wall's light falls off steeply (1/d^3 from the lamp 1 m in front of it) and the
        // camera sees its bright middle, the voxels all of it: compared loosely.
        const double tolerance = w.region == 2 ? 0.4 : 0.25;
        EXPECT_GT(voxels, (1.0 - tolerance) * raster) << w.name;
        EXPECT_LT(voxels, (1.0 + tolerance) * raster) << w.name;
    }
}

TEST(Vct, ColourBleedsFromTheWallsOntoTheFloor) {
    const GiReference& ref = reference("cornell");
    const VctImages v = renderVct(makeBuiltinScene("cornell"), vctSettings());
    const GiReference::FloorBleeding b = ref.floorBleeding(v.indirect);
    std::printf("VCT-TABLE bleeding floor red/green of the indirect term: near red wall %.3f, near green wall %.3f\n",
                b.nearRed, b.nearGreen);
    EXPECT_GT(b.nearRed, b.nearGreen);
}

// Issue 11: the error against the path tracer falls from 32^3 to 64^3. It does on a scene with
// detail a 32^3 grid cannot hold: the atrium's columns, arches and banners (cells of 0.7 m at
// 32^3, 0.35 m at 64^3). The frame (direct light plus one VCT bounce) against the path tracer
// with one bounce, as RMSE of the pixels and of 8x8 block means (the reference's noise averaged
// down): both must fall by at least 5%. Without sky rays, so the cones take the sky from the voxels
// too and resolution is the one thing that changes (the sky rays, which need no voxels, are
// measured by Vct.SkyRays*).
TEST(Vct, ErrorFallsWithResolutionOnTheAtrium) {
    const Scene scene = makeBuiltinScene("atrium");
    RenderSettings pt;
    pt.width = pt.height = kSize;
    pt.gi = "pathtrace";
    setParam(pt, "pathtrace.spp", std::to_string(kSpp));
    setParam(pt, "pathtrace.bounces", "1");
    const ImageF reference = renderHdr(scene, pt);
    double pixels[2], blocks[2];
    int i = 0;
    for (int res : {32, 64}) {
        RenderSettings s;
        s.width = s.height = kSize;
        setVct(s, "resolution", std::to_string(res));
        setVct(s, "sky-rays", "0");
        const ImageF frame = renderVct(scene, oneBounce(s)).frame;
        ASSERT_TRUE(allFinite(frame));
        pixels[i] = rmse(frame, reference);
        blocks[i] = rmse(downsample(frame, 8), downsample(reference, 8));
        std::printf("VCT-TABLE convergence atrium %d^3: RMSE %.5f, 8x8-block RMSE %.5f, PSNR %.2f dB sRGB\n", res, pixels[i],
                    blocks[i], compareImages(frame, reference).psnrSrgb);
        ++i;
    }
    EXPECT_LT(pixels[1], 0.95 * pixels[0]);
    EXPECT_LT(blocks[1], 0.95 * blocks[0]);
}

// The atrium under its sun alone (no sky), one bounce: the sky rays' first bounce over the image
// is the path tracer's within 15%. A ray's hit read its voxel's light, lit as one surface facing
// the voxel's mean normal: the shaded wall under a sunlit roof's edge and a column's shaded side
// showed sunlight, and the first bounce came out at 1.30 of the path tracer's (README, "A ray's hit
// lights itself with the punctual lights"); with each hit lit by the lights and their shadow maps,
// about 1.1.
TEST(Vct, SunlitAtriumsFirstBounceThroughRaysIsThePathTracers) {
    const Scene scene = makeBuiltinScene("atrium");
    RenderSettings pt = baseSettings("pathtrace");
    pt.width = pt.height = 64;
    pt.background = glm::vec3(0.0f);
    setParam(pt, "pathtrace.bounces", "0");
    const ImageF direct = renderHdr(scene, pt);
    setParam(pt, "pathtrace.bounces", "1");
    const ImageF bounced = renderHdr(scene, pt);
    RenderSettings s = oneBounce(vctSettings());
    s.width = s.height = 64;
    s.background = glm::vec3(0.0f);
    const ImageF frame = renderVct(scene, s).frame;
    ASSERT_TRUE(allFinite(frame));
    const std::vector<bool> none(64 * 64, false);
    const double ours = meanRgbExcept(frame, none) - meanRgbExcept(direct, none);
    const double theirs = meanRgbExcept(bounced, none) - meanRgbExcept(direct, none);
    std::printf("VCT-TABLE atrium sun alone, first bounce over the path tracer's: %.3f\n", ours / theirs);
    EXPECT_GT(ours, 0.85 * theirs);
    EXPECT_LT(ours, 1.15 * theirs);
}

// On the Cornell box the same comparison does not fall (measured, README): the room is five
// planes and two blocks that 32^3 already holds, and the error left is the cones' (the ceiling
// lights itself with its own lamp hot spot, see the README; more so at 64^3, where the margin of
// empty voxels around the room is thinner in the world). The back wall rises the same way, less:
// it faces the open front, where (our reading) the cones that leave the volume take in the walls'
// edges in the boundary's coarse texels. This prints the per-face lines and the indirect RMSE at both sizes and
// checks what does hold: on the side walls and the floor the mean comes closer to the path
// tracer's from 32^3 to 64^3 (or moves by at most 2 points away).
TEST(Vct, CornellErrorAgainstResolutionIsMeasured) {
    const GiReference& ref = reference("cornell");
    const ImageF pt = ref.ptIndirect();
    std::map<std::string, double> ratio[2];
    int i = 0;
    for (int res : {32, 64}) {
        RenderSettings s = oneBounce(vctSettings());
        setVct(s, "resolution", std::to_string(res));
        const VctImages v = renderVct(makeBuiltinScene("cornell"), s);
        for (const auto& [name, region] : kCornellFaces) {
            std::vector<bool> only = ref.interior();
            for (size_t p = 0; p < only.size(); ++p) only[p] = only[p] && ref.hits()[p].region == region;
            ratio[i][name] = ref.regionMean(v.indirect, region) / ref.regionMean(pt, region);
            std::printf("VCT-TABLE convergence cornell %d^3 %-10s mean %.0f%% of the path tracer, RMSE %.5f\n", res,
                        name.c_str(), 100.0 * ratio[i][name], interiorRmse(v.indirect, pt, only));
        }
        std::printf("VCT-TABLE convergence cornell %d^3 indirect RMSE %.5f, 8x8-block RMSE %.5f\n", res,
                    indirectRmse(v.indirect, pt, ref), blockRmse(v.indirect, pt, ref.interior(), 8));
        ++i;
    }
    for (const auto& [name, r] : ratio[0])
        if (name != "ceiling" && name != "back") {
            EXPECT_LE(std::abs(ratio[1].at(name) - 1.0), std::abs(r - 1.0) + 0.02) << name;
        }
}

// A camera move traces again (the pass is not settled) but keeps the voxels and their light.
TEST(Vct, CameraMoveReusesVoxels) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings s = vctSettings();
    s.gi = "vct";
    Renderer r(scene, s);
    const VctPass* pass = nullptr;
    size_t index = 0;
    for (size_t i = 0; i < r.passes().size(); ++i)
        if (auto* v = dynamic_cast<const VctPass*>(r.passes()[i].get())) pass = v, index = i;
    ASSERT_NE(pass, nullptr);
    r.renderFrame();
    EXPECT_FALSE(pass->voxelsReusedLastFrame());
    CameraMatrices c = r.camera();
    c.view = glm::translate(c.view, glm::vec3(0.05f, 0.0f, 0.0f));
    c.viewProj = c.proj * c.view;
    c.invViewProj = glm::inverse(c.viewProj);
    c.position = glm::vec3(glm::inverse(c.view)[3]);
    r.setCamera(c);
    r.renderFrame();
    EXPECT_FALSE(r.skippedLastFrame()[index]) << "a camera move must trace again";
    EXPECT_TRUE(pass->voxelsReusedLastFrame());
    EXPECT_EQ(pass->voxelizations(), 1);
    // Nor is the light relit: injection and the default's voxel-space bounces run with it.
    EXPECT_EQ(pass->injections(), 1);
}

// A light edit keeps the voxels (occupancy, albedo, normals) and injects the light again: the
// voxelizer ran once, the injection twice, and the injected radiance follows the new intensity.
TEST(Vct, LightEditReinjectsWithoutRevoxelizing) {
    context();
    RenderSettings s = vctSettings();
    setVct(s, "resolution", "32");
    s.gi = "vct";
    Scene scene = makeBuiltinScene("cornell");  // the renderer keeps a reference to it
    Renderer r(scene, s);
    const VctPass* pass = &vctPassOf(r);
    auto radianceSum = [&] {  // RGB of every voxel (alpha is occupancy, the same before and after)
        const std::vector<float> v = readVoxelsRgba16f(pass->volume().radiance().radiance());
        double sum = 0.0;
        for (size_t i = 0; i < v.size(); ++i) sum += i % 4 == 3 ? 0.0 : double(v[i]);
        return sum;
    };
    r.renderFrame();
    const double before = radianceSum();
    scene.lights[0].intensity *= 2.0f;
    r.lightsChanged();
    r.renderFrame();
    EXPECT_EQ(pass->voxelizations(), 1) << "a light edit re-voxelized the scene";
    EXPECT_EQ(pass->injections(), 2) << "a light edit did not re-inject";
    EXPECT_FALSE(pass->voxelsReusedLastFrame());
    EXPECT_NEAR(radianceSum() / before, 2.0, 0.02) << "the injected light did not follow the edit";
    r.invalidate(ChangeGeometry);
    r.renderFrame();
    EXPECT_EQ(pass->voxelizations(), 2);
    EXPECT_EQ(pass->injections(), 3);
}

// The bounces gather with the live cone settings: a change of vct.sky-rays (or the cones) gathers
// them again from the same injected light, and nothing else is redone.
TEST(Vct, ConeSettingsEditGathersTheBouncesAgain) {
    context();
    RenderSettings s = vctSettings();
    setVct(s, "resolution", "32");
    s.gi = "vct";
    const Scene scene = makeBuiltinScene("cornell");
    Renderer r(scene, s);
    const VctPass* pass = &vctPassOf(r);
    auto radiance = [&] { return readVoxelsRgba16f(pass->volume().radiance().radiance()); };
    r.renderFrame();
    const std::vector<float> withRays = radiance();
    r.renderFrame();
    EXPECT_EQ(pass->injections(), 1) << "a still frame relit the volume";
    RenderSettings live = s;
    setVct(live, "sky-rays", "0");
    r.setLiveSettings(live);
    r.renderFrame();
    EXPECT_EQ(pass->voxelizations(), 1);
    EXPECT_EQ(pass->injections(), 2) << "the bounces kept the rays they were gathered with";
    EXPECT_NE(radiance(), withRays) << "marching cones gathered the same bounces as rays";
}

TEST(Vct, EmitterLightsTheRoom) {
    // cornell-area has no punctual light: the rasterizer's direct term is the emitter itself, and
    // every bit of light on the walls comes from the emissive quad's voxels. (The path tracer
    // counts the quad's light on the walls as direct, so the full frames are compared.)
    const VctImages v = renderVct(makeBuiltinScene("cornell-area"), vctSettings());
    const GiReference& ref = reference("cornell-area");
    const ImageF& frame = v.frame;
    std::printf("VCT-TABLE psnr cornell-area default: %.2f dB sRGB vs 1-bounce path tracer\n",
                compareImages(frame, ref.ptOneBounce()).psnrSrgb);
    for (const auto& [name, region] : kCornellFaces) {
        const double ours = ref.regionMean(frame, region), one = ref.regionMean(ref.ptOneBounce(), region);
        std::printf("VCT-TABLE cornell-area %-10s vct frame %.4f, path tracer 1 bounce %.4f (%.0f%%)\n", name.c_str(),
                    ours, one, 100.0 * ours / one);
        if (name != "ceiling" && name != "back") {
            EXPECT_GT(ours, 0.25 * one) << name;
        }
    }
}

// builtin:leak at its thinnest wall (0.005 m, a tenth of a cell): any indirect light VCT puts in
// the dark room beyond what passes over the open tops leaked through the wall. Reported as
// dark-room mean / lit-room mean of the indirect term, for the knobs that change it (the default
// knobs' bound is the method contract's, tests/gi/test_method_contract.cpp).
TEST(Vct, ThinWallLeakIsMeasured) {
    const Scene s = makeBuiltinScene("leak?thickness=0.005");
    struct Knobs { bool anisotropic; float offset; const char* backfaces; };
    const Knobs knobs[] = {{false, 1.5f, "opaque"}, {false, 3.0f, "opaque"}, {true, 1.5f, "opaque"},
                           {true, 3.0f, "opaque"},  {true, 1.5f, "cull"}};
    for (const auto& [anisotropic, offset, backfaces] : knobs) {
        RenderSettings v = vctSettings();
        setVct(v, "anisotropic", anisotropic ? "true" : "false");
        setVct(v, "offset", std::to_string(offset));
        setVct(v, "backfaces", backfaces);
        const VctImages img = renderVct(s, v);
        ASSERT_TRUE(allFinite(img.indirect));
        double lit = 0.0;
        const double leak = darkOverLitRoom(img.indirect, &lit);
        std::printf("VCT-TABLE leak 64^3 anisotropic %s offset %.1f backfaces %s: dark room / lit room = %.4f\n",
                    anisotropic ? "on " : "off", offset, backfaces, leak);
        EXPECT_GT(lit, 0.0);
        EXPECT_LT(leak, 0.5);
    }
}

// Cones that leave the volume read the environment: a lone floor under a uniform sky of radiance
// L sees L in every direction, so indirect.diffuse (E / pi) should be L there. With
// vct.backfaces=cull it is (the directional mips leave out the floor's voxels for cones leaving it
// upwards). With the default (opaque) the floor's own voxels, which a cone's trilinear footprint
// reaches over part of its path despite the lift, absorb more than half of the sky: printed, not
// asserted (renderer/gi/vct/README.md, not done).
TEST(Vct, OpenFloorSeesTheSkyWithBackfacesCulled) {
    Scene s;
    s.materials.push_back(lambert(glm::vec3(0.5f)));
    addQuad(s, {0, 0, 0}, {0, 1, 0}, 4.0f, 0);
    s.cameras.push_back(lookAtCamera({0, 3, 3}, {0, 0, 0}, 40.0f));
    finalizeScene(s);
    // Every cone set's weights must add up to the sky's radiance once nothing is in the way.
    for (const char* backfaces : {"opaque", "cull"})
        for (const char* cones : {"six", "four", "many"}) {
            RenderSettings r = vctSettings();
            r.background = glm::vec3(0.2f, 0.4f, 0.8f);
            setVct(r, "backfaces", backfaces);
            setVct(r, "cones", cones);
            const VctImages v = renderVct(s, r);
            const float* centre = v.diffuse.at(kSize / 2, kSize / 2);
            std::printf("VCT-TABLE open floor under a (0.2, 0.4, 0.8) sky, backfaces %s, cones %s: indirect.diffuse "
                        "(%.3f, %.3f, %.3f), %.0f%%\n", backfaces, cones, centre[0], centre[1], centre[2], 100.0 * centre[2] / 0.8);
            if (std::string(backfaces) != "cull") continue;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], (*r.background)[c], 0.05 * (*r.background)[c]) << cones << c;
        }
}

// The cone tracer's energy balance apart from any light's shape: inside a closed box whose walls
// all emit radiance L (and reflect nothing), every surface sees L in every direction, so
// indirect.diffuse (E / pi) must be L on every wall, at the centre of a face as near its edges.
// (It cannot see self-occlusion: a cone that sees its own wall sees L there too.) What it does see
// is light escaping through coarse texels that straddle a wall and the volume's empty margin
// (VctPass's margin comment): 12% at 32^3, 4% at 64^3 by default.
TEST(Vct, ClosedEmissiveBoxIsAFurnace) {
    Scene s;
    Material glow = lambert(glm::vec3(0.0f));
    glow.emissive = glm::vec3(0.5f);
    s.materials.push_back(glow);
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f);
            n[axis] = -side;
            addQuad(s, -n, n, 2.0f, 0);
        }
    s.cameras.push_back(lookAtCamera({0.0f, 0.0f, 0.95f}, {0.0f, 0.0f, -1.0f}, 90.0f));
    finalizeScene(s);
    for (const char* backfaces : {"opaque", "cull"}) {
        RenderSettings r = vctSettings();
        setVct(r, "backfaces", backfaces);
        setParam(r, "emitters.mode", "gi");  // the emission carried by the volume is what is measured
        const VctImages v = renderVct(s, r);
        struct Spot { const char* name; int x, y; };
        const Spot spots[] = {{"back", kSize / 2, kSize / 2}, {"floor", kSize / 2, kSize * 15 / 16},
                              {"ceiling", kSize / 2, kSize / 16}, {"left", kSize / 16, kSize / 2},
                              {"back corner", kSize * 3 / 8, kSize * 5 / 8}};
        for (const Spot& p : spots) {
            const float e = v.diffuse.at(p.x, p.y)[0];
            std::printf("VCT-TABLE furnace backfaces %-6s %-12s indirect.diffuse %.3f of the walls' 0.5 (%.0f%%)\n",
                        backfaces, p.name, e, 200.0 * e);
            EXPECT_NEAR(e, 0.5f, 0.075f * 0.5f) << backfaces << " " << p.name;
        }
    }
}

// A closed room's walls are boxes: each has an outside that no light reaches, in the same coarse
// texels as its inside. Travelling outwards, a cone meets the outside first in the directional
// mips, so the room's own cones saw its walls as black (34% of their weight under a uniform light,
// README "Unlit outsides"). With vct.unlit-outsides=cull (the default) those voxels leave the
// volume, and the one-bounce indirect light of the point-lit room comes near the path tracer's.
TEST(Vct, UnlitOutsidesOfAClosedRoomLeaveTheVolume) {
    const Scene room = makeBuiltinScene("room");
    constexpr int kRoomSize = 64;
    RenderSettings pt = baseSettings("pathtrace");
    pt.width = pt.height = kRoomSize;
    setParam(pt, "pathtrace.spp", "128");
    setParam(pt, "pathtrace.bounces", "0");
    const double direct = meanRadiance(renderHdr(room, pt));
    setParam(pt, "pathtrace.bounces", std::to_string(kBounces));
    const double indirect = meanRadiance(renderHdr(room, pt)) - direct;
    // Marching cones (vct.sky-rays=0) see the outsides through the walls' coarse texels; rays stop
    // at the walls and see the room's insides alone, so with them keeping the outsides costs nothing.
    for (const char* rays : {"0", "1"}) {
        double ratio[2] = {};
        for (int keep = 0; keep < 2; ++keep) {
            RenderSettings r = vctSettings();
            r.width = r.height = kRoomSize;
            setVct(r, "unlit-outsides", keep ? "keep" : "cull");
            setVct(r, "sky-rays", rays);
            const VctImages v = renderVct(room, r);
            ASSERT_TRUE(allFinite(v.indirect));
            int culled = 0;
            for (size_t i = 0; i < v.albedo.size() / 4; ++i)
                culled += v.albedo[4 * i + 3] > 0 && v.radiance[4 * i + 3] == 0.0f;
            ratio[keep] = meanRadiance(v.indirect) / indirect;
            std::printf("VCT-TABLE room (point lamp), sky rays %s, unlit outsides %s: %d voxels left out, indirect %.4f, path "
                        "tracer's %d bounces %.4f (%.0f%%)\n", rays, keep ? "keep" : "cull", culled, meanRadiance(v.indirect),
                        kBounces, indirect, 100.0 * ratio[keep]);
            if (keep) EXPECT_EQ(culled, 0);
            else EXPECT_GT(culled, 1000) << "the room's outsides";
        }
        EXPECT_NEAR(ratio[0], 1.0, 0.2) << "sky rays " << rays;
        if (rays[0] == '0') EXPECT_LT(ratio[1], 0.8) << "what the outsides cost the marching cones when kept";
        else EXPECT_NEAR(ratio[1], 1.0, 0.2) << "kept outsides, seen by no ray";
    }
}

// In an open scene light reaches the air around everything: only shadowed pockets of air that the
// voxels close off (beside the blocks) lose their few surface voxels, and the light stays as it was.
TEST(Vct, UnlitOutsidesOfAnOpenSceneStay) {
    const Scene cornell = makeBuiltinScene("cornell");
    RenderSettings cull = vctSettings(), keep = vctSettings();
    cull.width = cull.height = keep.width = keep.height = 64;
    setVct(keep, "unlit-outsides", "keep");
    const VctImages culled = renderVct(cornell, cull), kept = renderVct(cornell, keep);
    int left = 0, surface = 0;
    for (size_t i = 0; i < culled.albedo.size() / 4; ++i) {
        surface += culled.albedo[4 * i + 3] > 0;
        left += culled.albedo[4 * i + 3] > 0 && culled.radiance[4 * i + 3] == 0.0f;
    }
    std::printf("VCT-TABLE cornell, unlit outsides cull: %d of %d surface voxels left out\n", left, surface);
    EXPECT_LT(left, surface / 200);
    double a = 0.0, b = 0.0;
    for (size_t i = 0; i < culled.indirect.rgba.size(); ++i) {
        a += culled.indirect.rgba[i];
        b += kept.indirect.rgba[i];
    }
    EXPECT_NEAR(a / b, 1.0, 0.01);
}

// A room with no opening in a sunlit building is unreached air too, but no outside: its walls'
// inner faces stay. At 128^3 (34 cm voxels) a 20 cm wall often splits across two voxels, one per
// face; culling the inner one opened the wall, and the room's cones saw the sunlit outer faces
// behind it: the closed room read 1.43x the corridor's light with `cull` against 0.25x with
// `keep`. Sun only, one gather (the sky and the bounces have leaks of their own).
TEST(Vct, UnlitOutsidesKeepAClosedRoomInASunlitBuildingClosed) {
    const Scene building = makeBuiltinScene("building");
    double leak[2] = {};
    for (int keep = 0; keep < 2; ++keep) {
        RenderSettings r;
        r.width = r.height = 32;
        r.background = glm::vec3(0.0f);
        setVct(r, "resolution", "128");
        setVct(r, "bounces", "1");
        setVct(r, "unlit-outsides", keep ? "keep" : "cull");
        double mean[2] = {};
        for (int dark = 0; dark < 2; ++dark) {
            r.camera = dark ? building.leakCameras.dark : building.leakCameras.lit;
            const VctImages v = renderVct(building, r);
            ASSERT_TRUE(allFinite(v.frame));
            mean[dark] = meanRadiance(v.frame);
        }
        leak[keep] = mean[1] / mean[0];
        std::printf("VCT-TABLE building at 128^3, sun only, unlit outsides %s: closed room over corridor %.3f\n",
                    keep ? "keep" : "cull", leak[keep]);
    }
    EXPECT_LT(leak[0], 1.05 * leak[1] + 0.01);
}

// A 4 m metal floor of `roughness` before a red emissive wall 2 m away, seen from 3 m in front.
Scene metalFloorBeforeALamp(float roughness) {
    Scene s;
    Material metal = lambert(glm::vec3(0.9f));
    metal.metallicFactor = 1.0f;
    metal.roughnessFactor = roughness;
    metal.specularFactor = 1.0f;
    s.materials.push_back(metal);
    Material lamp = lambert(glm::vec3(0.0f));
    lamp.emissive = glm::vec3(4.0f, 0.2f, 0.2f);
    s.materials.push_back(lamp);
    addQuad(s, {0, 0, 0}, {0, 1, 0}, 4.0f, 0);
    addQuad(s, {0, 1, -2}, {0, 0, 1}, 2.0f, 1);
    s.cameras.push_back(lookAtCamera({0, 1.0f, 3}, {0, 0, -1}, 40.0f));
    finalizeScene(s);
    return s;
}

// VCT at its defaults with the lamp's emission in the volume, where the specular cone sees it.
RenderSettings lampInTheVolume() {
    RenderSettings r = vctSettings();
    setParam(r, "emitters.mode", "gi");
    return r;
}

// The specular cone: a glossy metal floor in front of a red emissive wall reflects red, and a
// rough one reflects a wider, dimmer, still red image.
TEST(Vct, GlossyFloorReflectsAnEmitter) {
    const VctImages v = renderVct(metalFloorBeforeALamp(0.1f), lampInTheVolume());
    ASSERT_TRUE(allFinite(v.specular));
    double red = 0.0, green = 0.0;
    for (int y = kSize / 2; y < kSize; ++y)  // the floor: lower half of the image
        for (int x = 0; x < kSize; ++x) {
            red = std::max(red, double(v.specular.at(x, y)[0]));
            green = std::max(green, double(v.specular.at(x, y)[1]));
        }
    std::printf("VCT-TABLE glossy floor: brightest reflected red %.3f, green %.3f\n", red, green);
    EXPECT_GT(red, 0.5);
    EXPECT_GT(red, 5.0 * green);
}

// A mirror shows what lies far as it shows what lies near: vct.max-distance cuts the diffuse cones
// short (realtime's half-length ones), never the specular cone, which goes at least the volume's
// edge (realtime's mirror spheres in builtin:mirror had 0.44 of Cycles' light when it was cut too).
// A mirror floor before a red lamp 2-4 m away in a 4 m volume: the floor's reflected red is the
// same with cones a tenth of the volume long as with cones its whole length.
TEST(Vct, ShortDiffuseConesLeaveAMirrorItsFarReflection) {
    const Scene s = metalFloorBeforeALamp(0.0f);
    auto floorRed = [&](const char* maxDistance) {
        RenderSettings r = lampInTheVolume();
        setVct(r, "max-distance", maxDistance);
        const VctImages v = renderVct(s, r);
        EXPECT_TRUE(allFinite(v.specular));
        double red = 0.0;
        for (int y = kSize / 2; y < kSize; ++y)  // the floor: lower half of the image
            for (int x = 0; x < kSize; ++x) red += double(v.specular.at(x, y)[0]);
        return red / double(kSize * kSize / 2);
    };
    const double whole = floorRed("1"), tenth = floorRed("0.1");
    std::printf("VCT-TABLE mirror floor's mean reflected red: cones the volume's edge long %.4f, a tenth %.4f\n",
                whole, tenth);
    EXPECT_GT(whole, 0.05);
    EXPECT_NEAR(tenth, whole, 0.05 * whole);
}

// The debug views show the grid: ray-marched albedo sees the white back wall in the middle, the
// red wall on the left and the floor shaded by its angle to the eye; a slice across the room has red at its left end, green at its right
// (inside the frame whose left band marks its vertical axis in green).
TEST(Vct, DebugViewsShowTheGrid) {
    RenderSettings s = vctSettings();
    s.view = "vct.voxels";
    const VctImages voxels = renderVct(makeBuiltinScene("cornell"), s);
    ASSERT_EQ(voxels.frame.width, kSize);
    const float* centre = voxels.frame.at(kSize / 2, kSize / 4);
    EXPECT_NEAR(centre[0], 0.73f, 0.02f);
    EXPECT_NEAR(centre[1], 0.73f, 0.02f);
    const float* left = voxels.frame.at(kSize / 16, kSize / 2);
    EXPECT_GT(left[0], 4.0f * left[1]) << "the red wall";
    // Shaded by face: the floor, of the back wall's albedo, seen at a grazing angle is darker (it
    // was drawn at its albedo, flat); the mean over a row is the floor's, not one voxel's.
    double floor = 0.0;
    for (int x = kSize / 4; x < kSize * 3 / 4; ++x) floor += voxels.frame.at(x, kSize * 15 / 16)[1];
    floor /= double(kSize / 2);
    EXPECT_LT(floor, 0.73 * 0.85) << "the floor is as bright as the wall facing the eye";
    EXPECT_GT(floor, 0.73 * 0.4);
    s.view = "vct.slice";
    setVct(s, "slice-axis", "z");
    setVct(s, "slice-position", "0.5");
    const VctImages slice = renderVct(makeBuiltinScene("cornell"), s);
    int reddest = -1, greenest = -1;
    float bestRed = 0.0f, bestGreen = 0.0f;
    const int band = std::max(kSize / 48, 1);  // the slice frame's marker bands (debug_slice.glsl)
    for (int x = band; x < kSize - band; ++x) {
        const float* p = slice.frame.at(x, kSize / 2);
        if (p[0] - p[1] > bestRed) bestRed = p[0] - p[1], reddest = x;
        if (p[1] - p[0] > bestGreen) bestGreen = p[1] - p[0], greenest = x;
    }
    EXPECT_GE(reddest, 0);
    EXPECT_GT(greenest, reddest);
    EXPECT_LT(reddest, kSize / 8);
    EXPECT_GT(greenest, kSize * 7 / 8);
}

// The README's table: PSNR against the path tracer per preset on both Cornell scenes, and GPU
// milliseconds per sub-step on this machine.
// Opt-in (GIS_MEASURE=vct): the high preset is 128^3, beyond what the suite may use on llvmpipe.
TEST(Vct, MeasurePresets) {
    if (!measuring("vct")) GTEST_SKIP() << "set GIS_MEASURE=vct to measure the presets";
    for (const char* scene : {"cornell", "cornell-area"}) {
        const GiReference& ref = reference(scene);
        MetricOptions o;
        const ImageMetrics none = compareImages(ref.direct(), ref.ptFull(), o);
        std::printf("VCT-TABLE psnr %s none(direct only): %.2f dB sRGB vs 16-bounce path tracer\n", scene, none.psnrSrgb);
        for (const char* preset : {"low", "medium", "high", "realtime"}) {
            RenderSettings r = baseSettings("vct");
            applyPreset(r, "vct", preset);
            // The second frame reuses the volume; reduced-resolution presets converge later.
            VctImages v = renderVct(makeBuiltinScene(scene), r, std::max(2, giMethod("vct").framesToConverge(r)));
            const ImageF& frame = v.frame;
            const ImageMetrics full = compareImages(frame, ref.ptFull(), o);
            const ImageMetrics one = compareImages(frame, ref.ptOneBounce(), o);
            std::printf("VCT-TABLE psnr %s %s: %.2f dB sRGB vs 16-bounce, %.2f dB vs 1-bounce; "
                        "first-frame ms voxelize %.2f inject %.2f mips %.2f bounce %.2f trace %.2f\n",
                        scene, preset, full.psnrSrgb, one.psnrSrgb, v.stepMs["voxelize"], v.stepMs["inject"],
                        v.stepMs["mips"], v.stepMs["bounce"], v.stepMs["trace"]);
            EXPECT_TRUE(allFinite(frame));
        }
    }
}

// Issue #39: the environment reaches a surface only along rays that leave the scene.
// builtin:building's room with no opening under its sky alone (the sun taken away), one gather (the
// voxel bounces' cones still take the sky from the voxels): with sky rays through the triangles
// the room gets none of it; with the cones' own transmittance (vct.sky-rays=0) the sky comes
// through the 20 cm walls and roof in the 68 cm voxels (so the test can fail).
TEST(Vct, SkyRaysKeepTheSkyOutOfARoomWithNoOpening) {
    Scene building = makeBuiltinScene("building");
    building.lights.clear();
    RenderSettings s;
    s.width = s.height = 32;
    s.camera = building.leakCameras.dark;
    setVct(s, "bounces", "1");
    const double sky = (building.background.x + building.background.y + building.background.z) / 3.0;
    const int rays[2] = {0, 4};
    double mean[2] = {0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        setVct(s, "sky-rays", std::to_string(rays[i]));
        const VctImages v = renderVct(building, s);
        ASSERT_TRUE(allFinite(v.diffuse));
        mean[i] = meanRadiance(v.diffuse);
        std::printf("VCT-TABLE closed room under the sky alone, sky-rays %d: indirect.diffuse %.5f of the sky's radiance\n",
                    rays[i], mean[i] / sky);
    }
    EXPECT_GT(mean[0], 0.05 * sky) << "the cones no longer let the sky through: the test shows nothing";
    EXPECT_LT(mean[1], 1e-4 * sky);
}

}  // namespace
}  // namespace gis::test
