// The first hour with real files (docs/first-hour.md): the model everyone opens first is lit, the
// same method gives the same image everywhere, and the messages of the usual slips point at the
// fix. Each case failed before its change.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/bench_merge.h"
#include "bench/bench_row.h"
#include "cli_util.h"
#include "image.h"
#include "metrics.h"

namespace gis::test {
namespace {

const std::string kHelmet = std::string(GIS_SHARED_DIR) + "/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf";
const std::string kCornellBox = std::string(GIS_SHARED_DIR) + "/assets/reference/scenes/cornell_box/cornell_box.gltf";

// The program's messages on stderr ("gisandbox: ..."), not the progress bar a progressive pass
// (the emitters' ReSTIR accumulation on the helmet's emissive triangles) draws there.
int countMessages(const std::string& err) {
    int n = 0;
    for (size_t at = err.find("gisandbox:"); at != std::string::npos; at = err.find("gisandbox:", at + 1))
        n += at == 0 || err[at - 1] == '\n';
    return n;
}

TEST(FirstHour, DamagedHelmetIsLitByDefaultAndSaysWhatWasAdded) {
    const std::string dir = tempDir("first_hour_helmet");
    const CliResult lit = runCli("render --scene " + kHelmet + " --size 48x48 --out " + dir + "/lit.exr");
    ASSERT_EQ(lit.status, 0) << lit.err;
    EXPECT_EQ(countMessages(lit.err), 1) << lit.err;
    EXPECT_NE(lit.err.find("added the default sun"), std::string::npos) << lit.err;
    EXPECT_NE(lit.err.find("emission"), std::string::npos) << "the line says why the emission did not count: " << lit.err;
    const CliResult own = runCli("render --scene " + kHelmet + " --size 48x48 --lighting scene --out " + dir + "/own.exr");
    ASSERT_EQ(own.status, 0) << own.err;
    const double litMean = meanRadiance(readExr(dir + "/lit.exr")), ownMean = meanRadiance(readExr(dir + "/own.exr"));
    std::printf("DamagedHelmet 48x48 --gi none: mean radiance %.4f with auto, %.4f with its emission alone\n", litMean,
                ownMean);
    // The floor: a quarter of the default sky's radiance (0.4) over the whole frame, background
    // included (measured 0.345; 0.0036 before, with the emission alone).
    EXPECT_GT(litMean, 0.1);
    EXPECT_GT(litMean, 4.0 * ownMean);
}

TEST(FirstHour, EmitterLitCornellBoxIsUnchangedByAuto) {
    const std::string dir = tempDir("first_hour_cornell_box");
    const CliResult autoLit = runCli("render --scene " + kCornellBox + " --size 32x32 --out " + dir + "/auto.exr");
    ASSERT_EQ(autoLit.status, 0) << autoLit.err;
    EXPECT_EQ(autoLit.err.find("default sun"), std::string::npos) << autoLit.err;
    const CliResult own = runCli("render --scene " + kCornellBox + " --size 32x32 --lighting scene --out " + dir + "/own.exr");
    ASSERT_EQ(own.status, 0) << own.err;
    EXPECT_EQ(readExr(dir + "/auto.exr").rgba, readExr(dir + "/own.exr").rgba);
    const CliResult area = runCli("render --scene builtin:cornell-area --size 16x16 --out " + dir + "/area.exr");
    ASSERT_EQ(area.status, 0) << area.err;
    EXPECT_EQ(area.err.find("default sun"), std::string::npos) << area.err;
}

TEST(FirstHour, NoPresetIsTheViewersDefaultPreset) {
    // The viewer opens every pane at medium: render without --preset gives the same image (ssao:
    // GTAO, the fast kernel, not the hemisphere kernel of the bare parameter defaults).
    const std::string dir = tempDir("first_hour_preset");
    for (const char* method : {"ssao", "pathtrace"}) {
        SCOPED_TRACE(method);
        const std::string base = std::string("render --scene builtin:cornell --size 24x24 --gi ") + method;
        ASSERT_EQ(runCli(base + " --out " + dir + "/bare.exr").status, 0);
        ASSERT_EQ(runCli(base + " --preset medium --out " + dir + "/medium.exr").status, 0);
        EXPECT_EQ(readExr(dir + "/bare.exr").rgba, readExr(dir + "/medium.exr").rgba);
    }
}

TEST(FirstHour, DocumentedAliasesDoNotWarn) {
    const std::string dir = tempDir("first_hour_alias");
    const CliResult pt = runCli("render --scene builtin:cornell --size 8x8 --gi pathtrace --spp 2 --out " + dir + "/a.exr");
    ASSERT_EQ(pt.status, 0) << pt.err;
    EXPECT_EQ(pt.err.find("warning"), std::string::npos) << pt.err;
    const CliResult ao = runCli("render --scene builtin:cornell --size 8x8 --gi ssao --ao-radius 0.5 --out " + dir + "/b.exr");
    ASSERT_EQ(ao.status, 0) << ao.err;
    EXPECT_EQ(ao.err.find("warning"), std::string::npos) << ao.err;
    // An alias of no parameter of the rendered method still says it does nothing.
    const CliResult none = runCli("render --scene builtin:cornell --size 8x8 --spp 2 --out " + dir + "/c.exr");
    EXPECT_NE(none.err.find("another method"), std::string::npos) << none.err;
}

// vct's default conservative raster is the best the driver has, silently (every llvmpipe run
// warned that the hardware path it never asked for was missing); asking for `hardware` by name
// still says where it falls back.
TEST(FirstHour, VctWarnsOfAMissingHardwarePathOnlyWhenAskedForIt) {
    const std::string dir = tempDir("first_hour_conservative");
    const CliResult plain = runCli("render --scene builtin:cornell --size 8x8 --gi vct --frames 1 --out " + dir + "/a.png");
    ASSERT_EQ(plain.status, 0) << plain.err;
    EXPECT_EQ(plain.err.find("warning"), std::string::npos) << plain.err;
    const CliResult asked = runCli("render --scene builtin:cornell --size 8x8 --gi vct --frames 1 "
                                   "--set vct.conservative=hardware --out " + dir + "/b.png");
    ASSERT_EQ(asked.status, 0) << asked.err;
    const bool driverHasIt = asked.err.find("GL_NV_conservative_raster") == std::string::npos;
    if (driverHasIt) GTEST_SKIP() << "the driver has GL_NV_conservative_raster: nothing falls back";
    EXPECT_NE(asked.err.find("vct.conservative=hardware falls back to geometry"), std::string::npos) << asked.err;
}

TEST(FirstHour, HelpListsEveryBuiltinScene) {
    const CliResult help = runCli("render --help");
    ASSERT_EQ(help.status, 0);
    for (const char* name : {"cornell", "cornell-area", "brdf-gallery", "leak", "room", "mirror", "atrium", "building"})
        EXPECT_NE(help.out.find(name), std::string::npos) << name;
}

// A model whose only emission is a detail (ClearCoatTest's white label panels) counts as lit by
// it under --lighting auto and renders dark: the line says so and names the flag that adds a sky.
TEST(FirstHour, EmissionOnlySceneSaysItIsLitByItsEmission) {
    const std::string dir = tempDir("first_hour_clearcoat");
    const CliResult r = runCli("render --scene " + std::string(GIS_SHARED_DIR) +
                               "/assets/gltf/ClearCoatTest/ClearCoatTest.gltf --size 16x16 --out " + dir + "/c.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("lit by its emission alone"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--lighting default"), std::string::npos) << r.err;
}

TEST(FirstHour, TyposGetDidYouMean) {
    const std::string dir = tempDir("first_hour_typos");
    struct Case {
        std::string args, needle;
    };
    const std::vector<Case> cases = {
        {"render --scene builtin:cornell --gi vtc --out " + dir + "/a.png", "did you mean 'vct'"},
        {"render --scene builtin:cornel --out " + dir + "/a.png", "did you mean 'cornell'"},
        {"render --scene builtin:cornell --gi vct --set vct.resolutoin=32 --out " + dir + "/a.png",
         "did you mean 'resolution'"},
        // In the order typed, with the flag it was meant to be.
        {"render --scene builtin:cornell --gii vct --out " + dir + "/a.png", "--gii vct (did you mean '--gi'?)"},
        {"rendr --scene builtin:cornell --out " + dir + "/a.png", "did you mean 'render'"},
        // The value as a word of its own: the form --set takes.
        {"render --scene builtin:cornell --set vct.resolution 32 --out " + dir + "/a.png", "--set vct.resolution=32"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args);
        const CliResult r = runCli(c.args);
        EXPECT_NE(r.status, 0);
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fileExists(dir + "/a.png"));
}

TEST(FirstHour, MethodTableColumnsAlign) {
    const CliResult r = runCli("methods vct");
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line;
    int rows = 0;
    size_t column = std::string::npos;
    while (std::getline(lines, line)) {
        if (line.rfind("  vct.", 0) != 0) continue;
        ++rows;
        const size_t at = line.find(" default ");
        ASSERT_NE(at, std::string::npos) << line;
        if (column == std::string::npos) column = at;
        EXPECT_EQ(at, column) << line;
    }
    EXPECT_GT(rows, 3);
}

TEST(FirstHour, BenchMergeSaysWhatItUses) {
    const std::string dir = tempDir("first_hour_merge");
    const CliResult noManifest = runCli("bench --merge " + dir);
    EXPECT_NE(noManifest.status, 0);
    EXPECT_EQ(noManifest.err.find("--manifest '"), std::string::npos) << "names a path the user never gave: " << noManifest.err;
    EXPECT_NE(noManifest.err.find("no manifest"), std::string::npos) << noManifest.err;
    const CliResult elsewhere = runCli("bench --merge " + dir + " --out-dir " + dir + "/other");
    EXPECT_NE(elsewhere.status, 0);
    EXPECT_NE(elsewhere.err.find("--out-dir"), std::string::npos) << elsewhere.err;
}

TEST(FirstHour, DiffOfAPngAgainstAnExrComparesLikeForLike) {
    // The PNG and the EXR of one render: the same picture, so the error must be near zero; before,
    // the tone-mapped PNG was compared with raw radiance.
    const std::string dir = tempDir("first_hour_diff");
    ASSERT_EQ(runCli("render --scene builtin:cornell --size 32x32 --out " + dir + "/a.png").status, 0);
    ASSERT_EQ(runCli("render --scene builtin:cornell --size 32x32 --out " + dir + "/a.exr").status, 0);
    const CliResult r = runCli("diff " + dir + "/a.png " + dir + "/a.exr --json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("tone-mapped PNG"), std::string::npos) << r.err;
    const size_t at = r.out.find("\"flip\":");
    ASSERT_NE(at, std::string::npos) << r.out;
    const double flip = std::stod(r.out.substr(at + 7));
    std::printf("FLIP of a render's PNG against its EXR: %.4f\n", flip);
    EXPECT_LT(flip, 0.02);
}

TEST(FirstHour, BackgroundReachesTheConstantAmbient) {
    // --gi none's indirect term is the constant ambient: with --background B and no --ambient it
    // is B, as the default sky's radiance is when it is added; an explicit --ambient still wins.
    const std::string dir = tempDir("first_hour_background");
    const std::string base = "render --scene builtin:cornell --size 16x16 --no-shadows ";
    ASSERT_EQ(runCli(base + "--background 0.5 --out " + dir + "/bg.exr").status, 0);
    ASSERT_EQ(runCli(base + "--background 0.5 --ambient 0.5 --out " + dir + "/both.exr").status, 0);
    ASSERT_EQ(runCli(base + "--background 0.5 --ambient 0.03 --out " + dir + "/explicit.exr").status, 0);
    EXPECT_EQ(readExr(dir + "/bg.exr").rgba, readExr(dir + "/both.exr").rgba);
    EXPECT_GT(meanRadiance(readExr(dir + "/bg.exr")), meanRadiance(readExr(dir + "/explicit.exr")) + 0.05);
}

TEST(FirstHour, BenchRowsKeepBothCostsThroughTheirJson) {
    // A row carries the steady frame, the convergence after a cut and after a light edit, and the
    // time-to-quality curve; each survives the cell's record, and the chart's frame cost is the
    // dearer of a converging and a steady frame (a converged path tracer's frame costs nothing).
    BenchRow row;
    row.scene = "s", row.method = "pathtrace", row.preset = "low", row.description = "d";
    row.ms = 0.01;
    row.cut = {4, 20.0, 25.0, 4.5, 3, 15.0};
    row.quality = {{1, 5.0, {}}, {2, 10.0, {}}, {4, 20.0, {}}};
    row.quality.back().error.flip = 0.125;
    const BenchRow back = rowFromJson(rowToJson(row));
    EXPECT_EQ(back.cut.frames, 4);
    EXPECT_DOUBLE_EQ(back.cut.gpuMs, 20.0);
    EXPECT_DOUBLE_EQ(back.cut.frameMs, 4.5);
    EXPECT_EQ(back.cut.settledFrames, 3);
    EXPECT_DOUBLE_EQ(back.cut.settledGpuMs, 15.0);
    EXPECT_FALSE(back.edit.has_value()) << "no light edited, no figure";
    ASSERT_EQ(back.quality.size(), 3u);
    EXPECT_EQ(back.quality[2].frames, 4);
    EXPECT_DOUBLE_EQ(back.quality[2].error.flip, 0.125);
    EXPECT_DOUBLE_EQ(frameCostMs(back), 4.5);
    row.edit = BenchRow::Convergence{2, 8.0, 9.0, 4.0, 1, 4.0};
    EXPECT_EQ(rowFromJson(rowToJson(row)).edit->frames, 2);
    EXPECT_EQ(rowFromJson(rowToJson(row)).edit->settledFrames, 1);
}

// The README's first commands as it writes them (#42): the split-view script, with the screenshot
// and quit the README says to append under xvfb-run, and the per-term EXR render; run by the shell
// in a fresh directory whose build/gisandbox is this build's binary. (Stumbles 1 and 2: the script
// never exited, the render lacked its scene.)
std::string readmeCommand(const std::string& readme, const std::string& start, char end) {
    const size_t at = readme.find(start);
    if (at == std::string::npos) return "";
    std::string command = readme.substr(at, readme.find(end, at) - at);
    for (char& c : command)
        if (c == '\n') c = ' ';
    return command;
}

TEST(FirstHour, TheReadmesFirstCommandsRunAsWritten) {
    std::ifstream file(std::string(GIS_SOURCE_DIR) + "/README.md");
    const std::string readme((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const std::string script = readmeCommand(readme, "printf 'mode split", '\n');
    const std::string headless = readmeCommand(readme, "printf 'converge", '`');
    const std::string term = readmeCommand(readme, "build/gisandbox render --scene", '`');
    ASSERT_FALSE(script.empty() || headless.empty() || term.empty()) << "the README no longer has its first commands";
    const std::string dir = tempDir("readme_commands");
    std::filesystem::create_directories(dir + "/build");
    std::filesystem::create_symlink(GIS_BINARY, dir + "/build/gisandbox");
    for (const std::string& command : {script, headless, term}) {
        // A newline ends the command: the README's own comment after it must not swallow the brace.
        const std::string shell = "cd '" + dir + "' && { " + command + "\n} >> out.txt 2>&1";
        EXPECT_EQ(std::system(shell.c_str()), 0) << command;
    }
    bool screenshot = false;
    if (std::filesystem::is_directory(dir + "/screenshots"))
        for (const auto& e : std::filesystem::directory_iterator(dir + "/screenshots")) screenshot |= e.path().extension() == ".png";
    EXPECT_TRUE(screenshot) << "the split view's screenshot";
    ASSERT_TRUE(fileExists(dir + "/id.exr"));
    EXPECT_GT(meanRadiance(readExr(dir + "/id.exr")), 0.01) << "the indirect diffuse term is black";
}

}  // namespace
}  // namespace gis::test
