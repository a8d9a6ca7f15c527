// The command line as a user meets it: help, successful renders, and bad input that must end with
// one clear line on stderr, a non-zero exit status and no output file left behind.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>

#include "cli_util.h"
#include "image.h"

namespace gis::test {
namespace {

namespace fs = std::filesystem;

TEST(Cli, HelpListsSubcommandsAndDefaults) {
    CliResult r = runCli("--help");
    EXPECT_EQ(r.status, 0);
    for (const char* sub : {"render", "info", "shaders"}) EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
    r = runCli("render --help");
    EXPECT_EQ(r.status, 0);
    for (const char* flag : {"--scene", "--out", "--size", "--backend", "--camera", "--gi", "--diffuse", "--specular",
                             "--exposure", "--timings", "256x256", "auto", "lambert", "ggx"})
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

TEST(Cli, RendersPngAndExr) {
    const std::string dir = tempDir("cli_render");
    CliResult r = runCli("render --scene builtin:cornell --size 64x48 --out " + dir + "/a.png -v");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("wrote " + dir + "/a.png"), std::string::npos);
    EXPECT_NE(r.err.find("GL_RENDERER"), std::string::npos);
    EXPECT_NE(r.err.find("GL_VERSION"), std::string::npos);
    ImageU8 png = readPng(dir + "/a.png");
    EXPECT_EQ(png.width, 64);
    EXPECT_EQ(png.height, 48);

    r = runCli("render --scene builtin:cornell --size 64x48 --out " + dir + "/a.exr");
    ASSERT_EQ(r.status, 0) << r.err;
    ImageF exr = readExr(dir + "/a.exr");
    EXPECT_EQ(exr.width, 64);
    EXPECT_EQ(exr.height, 48);
    for (const std::string& f : {dir + "/a.png", dir + "/a.exr"}) EXPECT_TRUE(fileExists(f));
    size_t entries = std::distance(fs::directory_iterator(dir), fs::directory_iterator());
    EXPECT_EQ(entries, 2u) << "a temporary file was left behind";
}

TEST(Cli, TimingsListEveryPassWithMemory) {
    const std::string dir = tempDir("cli_timings");
    CliResult r = runCli("render --scene builtin:cornell --size 64x64 --out " + dir + "/t.png --timings --frames 4 --warmup 1");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* pass : {"shadows", "gbuffer", "lighting", "tonemap", "total"})
        EXPECT_TRUE(std::regex_search(r.out, std::regex(std::string("\\n") + pass + " +[0-9.]+"))) << pass << "\n" << r.out;
}

TEST(Cli, InfoReportsSceneAndGpuMemory) {
    CliResult r = runCli("info --scene builtin:cornell --json");
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["lights"], 1);
    EXPECT_GT(j["triangles"].get<int>(), 0);
    EXPECT_GT(j["gpu"]["bytes"]["gbuffer"].get<int64_t>(), 0);
    EXPECT_GT(j["gpu"]["bytes"]["shadows"].get<int64_t>(), 0);
    EXPECT_GT(j["gpu"]["bytes"]["scene"].get<int64_t>(), 0);
    // 256x256 G-buffer: depth 4 + base colour 4 + normal 8 + material 4 + emissive 8 bytes per pixel.
    EXPECT_EQ(j["gpu"]["bytes"]["gbuffer"].get<int64_t>(), 256 * 256 * 28);
}

// Bad input: one line on stderr that names the problem, non-zero status, no output file.
struct BadCase {
    const char* name;
    std::string args;
    const char* mustMention;
};

TEST(Cli, BadInputFailsCleanly) {
    const std::string dir = tempDir("cli_bad");
    {
        std::ofstream(dir + "/truncated.gltf") << R"({"asset": {"version": "2.0"}, "meshes": [)";
    }
    const std::string out = dir + "/out.png";
    const BadCase cases[] = {
        {"missing file", "render --scene " + dir + "/nope.gltf --out " + out, "nope.gltf"},
        {"truncated json", "render --scene " + dir + "/truncated.gltf --out " + out, "truncated.gltf"},
        {"unknown builtin", "render --scene builtin:nothing --out " + out, "nothing"},
        {"bad size", "render --scene builtin:cornell --size 0x10 --out " + out, "size"},
        {"garbage size", "render --scene builtin:cornell --size big --out " + out, "size"},
        {"huge size", "render --scene builtin:cornell --size 99999x2 --out " + out, "size"},
        {"bad extension", "render --scene builtin:cornell --out " + dir + "/out.jpg", ".png or .exr"},
        {"missing directory", "render --scene builtin:cornell --out " + dir + "/no/such/dir/x.png", "no/such/dir"},
        {"unknown gi", "render --scene builtin:cornell --gi magic --out " + out, "magic"},
        {"unknown brdf", "render --scene builtin:cornell --specular velvet --out " + out, "velvet"},
        {"unknown backend", "render --scene builtin:cornell --backend vulkan --out " + out, "vulkan"},
        {"bad camera", "render --scene builtin:cornell --camera 7 --out " + out, "camera 7"},
        {"absurd exposure", "render --scene builtin:cornell --exposure 1e9 --out " + out, "exposure"},
        {"negative ambient", "render --scene builtin:cornell --ambient -1 --out " + out, "ambient"},
        {"tiny shadow map", "render --scene builtin:cornell --shadow-size 2 --out " + out, "shadow map size"},
        {"no subcommand", "", "subcommand"},
    };
    for (const BadCase& c : cases) {
        CliResult r = runCli(c.args);
        EXPECT_NE(r.status, 0) << c.name;
        EXPECT_EQ(countLines(r.err), 1) << c.name << ": " << r.err;
        EXPECT_NE(r.err.find(c.mustMention), std::string::npos) << c.name << ": " << r.err;
        EXPECT_FALSE(fileExists(out)) << c.name;
    }
}

// A shader that fails to compile is reported with its own file name and line, and no image is written.
TEST(Cli, ShaderCompileErrorNamesFileAndLine) {
    const std::string dir = tempDir("cli_shader_error");
    fs::copy(fs::path(GIS_SOURCE_DIR) / "shaders", dir + "/shaders");
    const std::string broken = dir + "/shaders/brdf.glsl";
    std::vector<std::string> lines;
    {
        std::ifstream in(broken);
        for (std::string l; std::getline(in, l);) lines.push_back(l);
    }
    lines.insert(lines.begin() + 9, "float broken = undefined_symbol;");  // becomes line 10
    {
        std::ofstream o(broken);
        for (const auto& l : lines) o << l << "\n";
    }
    CliResult r = runCli("render --scene builtin:cornell --size 32x32 --out " + dir + "/x.png",
                         "GIS_SHADER_DIR='" + dir + "/shaders'");
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(countLines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("shaders/brdf.glsl:10"), std::string::npos) << r.err;
    EXPECT_FALSE(fileExists(dir + "/x.png"));

    r = runCli("render --scene builtin:cornell --size 32x32 --out " + dir + "/x.png", "GIS_SHADER_DIR=/nonexistent");
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("/nonexistent/"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gis::test
