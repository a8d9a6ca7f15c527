// The plan of a benchmark sweep: every job `gisandbox bench` runs, as data. A job is a reference
// render (per scene: the path-traced reference, and ray-traced AO when SSAO is measured) or a cell
// (a method at a preset on a scene, scored against its references). Each has a content id: the
// SHA-256 of everything that decides its result (see contentId), so results are named, cached and
// shared by id, and a job whose inputs did not change is never run twice.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "renderer.h"
#include "scene/scene.h"

namespace gis {

// Bumped when what a job's id covers changes meaning (not when a scene or setting changes: those
// change the id by themselves).
constexpr int kBenchIdVersion = 1;
// What a cell measures (part of cell ids only, so cached references keep theirs): 2 = the steady
// frame, convergence after a cut and a light edit, and the time-to-quality curve; 3 = the frame
// from which the image stopped changing, measured.
constexpr int kCellMeasuresVersion = 3;

enum class JobKind { Reference, Cell };

struct BenchJob {
    std::string id;
    JobKind kind = JobKind::Cell;
    std::string scene;         // the spec as given: a glTF path or builtin:NAME[?options]
    std::string sceneName;     // unique within the plan: the file stem or builtin name
    std::string sceneSha256;   // sceneDigest
    std::string method;        // references: the method in the Reference or AoReference role
    std::string preset;        // cells
    std::string size;          // WxH
    SceneSetupOptions setup;
    std::vector<float> ambient, background;   // as given (empty: not given)
    std::string environment;                  // --environment FILE.hdr, absolute (empty: none)
    std::string environmentSha256;            // the map's bytes at --plan: an edit since is named
    float environmentRotation = 0.0f;         // --environment-rotation DEG
    int referenceSpp = 0;
    int frames = 0, warmup = 0;               // cells; with flythrough, frames is the path's, warmup 0
    bool flythrough = false;                  // cells: fly the scripted camera path, scored against nothing
    std::string reference, aoReference;       // cells: the ids of the references they are scored against
};

// A scene made ready the way every job of it renders: loaded, lit and framed per the setup flags,
// with the settings every method starts from.
struct PreparedScene {
    Scene scene;
    RenderSettings base;
    std::string sha256;
};
PreparedScene prepareBenchScene(const BenchJob& job);

// The settings a job renders with, from its scene's base settings.
RenderSettings jobSettings(const BenchJob& job, const RenderSettings& sceneBase);

// The SHA-256 of the scene's content: a file's bytes (for .gltf, also the external buffers and
// images it names); a builtin's spec, generated geometry as exported glTF and sky, so a change to
// a builtin generator changes its ids too. `loaded` is the scene as loaded, before lighting.
std::string sceneDigest(const std::string& spec, const Scene& loaded);

// kBenchIdVersion, kind, method, preset, the scene digest, the lighting and camera flags, every
// field of the resolved RenderSettings with every parameter of the method (defaults included, so
// a changed preset or default changes the ids it touches), frames and warm-up, and the ids of
// the references a cell is scored against. Not the scene's path or name: a renamed or moved file
// keeps its ids. Hex, 16 digits (64 bits).
std::string contentId(const BenchJob& job, const RenderSettings& settings);
// SHA-256 of a map's bytes, as the id holds it.
std::string environmentSha256(const std::string& path);

// Validates the selection flags (one message each) and returns the jobs: per scene its references,
// then its cells; all references come before all cells.
std::vector<BenchJob> planBench(const BenchOptions& o);

nlohmann::ordered_json jobToJson(const BenchJob& job);
BenchJob jobFromJson(const nlohmann::json& json);  // throws gis::Error naming the field
void writeManifest(std::ostream& out, const std::vector<BenchJob>& jobs);  // JSON Lines
std::vector<BenchJob> readManifest(const std::string& path);  // throws gis::Error naming file and line
const BenchJob& findJob(const std::vector<BenchJob>& jobs, const std::string& id, const std::string& manifest);

}  // namespace gis
