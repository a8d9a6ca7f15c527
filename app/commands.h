#pragma once

#include <string>

#include "gl/context.h"
#include "renderer.h"

namespace CLI { class App; }

namespace gis {

struct RenderOptions {
    std::string scene;
    std::string out;
    std::string size = "256x256";
    std::string backend = "auto";
    int camera = 0;
    std::string gi = "none";
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
    int frames = 30;
    int warmup = 5;
    std::vector<float> background;
    int spp = 64;
    int maxBounces = 16;
    bool glDebug = false;
    bool verbose = false;
};

struct InfoOptions {
    std::string scene;
    std::string size = "256x256";
    std::string backend = "auto";
    bool json = false;
    bool noGpu = false;
};

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
};

// "WxH" -> width, height; throws gis::Error naming the flag value.
void parseRenderSize(const std::string& text, int& width, int& height);

void addBenchOptions(CLI::App& cmd, BenchOptions& o);
int runBench(const BenchOptions& o);

void addRenderOptions(CLI::App& cmd, RenderOptions& o);
void addInfoOptions(CLI::App& cmd, InfoOptions& o);
void addShaderDumpOptions(CLI::App& cmd, ShaderDumpOptions& o);

int runRender(const RenderOptions& o);
int runInfo(const InfoOptions& o);
int runShaderDump(const ShaderDumpOptions& o);

}  // namespace gis
