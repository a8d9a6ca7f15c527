// The lighting's terms as views (docs/cli.md "Debug views"): `render --view direct`,
// `indirect.diffuse`, `indirect.specular` and `emission` are radiance contributions that add up,
// pixel by pixel, to the final image before tone mapping; `ao` is the occlusion the indirect
// terms were multiplied by. Rendered as a user does, into linear EXRs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "gi/method.h"
#include "image.h"

namespace gis::test {
namespace {

const std::vector<std::string> kRadianceTerms{"direct", "indirect.diffuse", "indirect.specular", "emission"};

struct Case {
    const char* scene;
    const char* gi;
    const char* args;  // settings that shorten the progressive work (the same for every view)
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.gi << " on " << c.scene; }

// `render --view VIEW` of the case at 64x64, read back from its EXR. --hdr32: the final image is
// then float, so the only rounding the sum sees is the terms' own in the RGBA16F debug target.
ImageF renderView(const Case& c, const std::string& view, const std::string& dir) {
    const std::string out = dir + "/" + view + ".exr";
    const CliResult r = runCli(std::string("render --scene ") + c.scene + " --gi " + c.gi + " " + c.args +
                               " --size 64x64 --hdr32 --view " + view + " --out " + out);
    EXPECT_EQ(r.status, 0) << view << ": " << r.err;
    return r.status == 0 ? readExr(out) : ImageF{};
}

float maxChannel(const ImageF& img) {
    float m = 0.0f;
    for (size_t i = 0; i < img.rgba.size(); i += 4) m = std::max({m, img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]});
    return m;
}

double meanRgb(const ImageF& img) {
    double sum = 0.0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) sum += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2];
    return sum / double(img.rgba.size() / 4 * 3);
}

class TermViews : public ::testing::TestWithParam<Case> {};

TEST_P(TermViews, AddUpToTheFinalImageBeforeToneMapping) {
    const Case c = GetParam();
    const std::string dir = tempDir(std::string("term_views_") + c.gi + "_" + (c.scene + 8));
    const ImageF final = renderView(c, "final", dir);
    std::vector<ImageF> terms;
    for (const std::string& t : kRadianceTerms) terms.push_back(renderView(c, t, dir));
    const ImageF ao = renderView(c, "ao", dir);
    ASSERT_FALSE(::testing::Test::HasFailure());

    // Relative to the pixel, with a floor for black pixels: storing a term as a half float loses
    // less than 2^-10 = 9.8e-4 of it (llvmpipe truncates; measured worst 9.1e-4 of the sum).
    constexpr double kRelative = 1e-3, kAbsolute = 1e-5;
    int bad = 0, negative = 0;
    double worst = 0.0;
    for (size_t i = 0; i < final.rgba.size(); ++i) {
        if (i % 4 == 3) continue;  // alpha
        double sum = 0.0;
        for (const ImageF& t : terms) {
            negative += t.rgba[i] < 0.0f;
            sum += t.rgba[i];
        }
        const double error = std::abs(sum - final.rgba[i]);
        worst = std::max(worst, error / (final.rgba[i] + kAbsolute / kRelative));
        bad += error > kRelative * final.rgba[i] + kAbsolute;
    }
    EXPECT_EQ(bad, 0) << "channels where the terms do not add up to final";
    EXPECT_EQ(negative, 0) << "negative radiance in a term";
    std::printf("%s --gi %s: worst |sum - final| / (final + 0.01) %.2e; mean final %.4f = direct %.4f + "
                "indirect.diffuse %.4f + indirect.specular %.4f + emission %.4f\n",
                c.scene, c.gi, worst, meanRgb(final), meanRgb(terms[0]), meanRgb(terms[1]), meanRgb(terms[2]),
                meanRgb(terms[3]));

    // Each term is there where the scene has it: the ceiling light's direct light, and indirect
    // light from the method (or the constant ambient of `none`); the area light's own emission.
    EXPECT_GT(maxChannel(terms[0]), 0.1f) << "direct";
    EXPECT_GT(maxChannel(terms[1]), 0.01f) << "indirect.diffuse";
    const std::string scene = c.scene;
    if (scene == "builtin:cornell-area") {
        EXPECT_GT(maxChannel(terms[3]), 10.0f) << "emission";
    }
    if (scene == "builtin:cornell") {
        EXPECT_EQ(maxChannel(terms[3]), 0.0f) << "emission: nothing emits, no background";
    }
    // The gallery's glossy spheres (the Cornell boxes are Lambertian: no specular lobe).
    if (scene == "builtin:brdf-gallery") {
        EXPECT_GT(maxChannel(terms[2]), 0.01f) << "indirect.specular";
    }
    // AO: a grey occlusion in [0, 1]; partly occluded pixels (the box's corners) where the method
    // computes an occlusion (sdf only with sdf.ao, off by default: its case turns it on), none else
    // (the materials have no occlusion texture).
    int partly = 0;
    for (size_t i = 0; i < ao.rgba.size(); i += 4) {
        ASSERT_GE(ao.rgba[i], 0.0f);
        ASSERT_LE(ao.rgba[i], 1.0f);
        ASSERT_EQ(ao.rgba[i], ao.rgba[i + 1]);
        partly += ao.rgba[i] > 0.05f && ao.rgba[i] < 0.9f;
    }
    const double partlyShare = double(partly) / double(ao.rgba.size() / 4);
    std::printf("ao in (0.05, 0.9): %.1f%% of the pixels\n", 100.0 * partlyShare);
    const std::string gi = c.gi;
    if (gi == "ssao" || gi == "sdf") {
        EXPECT_GT(partlyShare, 0.02);
    } else {
        EXPECT_EQ(partly, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(, TermViews,
                         ::testing::Values(Case{"builtin:cornell", "none", ""}, Case{"builtin:cornell", "ssao", ""},
                                           Case{"builtin:cornell", "vct", ""}, Case{"builtin:cornell", "sdf", "--preset low --set sdf.ao=1"},
                                           Case{"builtin:cornell", "probes", "--preset low --set probes.max-updates=8"},
                                           Case{"builtin:cornell-area", "vct", "--set emitters.accumulate=4"},
                                           Case{"builtin:brdf-gallery", "vct", ""}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             std::string name = std::string(info.param.gi) + "_" + (info.param.scene + 8);
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// The path tracer's terms (issue 26): the same paths keep only the viewed term, so direct +
// emission + pathtrace.indirect is the final image, up to the half-float debug target's rounding,
// and indirect.diffuse + indirect.specular (the first surface's two lobes) is pathtrace.indirect.
// On cornell-area the area light is both seen (emission) and the first surfaces' direct light
// (sampled there and hit by BSDF samples, the two halves of the MIS).
TEST(PathTracerTermViews, AddUpToTheFinalImage) {
    const std::string dir = tempDir("term_views_pathtrace");
    auto render = [&](const std::string& view, const std::string& scene = "cornell-area") {
        const std::string out = dir + "/" + scene + view + ".exr";
        const CliResult r = runCli("render --scene builtin:" + scene + " --gi pathtrace --spp 4 --size 32x32 --hdr32 "
                                   "--view " + view + " --out " + out);
        EXPECT_EQ(r.status, 0) << view << ": " << r.err;
        return r.status == 0 ? readExr(out) : ImageF{};
    };
    const ImageF final = render("final");
    const std::vector<ImageF> terms{render("direct"), render("emission"), render("pathtrace.indirect")};
    const std::vector<ImageF> lobes{render("indirect.diffuse"), render("indirect.specular")};
    ASSERT_FALSE(::testing::Test::HasFailure());
    constexpr double kRelative = 1e-3, kAbsolute = 1e-5;  // as above: a half float per term
    auto badChannels = [&](const std::vector<ImageF>& parts, const ImageF& whole) {
        int bad = 0;
        for (size_t i = 0; i < whole.rgba.size(); ++i) {
            if (i % 4 == 3) continue;
            double sum = 0.0;
            for (const ImageF& t : parts) sum += t.rgba[i];
            bad += std::abs(sum - whole.rgba[i]) > kRelative * whole.rgba[i] + kAbsolute;
        }
        return bad;
    };
    EXPECT_EQ(badChannels(terms, final), 0) << "channels where the terms do not add up to final";
    EXPECT_EQ(badChannels(lobes, terms[2]), 0) << "channels where the lobes do not add up to pathtrace.indirect";
    // cornell-area's walls are Lambertian: their indirect light is all diffuse. The mirror sphere of
    // builtin:mirror reflects the room: indirect specular light.
    EXPECT_NEAR(meanRgb(lobes[0]), meanRgb(terms[2]), 1e-3 * meanRgb(terms[2]));
    EXPECT_GT(meanRgb(render("indirect.specular", "mirror")), 0.002);
    std::printf("pathtrace on cornell-area: mean final %.4f = direct %.4f + emission %.4f + indirect %.4f\n",
                meanRgb(final), meanRgb(terms[0]), meanRgb(terms[1]), meanRgb(terms[2]));
    EXPECT_GT(maxChannel(terms[0]), 0.1f) << "direct";
    EXPECT_GT(maxChannel(terms[1]), 10.0f) << "emission: the area light seen";
    EXPECT_GT(meanRgb(terms[2]), 0.01) << "indirect";
    const CliResult r = runCli("render --scene builtin:cornell --gi ao-reference --size 8x8 --view indirect.diffuse --out " +
                               dir + "/x.exr");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("it exists for none, ssao, pathtrace, vct"), std::string::npos) << r.err;
}

// The emission seen directly is box-filtered over each pixel, as the path tracer (a uniformly
// jittered point per sample) and the Cycles references filter it: the G-buffer's emission is the
// resolve of a multisampled draw. Point-sampled, each pixel an emitter's edge crosses was all or
// nothing of its radiance. Against the path tracer's own emission term on cornell-area (its area
// light seen from below at 64x64): the same total, pixels part-covered along the edge, and no
// pixel off by more than the path tracer's own coverage noise at 256 spp allows.
TEST(EmissionAntialiasing, EmitterEdgesAreBoxFilteredAsInThePathTracer) {
    const std::string dir = tempDir("emission_antialiasing");
    const ImageF raster = renderView(Case{"builtin:cornell-area", "none", ""}, "emission", dir);
    const ImageF traced =
        renderView(Case{"builtin:cornell-area", "pathtrace", "--spp 256"}, "emission", tempDir("emission_antialiasing_pt"));
    ASSERT_FALSE(::testing::Test::HasFailure());
    const float radiance = maxChannel(traced);
    ASSERT_GT(radiance, 1.0f);
    int partial = 0;
    double worst = 0.0;
    for (size_t i = 0; i < raster.rgba.size(); i += 4) {
        const float v = raster.rgba[i];
        partial += v > 0.05f * radiance && v < 0.95f * radiance;
        worst = std::max(worst, double(std::abs(v - traced.rgba[i])) / radiance);
    }
    std::printf("cornell-area 64x64 emission: mean %.4f, path tracer %.4f; %d part-covered pixels; worst pixel %.3f "
                "of the radiance\n", meanRgb(raster), meanRgb(traced), partial, worst);
    EXPECT_NEAR(meanRgb(raster) / meanRgb(traced), 1.0, 0.02);
    EXPECT_GE(partial, 8) << "the edge's pixels";
    EXPECT_LT(worst, 0.25);
}

// Every method that lights a G-buffer offers every term, each once (a method's own "ao" stands
// for the lighting's), with its help line.
TEST(TermViewList, EveryDeferredMethodOffersEveryTerm) {
    for (const GiMethod& m : giMethods()) {
        if (m.pipeline != MethodPipeline::Deferred) continue;
        const CliResult list = runCli("render --scene builtin:cornell --size 16x16 --gi " + m.name + " --view list");
        ASSERT_EQ(list.status, 0) << m.name << ": " << list.err;
        std::vector<std::string> names{kRadianceTerms};
        names.push_back("ao");
        for (const std::string& name : names) {
            const std::string row = "\n" + name + " ";
            const size_t at = ("\n" + list.out).find(row);
            EXPECT_NE(at, std::string::npos) << m.name << " lacks " << name << "\n" << list.out;
            EXPECT_EQ(("\n" + list.out).find(row, at + 1), std::string::npos) << m.name << " lists " << name << " twice";
        }
    }
}

// A view the method does not offer is one line naming the views it does.
TEST(TermViewList, AnUnknownViewNamesTheAvailableOnes) {
    const std::string dir = tempDir("term_views_unknown");
    const CliResult r = runCli("render --scene builtin:cornell --size 16x16 --gi vct --view indirect --out " + dir +
                               "/x.exr");
    EXPECT_NE(r.status, 0);
    const size_t at = r.err.find("gisandbox: error: --view 'indirect' is not produced by --gi vct (available: ");
    ASSERT_NE(at, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("gisandbox: error", at + 1), std::string::npos) << "one error: " << r.err;
    const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
    for (const char* name : {"final", "direct", "indirect.diffuse", "indirect.specular", "emission", "ao", "vct.slice"})
        EXPECT_TRUE(line.find(std::string(" ") + name + ",") != std::string::npos ||
                    line.find(std::string(" ") + name + ")") != std::string::npos)
            << name << " missing from: " << line;
    EXPECT_FALSE(fileExists(dir + "/x.exr"));
}

}  // namespace
}  // namespace gis::test
