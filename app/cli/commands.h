#pragma once

#include <functional>
#include <map>
#include <string>

#include "gl/context.h"
#include "renderer.h"
#include "cli/scene_setup_options.h"

namespace CLI { class App; }

namespace gis {

struct RenderOptions {
    std::string scene;
    std::string out;
    std::string size = "256x256";
    int supersample = 1;                 // --supersample N: rendered at N x the size, box-filtered down
    std::string backend = "auto";
    SceneSetupOptions setup;             // --lighting, --camera, --camera-pos, --look-at, --fov
    std::string gi = kDefaultGiMethod;
    std::string diffuse = "lambert";
    std::string specular = "ggx";
    std::string tonemap = "aces";
    float exposure = 0.0f;
    std::vector<float> ambient{0.03f};
    int shadowSize = 1024;
    int shadowCubeSize = 512;
    bool noShadows = false;
    bool hdr32 = false;
    bool timings = false;
    bool rerunSettled = false;   // --rerun-settled: execute every pass every frame (frame-cost measurements)
    int frames = 30;
    int warmup = 5;
    int flythrough = 0;                  // --flythrough[=N]: N frames of the scripted camera path; 0: still camera
    std::vector<float> background;
    std::string environment;                 // --environment FILE.hdr
    float environmentRotation = 0.0f;        // --environment-rotation DEG
    std::string preset;                      // --preset low|medium|high: the method's preset
    std::vector<std::string> sets;           // --set METHOD.KEY=VALUE, in order
    std::map<std::string, std::string> aliases;  // older flags of parameter rows: --spp, --ao-samples ...
    std::map<std::string, bool> aliasFlags;      // boolean ones: --ao-half-res, --ao-temporal
    std::string view = "final";
    bool glDebug = false;
    bool verbose = false;
    // --settings FILE (a `gisandbox view` settings file): pane --pane of it, rendered as the view
    // renders it; flags given on the command line override what the file says.
    std::string settings;
    int pane = 0;
    std::function<bool(const std::string& flag)> given;  // was the flag on the command line?
};

struct InfoOptions {
    std::string scene;
    std::string gi = kDefaultGiMethod;
    std::string preset;
    std::string size = "256x256";
    std::string backend = "auto";
    int camera = 0;
    bool json = false;
    bool noGpu = false;
};

struct MethodsOptions {
    std::string method;   // empty: list every method
    bool json = false;
};

struct ExportOptions {
    std::string scene;
    std::string out;   // .gltf (a .bin is written beside it)
};
void addExportOptions(CLI::App& cmd, ExportOptions& o);
int runExport(const ExportOptions& o);

struct ShaderDumpOptions {
    std::string dir;
};

struct BenchOptions {
    std::vector<std::string> scenes{"builtin:cornell", "builtin:cornell-area"};
    std::string size = "128x128";
    int frames = 20;
    int warmup = 5;
    std::vector<std::string> methods;
    std::vector<std::string> presets{"low", "medium", "high"};
    int referenceSpp = 512;
    std::string metric = "flip";
    std::string outDir = "bench";
    std::string cacheDir;
    std::string backend = "auto";
    SceneSetupOptions setup;
    std::vector<float> ambient;
    std::vector<float> background;
    std::string environment;          // --environment FILE.hdr, for every cell and the reference
    float environmentRotation = 0.0f; // --environment-rotation DEG
    int flythrough = 0;               // --flythrough[=N]: each cell flies N frames of the scripted path, unscored
    bool useCurrentContext = false;   // in-process callers (tests) that hold a current GL context
    // A sweep spread over processes (app/bench_command.cpp): --plan prints the jobs, --cell ID
    // runs one of --manifest, --merge DIR gathers their results, --ids KIND lists job ids.
    bool plan = false;
    std::string cell, manifest, merge, ids;
    bool force = false;
};

// "WxH" -> width, height; throws gis::Error naming the flag value.
void parseRenderSize(const std::string& text, int& width, int& height);

void addBenchOptions(CLI::App& cmd, BenchOptions& o);
int runBench(const BenchOptions& o);

struct DiffOptions {  // app/diff_command.cpp
    std::string test, reference;
    std::string heatmap;
    std::string metric = "flip";
    std::string tonemap = "auto";
    float exposure = 0.0f;
    double ppd = 67.0;
    double heatmapMax = 0.0;  // 0: 1 for flip and ssim, the map's maximum for rmse and relmse
    std::string mask;
    bool colorBar = false;
    bool json = false;
};

// gisandbox view: the interactive sandbox (app/view_app.cpp).
struct ViewOptions {
    std::string scene = "builtin:cornell";
    std::string settings;
    std::string size = "1280x720";       // window
    std::string script;
    std::string screenshotDir = "screenshots";
    std::string frameLog;                // --frame-log FILE: a line per window frame
    std::string environment;             // --environment FILE.hdr
    float environmentRotation = 0.0f;    // --environment-rotation DEG
    SceneSetupOptions setup;
    bool glDebug = false;
    bool verbose = false;
    std::function<bool(const std::string& flag)> given;
};
void addViewOptions(CLI::App& cmd, ViewOptions& o);
int runView(const ViewOptions& o);

void addRenderOptions(CLI::App& cmd, RenderOptions& o);
// --environment FILE.hdr and --environment-rotation DEG, as render, bench and view take them: an
// empty name is refused (it meant no map); the rotation is checked with the settings
// (checkEnvironmentRotation), where the map is known.
void addEnvironmentOptions(CLI::App& cmd, std::string& path, float& rotationDegrees);
void addInfoOptions(CLI::App& cmd, InfoOptions& o);
void addShaderDumpOptions(CLI::App& cmd, ShaderDumpOptions& o);
void addMethodsOptions(CLI::App& cmd, MethodsOptions& o);
int runMethods(const MethodsOptions& o);
void addDiffOptions(CLI::App& cmd, DiffOptions& o);

int runRender(const RenderOptions& o);
int runInfo(const InfoOptions& o);
int runShaderDump(const ShaderDumpOptions& o);
int runDiff(const DiffOptions& o);

}  // namespace gis
