// Outputs under hostile conditions: the atomic writer's guarantees (private, exclusive temporary;
// the old file kept on failure; no kill at a file-size limit), exports and bench cells under a
// size limit, content ids that do not depend on the temporary directory, and `diff` refusing to
// write its heatmap over one of its inputs.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_util.h"
#include "gl/gl.h"
#include "render_test_util.h"
#include "gi/method.h"
#include "gi/sdf/sdf_settings.h"
#include "gi/vct/vct_settings.h"
#include "volume/scene_volume.h"
#include "image.h"
#include "scene/atomic_file.h"
#include "scene/scene.h"
#include "cli/settings_io.h"
#include "view/view_script.h"
#include "cli/view_state.h"

namespace {

using gis::test::countLines;
using gis::test::runCli;
using gis::test::tempDir;
namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void spit(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// The temporary is the writer's own: a fresh name beside the target, mode 0600 while it is
// being written; the target gets the old file's mode back on commit.
TEST(AtomicFile, TemporaryIsExclusivePrivateAndBesideTheTarget) {
    const std::string dir = tempDir("atomic_private");
    const std::string target = dir + "/out.json";
    spit(target, "old");
    ASSERT_EQ(::chmod(target.c_str(), 0644), 0);
    {
        gis::AtomicFile a(target), b(target);  // two writers of one target never share a temporary
        EXPECT_NE(a.tempPath(), b.tempPath());
        EXPECT_EQ(fs::path(a.tempPath()).parent_path(), fs::path(target).parent_path());
        struct stat st {};
        ASSERT_EQ(::stat(a.tempPath().c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & 0777, 0600u);
        a.write("new");
        a.commit();
    }
    EXPECT_EQ(slurp(target), "new");
    struct stat st {};
    ASSERT_EQ(::stat(target.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0644u);
    EXPECT_EQ(entries(dir), std::vector<std::string>{"out.json"}) << "a temporary was left behind";
}

// A symlink planted at the target is replaced, not followed: the file it points to is unchanged.
TEST(AtomicFile, PlantedSymlinkAtTheTargetIsReplacedNotFollowed) {
    const std::string dir = tempDir("atomic_symlink");
    spit(dir + "/victim", "precious");
    fs::create_symlink(dir + "/victim", dir + "/out.png");
    gis::writeFileAtomically(dir + "/out.png", "image");
    EXPECT_EQ(slurp(dir + "/victim"), "precious");
    EXPECT_FALSE(fs::is_symlink(dir + "/out.png"));
    EXPECT_EQ(slurp(dir + "/out.png"), "image");
}

// A set is all or nothing: the second file's failure (its directory is missing) leaves the first
// target as it was, and no temporary behind.
TEST(AtomicFile, ASetThatFailsChangesNoneOfItsTargets) {
    const std::string dir = tempDir("atomic_set");
    spit(dir + "/a.csv", "old");
    EXPECT_THROW(gis::writeFilesAtomically({{dir + "/a.csv", "new"}, {dir + "/missing/b.csv", "x"}}), gis::Error);
    EXPECT_EQ(slurp(dir + "/a.csv"), "old");
    EXPECT_EQ(entries(dir), std::vector<std::string>{"a.csv"});
}

// `export --scene SCENE` over the pair dir/keep.gltf + keep.bin, run after `shellPrefix`, is
// refused: one error line naming `reason`, exit 1, no "wrote", the old pair intact and nothing else
// left in the folder.
void expectExportRefusedKeepingThePair(const std::string& dir, const std::string& scene,
                                       const std::string& shellPrefix, const std::string& reason) {
    const std::string out = dir + "/keep.gltf";
    const std::string gltf = slurp(out), bin = slurp(dir + "/keep.bin");
    const gis::test::CliResult r = runCli("export --scene " + scene + " --out " + quoted(out), shellPrefix);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
    EXPECT_TRUE(slurp(out) == gltf) << "the .gltf was replaced";
    EXPECT_TRUE(slurp(dir + "/keep.bin") == bin) << "the .bin was replaced";
    EXPECT_EQ(entries(dir), (std::vector<std::string>{"keep.bin", "keep.gltf"}));
}

// `export` over an existing pair under a file-size limit: one error line with the OS's reason,
// exit 1 (it used to die of SIGXFSZ, status 153, with a partial .bin), both old files intact.
TEST(Hardening, ExportUnderAFileSizeLimitKeepsTheOldPair) {
    const std::string dir = tempDir("hardening_export");
    ASSERT_EQ(runCli("export --scene builtin:room --out " + quoted(dir + "/keep.gltf")).status, 0);
    ASSERT_GT(slurp(dir + "/keep.bin").size(), 4096u) << "the limit below must be smaller than the buffer";
    // The old pair is replaced by a different scene's, so a partial write would show.
    expectExportRefusedKeepingThePair(dir, "builtin:cornell", "ulimit -f 4;", "File too large");
}

// `export` over an existing pair on a file system that is full (a 32 KiB tmpfs: the new pair's
// temporaries do not fit beside the old pair): one error line with the OS's reason, exit 1, the old
// pair intact and no temporary left. Mounting needs root; skipped where it is refused.
TEST(Hardening, ExportOnAFullFileSystemKeepsTheOldPair) {
    const std::string dir = tempDir("hardening_tmpfs");
    if (geteuid() != 0) GTEST_SKIP() << "mounting a tmpfs needs root (the ulimit test above covers the same path)";
    if (std::system(("mount -t tmpfs -o size=32k tmpfs " + quoted(dir) + " 2>/dev/null").c_str()) != 0)
        GTEST_SKIP() << "this machine refuses to mount a tmpfs";
    struct Unmount {
        std::string dir;
        ~Unmount() { (void)std::system(("umount '" + dir + "'").c_str()); }
    } unmount{dir};
    ASSERT_EQ(runCli("export --scene builtin:cornell --out " + quoted(dir + "/keep.gltf")).status, 0)
        << "the old pair fits";
    expectExportRefusedKeepingThePair(dir, "builtin:room", "", "No space left on device");
}

// A built-in scene's content id is its glTF serialization hashed in memory: no export to a
// temporary directory (which another user could pre-create), so TMPDIR cannot change or break it.
TEST(Hardening, BuiltinSceneIdsDoNotDependOnTheTemporaryDirectory) {
    const std::string dir = tempDir("hardening_tmpdir");
    const std::string plan = "bench --plan --scenes builtin:cornell --methods none --presets low --size 24x24 "
                             "--frames 3 --warmup 1 --reference-spp 8";
    const gis::test::CliResult normal = runCli(plan);
    ASSERT_EQ(normal.status, 0) << normal.err;
    ASSERT_FALSE(normal.out.empty());
    for (const std::string& tmpdir : {dir + "/does-not-exist", dir}) {
        const gis::test::CliResult r = runCli(plan, "TMPDIR=" + quoted(tmpdir));
        EXPECT_EQ(r.status, 0) << tmpdir << ": " << r.err;
        EXPECT_EQ(r.out, normal.out) << "TMPDIR=" << tmpdir << " changed the ids";
    }
    EXPECT_TRUE(entries(dir).empty()) << "the plan wrote into TMPDIR";
}

// A bench cell under a file-size limit: one error line naming the reason, status 1 -- not a
// SIGXFSZ kill (153) -- and no temporary left in the output folder.
TEST(Hardening, BenchCellUnderAFileSizeLimitIsAnErrorNotAKill) {
    const std::string dir = tempDir("hardening_cell");
    const gis::test::CliResult plan = runCli("bench --plan --scenes builtin:cornell --methods none --presets low "
                                             "--size 24x24 --frames 3 --warmup 1 --reference-spp 8");
    ASSERT_EQ(plan.status, 0) << plan.err;
    spit(dir + "/sweep.jsonl", plan.out);
    const std::string firstId = nlohmann::json::parse(plan.out.substr(0, plan.out.find('\n')))["id"];
    const gis::test::CliResult r =
        runCli("bench --manifest " + quoted(dir + "/sweep.jsonl") + " --out-dir " + quoted(dir + "/O") + " --cell " + firstId,
               "ulimit -f 1; MESA_SHADER_CACHE_DISABLE=true");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << "left " << e.path();
}

// `diff --heatmap` naming one of its inputs -- by the same name, another spelling, a symlink or a
// hard link -- is refused before anything is written; the input is unchanged.
TEST(Hardening, DiffRefusesAHeatmapPathThatIsOneOfItsInputs) {
    const std::string dir = tempDir("hardening_diff");
    gis::ImageU8 img;
    img.width = img.height = 8;
    img.rgba.assign(8 * 8 * 4, 200);
    gis::writePng(dir + "/t.png", img);
    img.rgba.assign(8 * 8 * 4, 100);
    gis::writePng(dir + "/ref.png", img);
    fs::create_symlink(dir + "/t.png", dir + "/alias.png");
    fs::create_hard_link(dir + "/ref.png", dir + "/hard.png");
    const std::string t = slurp(dir + "/t.png"), ref = slurp(dir + "/ref.png");
    const std::string base = "diff " + quoted(dir + "/t.png") + " " + quoted(dir + "/ref.png") + " --heatmap ";
    for (const std::string& heatmap : {dir + "/t.png", dir + "/./ref.png", dir + "/alias.png", dir + "/hard.png"}) {
        const gis::test::CliResult r = runCli(base + quoted(heatmap));
        EXPECT_EQ(r.status, 1) << heatmap;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("would be overwritten"), std::string::npos) << r.err;
        EXPECT_TRUE(slurp(dir + "/t.png") == t && slurp(dir + "/ref.png") == ref) << heatmap << " overwrote an input";
    }
    EXPECT_EQ(runCli(base + quoted(dir + "/heat.png")).status, 0);  // another path is fine
}

// Every registered method renders under the GL debug output without one GL error message: a
// failed call (a dispatch past the work-group limit, a uniform the program lacks) is a silently
// wrong image, not a crash. Probes used to log GL_INVALID_OPERATION for two uniforms every frame.
// On the point-lit Cornell box and on the emitter-lit one (the emitters' ReSTIR pass, their light
// injected into the volumes, and the volumes' emission with emitters.mode=gi).
TEST(Hardening, EveryMethodRendersWithoutAGlError) {
    const std::string dir = tempDir("hardening_gl_debug");
    const char* scenes[] = {"builtin:cornell", "builtin:cornell-area", "builtin:cornell-area --emitters gi"};
    for (const char* scene : scenes)
        for (const gis::GiMethod& m : gis::giMethods()) {
            // Few frames, samples and updates: the calls are what is checked, not convergence.
            const std::string extra = m.name == "pathtrace" || m.name == "ao-reference" ? " --set " + m.name + ".spp=2"
                                      : m.name == "probes" || m.name == "hddagi" ? " --set " + m.name + ".max-updates=2"
                                                                                 : "";
            const gis::test::CliResult r = runCli(std::string("render --gl-debug --scene ") + scene +
                                                  " --size 32x32 --frames 4 --set emitters.accumulate=2 --gi " + m.name + extra +
                                                  " --out " + quoted(dir + "/" + m.name + ".exr"));
            EXPECT_EQ(r.status, 0) << scene << " " << m.name << ": " << r.err;
            EXPECT_EQ(r.err.find("GL debug [error"), std::string::npos) << scene << " " << m.name << ":\n" << r.err;
        }
}

// 41^3 probes: one work group per probe is past the 65,535-group limit of one dispatch. The trace
// and blend are split over several dispatches, so the probes light the scene (the image differs
// from intensity 0, which it equalled when the dispatch failed) and no GL error is logged.
TEST(Hardening, ProbesPastTheWorkGroupLimitStillLightTheScene) {
    const std::string dir = tempDir("hardening_probes");
    const std::string base = "render --gl-debug --scene builtin:cornell --gi probes --size 16x16 "
                             "--set probes.spacing=0.0245 --set probes.rays=8 --set probes.ray-budget=0 "
                             "--set probes.max-updates=1 --out ";
    const gis::test::CliResult lit = runCli(base + quoted(dir + "/lit.exr"));
    ASSERT_EQ(lit.status, 0) << lit.err;
    EXPECT_EQ(lit.err.find("GL debug [error"), std::string::npos) << lit.err;
    ASSERT_EQ(runCli(base + quoted(dir + "/dark.exr") + " --set probes.intensity=0").status, 0);
    const gis::ImageF a = gis::readExr(dir + "/lit.exr"), b = gis::readExr(dir + "/dark.exr");
    double sumA = 0, sumB = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) sumA += a.rgba[i] + a.rgba[i + 1] + a.rgba[i + 2];
    for (size_t i = 0; i < b.rgba.size(); i += 4) sumB += b.rgba[i] + b.rgba[i + 1] + b.rgba[i + 2];
    EXPECT_GT(sumA, sumB * 1.05) << "indirect light missing: " << sumA << " vs " << sumB;
}

// A probe grid whose distance moments (1568 bytes a probe) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE:
// its binding would be GL_INVALID_VALUE and every probe would read nothing (on llvmpipe it traced
// for minutes, then wrote an image). Now refused before anything renders, naming the limit, with
// no output. On a GPU whose limit holds the grid there is nothing to check.
TEST(Hardening, AProbeGridPastTheStorageBlockLimitIsOneClearError) {
    gis::test::context();
    const int64_t distanceBytes = 196000000;  // 50^3 probes at spacing 0.02 on the Cornell box
    if (gis::gl::maxStorageBlockBytes() >= distanceBytes) GTEST_SKIP() << "this GPU's storage blocks hold the grid";
    const std::string dir = tempDir("hardening_storage_limit");
    const gis::test::CliResult r = runCli("render --scene builtin:cornell --gi probes --size 16x16 "
                                          "--set probes.spacing=0.02 --set probes.rays=8 --out " +
                                          quoted(dir + "/out.exr"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::to_string(distanceBytes)), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
}

// A settings file's camera gets the glTF loader's checks: a znear the depth buffer cannot resolve
// (it rendered near-black at 1e-7, black at 1e-30, exit 0) is refused, and each bad value is
// named by its own key (distance, pitch and yfov errors all used to name camera.znear).
TEST(Hardening, SettingsCameraIsCheckedLikeAGltfCamera) {
    const std::string dir = tempDir("hardening_settings_camera");
    struct Case {
        const char* camera;
        const char* mention;
    };
    const Case cases[] = {
        {R"({"free": true, "position": [0, 1, 3.5], "znear": 1e-7})", "depth buffer cannot resolve"},
        {R"({"free": true, "position": [0, 1, 3.5], "znear": 1e-30})", "depth buffer cannot resolve"},
        // A valid znear last: the key the old message named was the last one read.
        {R"({"distance": -1, "znear": 0.01})", "camera.distance"},
        {R"({"pitch": 3, "znear": 0.01})", "camera.pitch"},
        {R"({"yfov": 4, "znear": 0.01})", "camera.yfov"},
        {R"({"scene_camera": -1, "znear": 0.01})", "camera.scene_camera"},
    };
    for (const Case& c : cases) {
        spit(dir + "/s.json", std::string(R"({"scene": "builtin:cornell", "camera": )") + c.camera + "}");
        const gis::test::CliResult r =
            runCli("render --settings " + quoted(dir + "/s.json") + " --size 16x16 --out " + quoted(dir + "/x.png"));
        EXPECT_EQ(r.status, 1) << c.camera;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(c.mention), std::string::npos) << c.camera << ": " << r.err;
        if (std::string(c.mention) != "camera.znear") {
            EXPECT_EQ(r.err.find("camera.znear"), std::string::npos) << r.err;
        }
        EXPECT_FALSE(fs::exists(dir + "/x.png")) << c.camera;
    }
}

// What the panel or a script accepts saves and loads again: values whose saved form the loader
// refuses (a light intensity of 3e38) or that overflow when applied (two camera moves of 3e38:
// the position became inf, saved as null) are refused when set, and the state stays as it was.
TEST(Hardening, WhatIsAcceptedWhenSetSavesAndLoadsAgain) {
    const std::string dir = tempDir("hardening_save_load");
    gis::view::ViewState s;
    const gis::Scene scene = gis::makeBuiltinScene("cornell");
    s.scene = "builtin:cornell";
    gis::view::resetCamera(s, scene, 0);
    gis::view::resetLights(s, scene.lights);
    for (const char* line : {"camera move 3e38 0 0", "camera move 3e38 0 0", "light 0 intensity 3e38",
                             "light 0 color 3e38 3e38 3e38"}) {
        const gis::view::PanelAction a = gis::view::parsePanelAction(gis::view::splitWords(line));
        EXPECT_THROW(gis::view::applyPanelAction(s, a), gis::Error) << line;
    }
    gis::view::saveViewSettings(dir + "/s.json", s);
    gis::view::ViewState loaded;
    EXPECT_NO_THROW(loaded = gis::view::loadViewSettings(dir + "/s.json")) << slurp(dir + "/s.json");
    EXPECT_EQ(loaded.camera.position, s.camera.position);
}

// Scripts take numbers as settings files write them: 0x10, +5, inf and .5 are refused with the
// word named (strtod read them silently), and a UTF-8 byte order mark is accepted as in settings.
TEST(Hardening, ScriptNumbersAreStrictAndABomIsAccepted) {
    for (const char* bad : {"exposure 0x1", "exposure +5", "exposure .5", "exposure 1e", "wait 0x10", "exposure nan"}) {
        try {
            gis::view::parseScript(std::string(bad) + "\n", "s.txt");
            ADD_FAILURE() << bad << " was accepted";
        } catch (const gis::Error& e) {
            EXPECT_NE(std::string(e.what()).find("is not a number"), std::string::npos) << e.what();
        }
    }
    for (const char* good : {"exposure 1.5", "exposure -2", "exposure 1e-1", "wait 3"})
        EXPECT_NO_THROW(gis::view::parseScript(std::string(good) + "\n", "s.txt")) << good;
    EXPECT_EQ(gis::view::parseScript("\xEF\xBB\xBFwait 2\nquit\n", "bom.txt").size(), 2u);
}

// The voxel view at a coarse level shows the walls: a one-voxel-thick wall never reached the fixed
// occupancy 0.5 at level 2, and the view of the Cornell box was all black. The albedo grid has no
// coarser level: asking for one is refused, not a black image.
TEST(Hardening, CoarseVoxelViewShowsThinWalls) {
    const std::string dir = tempDir("hardening_voxels");
    const std::string view = "render --scene builtin:cornell --gi vct --view vct.voxels --set vct.debug-level=2 --size 32x32 ";
    const gis::test::CliResult albedo = runCli(view + "--out " + quoted(dir + "/a.exr"));
    EXPECT_EQ(albedo.status, 1);
    EXPECT_NE(albedo.err.find("exists at level 0 only"), std::string::npos) << albedo.err;
    const gis::test::CliResult r = runCli(view + "--set vct.debug-channel=occupancy --out " + quoted(dir + "/v.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    const gis::ImageF img = gis::readExr(dir + "/v.exr");
    size_t lit = 0;
    for (size_t i = 0; i < img.rgba.size(); i += 4) lit += img.rgba[i] + img.rgba[i + 1] + img.rgba[i + 2] > 0.0f;
    EXPECT_GT(lit, img.rgba.size() / 4 / 2) << "fewer than half the pixels show a voxel";
}

// A memory refusal's advice follows its largest part: a voxel volume does not shrink with --size
// (the message said "use a smaller --size" for vct.resolution=256 at 16x16).
TEST(Hardening, MemoryRefusalNamesWhatToLower) {
    const std::string dir = tempDir("hardening_memory");
    const gis::test::CliResult volume = runCli("render --scene builtin:cornell --gi vct --set vct.resolution=256 --size 16x16 --out " +
                                                   quoted(dir + "/a.png"),
                                               "GIS_MEMORY_BUDGET_MB=64");
    EXPECT_EQ(volume.status, 1);
    EXPECT_NE(volume.err.find("lower the settings that size VCT"), std::string::npos) << volume.err;
    EXPECT_EQ(volume.err.find("smaller --size"), std::string::npos) << volume.err;
    const gis::test::CliResult pixels =
        runCli("render --scene builtin:cornell --size 8192x8192 --out " + quoted(dir + "/b.png"), "GIS_MEMORY_BUDGET_MB=64");
    EXPECT_EQ(pixels.status, 1);
    EXPECT_NE(pixels.err.find("use a smaller --size"), std::string::npos) << pixels.err;
}

std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// `bench --merge` verifies the manifest it merges: a cell line whose method was edited with its id
// kept (it used to give a `cornell,ssao,low` row holding the `none` numbers), a line given twice
// (duplicate rows) and a removed reference line (`error: map::at`) are each refused by id, and the
// previous outputs stay as they were. `--plan` refuses a method named twice.
TEST(Hardening, MergeVerifiesEachLineAgainstItsIdAndRefusesDuplicates) {
    const std::string dir = tempDir("hardening_merge");
    const std::string out = dir + "/O";
    const gis::test::CliResult run = runCli("bench --scenes builtin:cornell --methods none --presets low --size 24x24 "
                                            "--frames 3 --warmup 1 --reference-spp 8 --out-dir " + quoted(out));
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string manifest = slurp(out + "/manifest.jsonl"), csv = slurp(out + "/bench.csv");
    ASSERT_EQ(runCli("bench --merge " + quoted(out)).status, 0);
    std::vector<std::string> lines;
    std::istringstream in(manifest);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_EQ(lines.size(), 2u);  // reference, cell
    const std::string cellId = nlohmann::json::parse(lines[1])["id"];
    const std::string refId = nlohmann::json::parse(lines[0])["id"];
    struct Case {
        std::string name, manifest, mention;
    };
    const Case cases[] = {
        {"method edited", replaceOnce(manifest, R"("method":"none")", R"("method":"ssao")"), cellId},
        {"line twice", manifest + lines[1] + "\n", "listed twice"},
        {"reference removed", lines[1] + "\n", "its reference " + refId + " is not in the manifest"},
        {"scene_name edited on the cell", lines[0] + "\n" + replaceOnce(lines[1], R"("scene_name":"cornell")", R"("scene_name":"other")") + "\n",
         "is not listed for scene other"},
    };
    for (const Case& c : cases) {
        spit(out + "/manifest.jsonl", c.manifest);
        const gis::test::CliResult r = runCli("bench --merge " + quoted(out));
        EXPECT_EQ(r.status, 1) << c.name;
        EXPECT_NE(r.err.find(c.mention), std::string::npos) << c.name << ": " << r.err;
        EXPECT_EQ(r.err.find("map::at"), std::string::npos) << c.name << ": " << r.err;
        EXPECT_TRUE(slurp(out + "/bench.csv") == csv) << c.name << ": the previous table was replaced";
    }
    // A merge that fails half way (a file-size limit that the first outputs fit under and a later
    // one does not) replaces none of the previous outputs and leaves no temporary.
    spit(out + "/manifest.jsonl", manifest);
    std::vector<std::string> outputs;
    for (const auto& e : fs::directory_iterator(out))
        if (e.is_regular_file() && e.path().filename() != "manifest.jsonl") {
            outputs.push_back(e.path().string());
            spit(e.path().string(), "previous " + e.path().filename().string());
        }
    ASSERT_GE(outputs.size(), 3u);
    bool refused = false;
    for (const char* limit : {"ulimit -f 4;", "ulimit -f 16;", "ulimit -f 64;"}) {
        const gis::test::CliResult r = runCli("bench --merge " + quoted(out), std::string(limit) + " MESA_SHADER_CACHE_DISABLE=true");
        if (r.status == 0) continue;
        refused = true;
        EXPECT_NE(r.err.find("File too large"), std::string::npos) << limit << r.err;
        for (const std::string& f : outputs)
            EXPECT_EQ(slurp(f), "previous " + fs::path(f).filename().string()) << limit << ": " << f << " was replaced";
        for (const auto& e : fs::recursive_directory_iterator(out))
            EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << "left " << e.path();
    }
    EXPECT_TRUE(refused) << "no limit stopped the merge";
    const gis::test::CliResult twice = runCli("bench --plan --scenes builtin:cornell --methods none,none --presets low");
    EXPECT_EQ(twice.status, 1);
    EXPECT_NE(twice.err.find("--methods names 'none' twice"), std::string::npos) << twice.err;
}

}  // namespace

namespace {

// A scene without triangles: the path tracer and the AO reference see the background, as the
// rasterized methods do, instead of refusing with "cannot build a BVH".
TEST(Hardening, RayTracersRenderAnEmptySceneAsTheBackground) {
    const std::string dir = tempDir("hardening_empty_scene");
    spit(dir + "/empty.gltf", R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0})");
    auto meanOf = [&](const std::string& gi) {
        const std::string out = dir + "/" + gi + ".exr";
        const auto r = runCli("render --scene " + dir + "/empty.gltf --gi " + gi +
                              " --background 0.2,0.4,0.8 --spp 4 --size 16x16 --out " + out);
        EXPECT_EQ(r.status, 0) << gi << ": " << r.err;
        std::vector<double> mean(3, 0.0);
        if (r.status != 0) return mean;
        const gis::ImageF img = gis::readExr(out);
        for (size_t i = 0; i < img.rgba.size(); i += 4)
            for (int c = 0; c < 3; ++c) mean[c] += img.rgba[i + c] / double(img.width * img.height);
        return mean;
    };
    const std::vector<double> none = meanOf("none"), traced = meanOf("pathtrace");
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(none[c], 0.1) << "the background is seen";
        EXPECT_NEAR(traced[c], none[c], 1e-3 * none[c]) << "channel " << c;
    }
    const std::vector<double> ao = meanOf("ao-reference");
    EXPECT_EQ(ao[0], 0.0) << "no surface: what the AO reference writes where a pixel sees the sky";
}

}  // namespace

namespace {

// vct.resolution's listed range ends where the voxel budget does: 512 was listed and always refused
// (its volume needs more than the 8 GiB cap in every form). The largest listed one fits with the
// default settings, twice it fits in none.
TEST(Hardening, VctResolutionListsOnlyWhatTheVoxelBudgetHolds) {
    const gis::ParamDesc* row = nullptr;
    for (const gis::ParamDesc& d : gis::vctParams().rows)
        if (d.key == "resolution") row = &d;
    ASSERT_NE(row, nullptr);
    const int largest = int(row->max);
    EXPECT_EQ(largest, gis::maxVctResolution());
    gis::VctSettings defaults;
    defaults.resolution = largest;
    gis::VolumeRequest r = gis::vctVolumeRequest(defaults);
    EXPECT_LE(gis::sceneVolumeBytes(r, r.cascades), gis::kVoxelBudgetBytes) << largest << "^3 with the defaults";
    gis::VctSettings smallest;
    smallest.resolution = 2 * largest;
    smallest.anisotropic = false;
    smallest.bounces = 1;
    r = gis::vctVolumeRequest(smallest);
    EXPECT_GT(gis::sceneVolumeBytes(r, r.cascades), gis::kVoxelBudgetBytes) << 2 * largest << "^3 in its smallest form";

    const auto list = runCli("methods vct");
    EXPECT_NE(list.out.find("[8, " + std::to_string(largest) + "]"), std::string::npos) << list.out;
    const std::string dir = tempDir("hardening_vct_range");
    const auto r2 = runCli("render --scene builtin:cornell --gi vct --set vct.resolution=" + std::to_string(2 * largest) +
                           " --size 8x8 --out " + dir + "/x.png");
    EXPECT_NE(r2.status, 0);
    EXPECT_NE(r2.err.find("out of range [8, " + std::to_string(largest) + "]"), std::string::npos) << r2.err;
}

// sdf.resolution is any whole number: its maximum is the largest whose volume in its smallest form
// (one cascade, one bounce) fits the budget. It listed [8, 512], and 512 was always refused.
TEST(Hardening, SdfResolutionListsOnlyWhatTheVoxelBudgetHolds) {
    const gis::ParamDesc* row = nullptr;
    for (const gis::ParamDesc& d : gis::sdfParams().rows)
        if (d.key == "resolution") row = &d;
    ASSERT_NE(row, nullptr);
    const int largest = int(row->max);
    EXPECT_EQ(largest, gis::maxSdfResolution());
    EXPECT_LT(largest, 512);
    gis::SdfGiSettings s;
    s.bounces = 1;
    s.resolution = largest;
    EXPECT_LE(gis::sceneVolumeBytes(gis::sdfVolumeRequest(s), 1), gis::kVoxelBudgetBytes) << largest;
    s.resolution = largest + 1;
    EXPECT_GT(gis::sceneVolumeBytes(gis::sdfVolumeRequest(s), 1), gis::kVoxelBudgetBytes) << largest + 1;

    const auto list = runCli("methods sdf");
    EXPECT_NE(list.out.find("[8, " + std::to_string(largest) + "]"), std::string::npos) << list.out;
    const std::string dir = tempDir("hardening_sdf_range");
    const auto r = runCli("render --scene builtin:cornell --gi sdf --set sdf.resolution=512 --size 8x8 --out " + dir + "/x.png");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("out of range [8, " + std::to_string(largest) + "]"), std::string::npos) << r.err;
}

// `bench --plan` refuses a scene named twice, as it refuses `--methods none,none` (issue 27:
// duplicates are refused at --plan): the same builtin, or one file by another spelling or through
// a symlink, planned every job twice under a second name (cornell-2), and the merge gave two rows
// of the same numbers.
TEST(Hardening, BenchPlanRefusesASceneNamedTwice) {
    const std::string dir = tempDir("bench_plan_scene_twice");
    ASSERT_EQ(runCli("export --scene builtin:cornell --out " + dir + "/a.gltf").status, 0);
    fs::create_symlink(dir + "/a.gltf", dir + "/link.gltf");
    const std::string plan =
        "bench --plan --methods none --presets low --size 8x8 --frames 2 --warmup 1 --reference-spp 1 --scenes ";
    for (const std::string& scenes : {std::string("builtin:cornell,builtin:cornell"), dir + "/a.gltf," + dir + "/./a.gltf",
                                      dir + "/a.gltf," + dir + "/link.gltf"}) {
        const gis::test::CliResult r = runCli(plan + scenes);
        EXPECT_EQ(r.status, 1) << scenes;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("--scenes names"), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
    const gis::test::CliResult two = runCli(plan + "builtin:cornell," + dir + "/a.gltf");
    EXPECT_EQ(two.status, 0) << two.err;
    EXPECT_EQ(countLines(two.out), 4) << two.out;  // a reference and a cell per scene
}

// --- Third round (issue 37): hostile environment maps, settings files, manifests and viewer outputs.

// A flat-RGBE Radiance file of one grey (1.0) texel repeated.
std::string greyHdr(const std::string& path, int width, int height) {
    std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
    for (int i = 0; i < width * height; ++i) s += "\x80\x80\x80\x81";
    spit(path, s);
    return path;
}

// A map wider than GL_MAX_TEXTURE_SIZE (16385x1 on llvmpipe) rendered every method with a black sky
// and exit 0 (glTexStorage2D's GL_INVALID_VALUE went unchecked): refused before upload, naming the limit.
TEST(Hardening, AMapPastTheTextureSizeLimitIsOneClearError) {
    gis::test::context();
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
    const std::string dir = tempDir("hardening_texture_limit");
    const std::string map = greyHdr(dir + "/wide.hdr", limit + 1, 1);
    const gis::test::CliResult r = runCli("render --scene builtin:cornell --size 8x8 --environment " + quoted(map) +
                                          " --out " + quoted(dir + "/out.png"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("GL_MAX_TEXTURE_SIZE"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::to_string(limit)), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out.png"));
}

// A FIFO given as a map, a settings file or a script's settings line hung the program; /dev/zero
// as settings was read without end. Each is refused at once, naming the file.
TEST(Hardening, InputsThatAreNotRegularFilesAreRefusedWithoutBlocking) {
    const std::string dir = tempDir("hardening_fifo");
    const std::string fifo = dir + "/fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    spit(dir + "/script.txt", "settings " + fifo + "\nquit\n");
    const std::string out = " --scene builtin:cornell --size 8x8 --out " + quoted(dir + "/o.png");
    for (const std::string& args : {"render --environment " + fifo + out, "render --settings " + fifo + out,
                                    "render --settings /dev/zero" + out, "view --script " + dir + "/script.txt"}) {
        SCOPED_TRACE(args);
        const gis::test::CliResult r = runCli(args, "timeout 20");
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
    }
}

// The memory refusal for a map advised lowering "the method's resolution".
TEST(Hardening, AMapPastTheMemoryBudgetAdvisesASmallerMap) {
    const std::string dir = tempDir("hardening_map_budget");
    const std::string map = greyHdr(dir + "/big.hdr", 1024, 512);
    const gis::test::CliResult r = runCli("render --scene builtin:cornell --size 8x8 --environment " + quoted(map) +
                                              " --out " + quoted(dir + "/o.png"),
                                          "GIS_MEMORY_BUDGET_MB=4");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("use a smaller environment map"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("resolution"), std::string::npos) << r.err;
}

// Security: a manifest's id was a path before it was checked: `"id": "../../PWNED"` made
// `bench --cell` create out/cells/../../PWNED.failed. Ids are checked when the manifest is read.
TEST(Hardening, ManifestIdsAreCheckedWhenRead) {
    const std::string dir = tempDir("hardening_manifest_id");
    const gis::test::CliResult plan = runCli("bench --plan --scenes builtin:cornell --methods none --presets low --size 8x8");
    ASSERT_EQ(plan.status, 0) << plan.err;
    const std::string id = nlohmann::json::parse(plan.out.substr(0, plan.out.find('\n')))["id"];
    spit(dir + "/m.jsonl", replaceOnce(plan.out, "\"" + id + "\"", "\"../../PWNED\""));
    fs::create_directories(dir + "/a/b");
    const gis::test::CliResult r = runCli("bench --manifest " + quoted(dir + "/m.jsonl") + " --out-dir " +
                                          quoted(dir + "/a/b/O") + " --cell ../../PWNED");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("m.jsonl:1"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'../../PWNED' is not a job id"), std::string::npos) << r.err;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find("PWNED"), std::string::npos) << "wrote " << e.path();
}

// A map edited after --plan was "settings resolve differently in this build"; a relative map path
// failed as "cannot read" from another directory. The plan records the map's absolute path and hash.
TEST(Hardening, BenchJobsKeepTheirMapAndNameItsEdit) {
    const std::string dir = tempDir("hardening_bench_map");
    greyHdr(dir + "/sky.hdr", 8, 4);
    const gis::test::CliResult plan = runCli("bench --plan --scenes builtin:cornell --methods none --presets low --size 8x8 "
                                             "--reference-spp 2 --environment sky.hdr",
                                             "cd " + quoted(dir) + " &&");
    ASSERT_EQ(plan.status, 0) << plan.err;
    spit(dir + "/m.jsonl", plan.out);
    const std::string refId = nlohmann::json::parse(plan.out.substr(0, plan.out.find('\n')))["id"];
    const std::string cell = "bench --manifest " + quoted(dir + "/m.jsonl") + " --out-dir " + quoted(dir + "/O") + " --cell " + refId;
    const gis::test::CliResult elsewhere = runCli(cell, "cd / &&");
    EXPECT_EQ(elsewhere.status, 0) << elsewhere.err;
    greyHdr(dir + "/sky.hdr", 8, 2);
    const gis::test::CliResult edited = runCli(cell + " --force");
    EXPECT_EQ(edited.status, 1) << edited.err;
    EXPECT_NE(edited.err.find("the environment map " + dir + "/sky.hdr changed"), std::string::npos) << edited.err;
}

// `--environment ""` silently meant no map.
TEST(Hardening, AnEmptyEnvironmentNameIsRefused) {
    const std::string dir = tempDir("hardening_empty_map");
    for (const std::string& cmd : {"render --scene builtin:cornell --size 8x8 --out " + quoted(dir + "/o.png"),
                                   std::string("bench --plan --scenes builtin:cornell --methods none")}) {
        SCOPED_TRACE(cmd);
        const gis::test::CliResult r = runCli(cmd + " --environment ''");
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_NE(r.err.find("--environment"), std::string::npos) << r.err;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
    }
}

// A settings integer above INT64_MAX wrapped (18446744073709551615 read as -1: "must be >= 0").
TEST(Hardening, SettingsIntegersPastInt64AreNamed) {
    const std::string dir = tempDir("hardening_int64");
    spit(dir + "/s.json", R"({"gisandbox_view_settings": 1, "camera": {"scene_camera": 18446744073709551615}})");
    const gis::test::CliResult r = runCli("render --settings " + quoted(dir + "/s.json") + " --size 8x8 --out " + quoted(dir + "/o.png"));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("18446744073709551615 is too large"), std::string::npos) << r.err;
}

// The viewer's save-settings and capture overwrote the open scene, the map or the running script
// (exit 0), and capture took any extension: refused before the window opens, nothing written.
TEST(Hardening, ViewerOutputsRefuseTheFilesTheViewerHasOpen) {
    const std::string dir = tempDir("hardening_view_outputs");
    ASSERT_EQ(runCli("export --scene builtin:cornell --out " + quoted(dir + "/s.gltf")).status, 0);
    const std::string map = greyHdr(dir + "/sky.hdr", 8, 4), script = dir + "/script.txt";
    const std::string scene = slurp(dir + "/s.gltf"), sky = slurp(map);
    for (const std::string& line : {"save-settings " + dir + "/s.gltf", "capture " + dir + "/sky.hdr",
                                    "save-settings " + script, "capture " + dir + "/shot.txt"}) {
        SCOPED_TRACE(line);
        spit(script, line + "\nquit\n");
        // Under a display, as a user runs it: before the check the window opened and the file was replaced.
        const gis::test::CliResult r = runCli("view --scene " + quoted(dir + "/s.gltf") + " --environment " + quoted(map) +
                                                  " --script " + quoted(script),
                                              "xvfb-run -a");
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_EQ(countLines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find("script.txt:1"), std::string::npos) << r.err;
        EXPECT_EQ(slurp(script), line + "\nquit\n");
    }
    EXPECT_TRUE(slurp(dir + "/s.gltf") == scene);
    EXPECT_TRUE(slurp(map) == sky);
    EXPECT_FALSE(fs::exists(dir + "/shot.txt"));
}

// Under `ulimit -v` of 300 to 700 MB Mesa's llvmpipe segfaulted inside shader compilation (exit 139,
// no message) or failed an allocation: a limit below the floor is refused before any GL.
TEST(Hardening, AnAddressSpaceLimitBelowTheFloorIsOneClearError) {
    const std::string dir = tempDir("hardening_ulimit_v");
    const gis::test::CliResult r = runCli("render --scene builtin:cornell --gi vct --size 8x8 --out " + quoted(dir + "/o.png"),
                                          "ulimit -v 700000;");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("ulimit -v"), std::string::npos) << r.err;
    EXPECT_EQ(countLines(r.err), 1) << r.err;
}

}  // namespace
