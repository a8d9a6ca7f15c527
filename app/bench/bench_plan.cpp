#include "bench/bench_plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <unistd.h>

#include "cli/content_hash.h"
#include "environment.h"
#include "gi/method.h"
#include "metrics.h"
#include "cli/settings_io.h"
#include "cli/user_json.h"

namespace gis {

namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

constexpr int kReferenceBounces = 64;
constexpr int kReferenceSamplesPerFrame = 16;
constexpr int kAoReferenceSamplesPerFrame = 64;
constexpr size_t kIdHexDigits = 16;

glm::vec3 colourFlag(const std::vector<float>& v, const char* flag) {
    if (v.size() != 1 && v.size() != 3) throw Error(std::string(flag) + " takes one value or R,G,B");
    for (float x : v)
        if (!std::isfinite(x) || x < 0.0f) throw Error(std::string(flag) + " must be finite and non-negative");
    return v.size() == 3 ? glm::vec3(v[0], v[1], v[2]) : glm::vec3(v[0]);
}

// Results are named by the scene's file stem (or builtin name), made unique within the run: two
// files whose glTF scene is called "Scene" no longer overwrite each other's chart and rows.
std::vector<std::string> uniqueSceneNames(const std::vector<std::string>& specs) {
    std::vector<std::string> names;
    for (const std::string& spec : specs) {
        std::string base = spec.rfind("builtin:", 0) == 0 ? spec.substr(8) : fs::path(spec).stem().string();
        if (base.empty()) base = "scene";
        std::string name = base;
        for (int k = 2; std::find(names.begin(), names.end(), name) != names.end(); ++k) name = base + "-" + std::to_string(k);
        names.push_back(name);
    }
    return names;
}

// --emitters as a list (bench only): the modes each cell is measured in, "" for none given.
std::vector<std::string> emitterModes(const std::string& flag) {
    std::vector<std::string> modes;
    std::stringstream in(flag);
    for (std::string mode; std::getline(in, mode, ',');) {
        if (mode.empty() || std::find(modes.begin(), modes.end(), mode) != modes.end())
            throw Error("--emitters '" + flag + "': each mode once, comma-separated (lights, gi, off)");
        modes.push_back(mode);
    }
    if (!flag.empty() && flag.back() == ',')
        throw Error("--emitters '" + flag + "': each mode once, comma-separated (lights, gi, off)");
    if (modes.empty()) modes.push_back("");
    return modes;
}

// The methods measured: --methods, else every benchmarked one; each must score against radiance.
std::vector<std::string> selectMethods(const BenchOptions& o) {
    std::vector<std::string> methods = o.methods;
    if (methods.empty())
        for (const GiMethod& m : giMethods())
            if (m.benchmarked) methods.push_back(m.name);
    for (const std::string& m : methods) {
        const GiMethod& method = giMethod(m);
        if (method.image != MethodImage::Radiance)
            throw Error("--methods " + m + ": its image is not radiance, so it cannot be scored against the "
                        "path-traced reference (it is the AO reference itself)");
        for (const std::string& p : o.presets) method.preset(p);  // validates the name
    }
    return methods;
}

void validateFlags(const BenchOptions& o) {
    RenderSettings s;
    parseRenderSize(o.size, s.width, s.height);
    if (o.frames < 1 || o.frames > 100000) throw Error("--frames must be in [1, 100000]");
    if (o.flythrough < 0 || o.flythrough > 100000)
        throw Error("--flythrough=N must be in [0, 100000] (0: a still camera)");
    if (o.warmup < 0 || o.warmup >= o.frames)
        throw Error("--warmup " + std::to_string(o.warmup) + " must be in [0, --frames " + std::to_string(o.frames) +
                    ") (the default warm-up is 5 frames: with fewer --frames, lower --warmup too)");
    if (!o.ambient.empty()) colourFlag(o.ambient, "--ambient");
    if (!o.background.empty()) colourFlag(o.background, "--background");
    if (!o.environment.empty()) {  // the render's own checks, before any job runs
        checkEnvironmentChoice(!o.background.empty(), o.environment, !o.ambient.empty());
        loadEnvironmentMap(o.environment);
    }
    checkEnvironmentRotation(o.environmentRotation, o.environment);
    cameraRequest(o.setup);  // validates the camera flags before any work
    parseLightingMode(o.setup.lighting);
    if (o.referenceSpp < 1 || o.referenceSpp > (1 << 20)) throw Error("--reference-spp must be in [1, 1048576]");
    parseErrorMetric(o.metric);
    if (o.scenes.empty()) throw Error("--scenes needs at least one scene");
    if (o.presets.empty()) throw Error("--presets needs at least one preset");
    // A name given twice would plan two lines with one id: a sweep that runs and counts a cell twice.
    for (const auto& [flag, list] : {std::pair<const char*, const std::vector<std::string>&>{"--methods", o.methods},
                                     {"--presets", o.presets}})
        for (size_t i = 0; i < list.size(); ++i)
            if (std::find(list.begin(), list.begin() + long(i), list[i]) != list.begin() + long(i))
                throw Error(std::string(flag) + " names '" + list[i] + "' twice");
    // A scene given twice (`builtin:cornell,builtin:cornell`, or one file as `a.gltf,./a.gltf`) planned
    // every job twice under a second name (cornell-2) and merged into duplicate rows.
    for (size_t i = 0; i < o.scenes.size(); ++i)
        for (size_t k = 0; k < i; ++k) {
            std::error_code ec;
            const bool sameSpec = o.scenes[i] == o.scenes[k];
            if (sameSpec || (o.scenes[i].rfind("builtin:", 0) != 0 && fs::equivalent(o.scenes[i], o.scenes[k], ec)))
                throw Error("--scenes names '" + o.scenes[i] + "' twice" +
                            (sameSpec ? std::string() : " (it is the file '" + o.scenes[k] + "')"));
        }
}

// A .gltf names its buffers and images by URI; their bytes are the scene as much as its own.
void hashGltfResources(const std::string& path, Sha256& h) {
    std::ifstream in(path);
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return;  // the loader already accepted it; nothing more to add
    for (const char* list : {"buffers", "images"}) {
        if (!j.contains(list) || !j[list].is_array()) continue;
        for (const auto& entry : j[list]) {
            if (!entry.contains("uri") || !entry["uri"].is_string()) continue;
            const std::string uri = entry["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;  // embedded: already in the file's bytes
            const fs::path file = fs::path(path).parent_path() / uri;
            h.update("|" + uri + "|");
            if (fs::is_regular_file(file)) h.updateFile(file.string());
        }
    }
}

std::string vecText(const glm::vec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z}).dump();
}

}  // namespace

std::string sceneDigest(const std::string& spec, const Scene& loaded) {
    Sha256 h;
    if (spec.rfind("builtin:", 0) != 0) {
        h.update("file|");
        h.updateFile(spec);
        if (fs::path(spec).extension() == ".gltf") hashGltfResources(spec, h);
        return h.hex();
    }
    // A builtin has no file: hash what its generator makes, serialized as glTF in memory (and the
    // sky, which glTF cannot hold). In memory, not through a temporary export: nothing another
    // user could pre-create or redirect, and no failed write that could change the id.
    const GltfBytes bytes = serializeGltf(loaded, "scene.bin");
    h.update("builtin|" + spec + "|sky" + vecText(loaded.background) + "|");
    h.update(bytes.json);
    h.update(bytes.bin);
    return h.hex();
}

PreparedScene prepareBenchScene(const BenchJob& job) {
    PreparedScene p;
    parseRenderSize(job.size, p.base.width, p.base.height);
    if (!job.ambient.empty()) p.base.ambient = colourFlag(job.ambient, "--ambient");
    if (!job.background.empty()) p.base.background = colourFlag(job.background, "--background");
    if (!job.background.empty() && job.ambient.empty()) p.base.ambient = *p.base.background;  // as render does
    p.base.environment = job.environment;
    p.base.environmentRotation = job.environmentRotation;
    p.scene = loadScene(job.scene);
    p.sha256 = sceneDigest(job.scene, p.scene);
    p.base.camera = prepareScene(p.scene, job.setup, float(p.base.width) / float(p.base.height), &p.base,
                                 !job.ambient.empty() || !job.background.empty());
    return p;
}

RenderSettings jobSettings(const BenchJob& job, const RenderSettings& sceneBase) {
    RenderSettings s = sceneBase;
    if (job.kind == JobKind::Cell) {
        // A scene's base is prepared once for all its cells; --emitters A,B gives cells their own mode.
        if (!job.setup.emitters.empty()) setParam(s, "emitters.mode", job.setup.emitters);
        applyPreset(s, job.method, job.preset);
        // A cell measures what a first run pays: a method's disk cache of finished work (the
        // lightmap's bake, row "cache") would make its cut and its light edit a file read.
        for (const ParamDesc& p : giMethod(job.method).params)
            if (p.key == "cache") setParam(s, job.method + "." + p.key, "false");
    } else if (job.method == methodInRole(MethodRole::Reference).name) {
        s.gi = job.method;
        setParam(s, roleParamKey(MethodRole::Reference, "spp"), std::to_string(job.referenceSpp));
        setParam(s, roleParamKey(MethodRole::Reference, "bounces"), std::to_string(kReferenceBounces));
        s.samplesPerFrame = kReferenceSamplesPerFrame;
    } else {
        s.gi = methodInRole(MethodRole::AoReference).name;
        setParam(s, roleParamKey(MethodRole::AoReference, "spp"), std::to_string(job.referenceSpp));
        s.samplesPerFrame = kAoReferenceSamplesPerFrame;
    }
    return s;
}

std::string environmentSha256(const std::string& path) {
    Sha256 h;
    h.updateFile(path);
    return h.hex();
}

std::string contentId(const BenchJob& job, const RenderSettings& settings) {
    ojson key{{"version", kBenchIdVersion},
              {"kind", job.kind == JobKind::Cell ? "cell" : "reference"},
              {"method", job.method},
              {"preset", job.preset},
              {"scene_sha256", job.sceneSha256},
              {"lighting", job.setup.lighting},
              {"camera", job.setup.camera},
              {"camera_pos", job.setup.cameraPos},
              {"look_at", job.setup.lookAt},
              {"fov", job.setup.fov},
              {"settings", view::renderSettingsToJson(settings)}};
    if (job.flythrough) key["flythrough"] = true;  // only then: the ids of still-camera jobs stay as they were
    // The settings' JSON holds the method's parameters, not the shared emitters.* table: without
    // this a cell's --emitters gi and lights results would share one id (and one cache entry).
    if (!job.setup.emitters.empty()) key["emitters"] = job.setup.emitters;
    // The map's bytes, not only its name: an edited file is another environment (and reference).
    // And how they are mapped: a reference cached before the map meant what Blender's does (its
    // centre column looked down -Z then) is another sky. (The rotation is in the settings' JSON.)
    if (!job.environment.empty()) {
        key["environment_sha256"] = environmentSha256(job.environment);
        key["environment_mapping"] = "blender";
    }
    if (job.kind == JobKind::Cell) {
        key["measures"] = kCellMeasuresVersion;
        key["frames"] = job.frames;
        key["warmup"] = job.warmup;
        key["reference"] = job.reference;
        key["ao_reference"] = job.aoReference;
    }
    return sha256Hex(key.dump()).substr(0, kIdHexDigits);
}

std::vector<BenchJob> planBench(const BenchOptions& o) {
    validateFlags(o);
    const std::vector<std::string> methods = selectMethods(o);
    const bool wantsAo = std::any_of(methods.begin(), methods.end(),
                                     [](const std::string& m) { return giMethod(m).scoredAgainstAo; });
    const std::vector<std::string> names = uniqueSceneNames(o.scenes);
    const std::vector<std::string> modes = emitterModes(o.setup.emitters);
    std::vector<BenchJob> references, cells;
    for (size_t si = 0; si < o.scenes.size(); ++si) {
        BenchJob common;
        common.scene = o.scenes[si];
        common.sceneName = names[si];
        common.size = o.size;
        common.setup = o.setup;
        common.setup.emitters = modes.front();  // the references' (the path tracer reads no mode)
        common.ambient = o.ambient;
        common.background = o.background;
        // Absolute: a cell may run from another directory than the plan's.
        if (!o.environment.empty()) {
            common.environment = std::filesystem::absolute(o.environment).lexically_normal().string();
            common.environmentSha256 = environmentSha256(common.environment);
        }
        common.environmentRotation = o.environmentRotation;
        common.referenceSpp = o.referenceSpp;
        const PreparedScene prepared = prepareBenchScene(common);  // fails early on a bad scene
        common.sceneSha256 = prepared.sha256;
        auto add = [&](std::vector<BenchJob>& to, JobKind kind, const std::string& method, const std::string& preset) {
            BenchJob job = common;
            job.kind = kind;
            job.method = method;
            job.preset = preset;
            to.push_back(job);
            to.back().id = contentId(to.back(), jobSettings(to.back(), prepared.base));
            return to.back().id;
        };
        // A fly-through's frames have no reference (each is a new view): its cells need none.
        const bool fly = o.flythrough > 0;
        const std::string reference =
            fly ? "" : add(references, JobKind::Reference, methodInRole(MethodRole::Reference).name, "");
        const std::string aoReference =
            wantsAo && !fly ? add(references, JobKind::Reference, methodInRole(MethodRole::AoReference).name, "") : "";
        common.frames = fly ? o.flythrough : o.frames;
        common.warmup = fly ? 0 : o.warmup;
        common.flythrough = fly;
        common.reference = reference;
        // --emitters lights,gi: every cell once per mode, scored against the same reference.
        for (const std::string& emitters : modes) {
            common.setup.emitters = emitters;
            for (const std::string& method : methods) {
                common.aoReference = giMethod(method).scoredAgainstAo ? aoReference : "";
                for (const std::string& preset : o.presets) add(cells, JobKind::Cell, method, preset);
            }
        }
    }
    references.insert(references.end(), cells.begin(), cells.end());
    return references;
}

ojson jobToJson(const BenchJob& job) {
    ojson j{{"id", job.id}, {"kind", job.kind == JobKind::Cell ? "cell" : "reference"}};
    j["scene"] = job.scene;
    j["scene_name"] = job.sceneName;
    j["scene_sha256"] = job.sceneSha256;
    j["method"] = job.method;
    if (job.kind == JobKind::Cell) j["preset"] = job.preset;
    j["size"] = job.size;
    j["lighting"] = job.setup.lighting;
    j["camera"] = job.setup.camera;
    j["camera_pos"] = job.setup.cameraPos;
    j["look_at"] = job.setup.lookAt;
    j["fov"] = job.setup.fov;
    if (!job.setup.emitters.empty()) j["emitters"] = job.setup.emitters;
    j["ambient"] = job.ambient;
    j["background"] = job.background;
    if (!job.environment.empty()) {
        j["environment"] = job.environment;
        j["environment_sha256"] = job.environmentSha256;
        if (job.environmentRotation != 0.0f) j["environment_rotation"] = job.environmentRotation;
    }
    j["reference_spp"] = job.referenceSpp;
    if (job.kind == JobKind::Cell) {
        j["frames"] = job.frames;
        j["warmup"] = job.warmup;
        j["reference"] = job.reference;
        if (!job.aoReference.empty()) j["ao_reference"] = job.aoReference;
        if (job.flythrough) j["flythrough"] = true;
    }
    return j;
}

BenchJob jobFromJson(const nlohmann::json& j) {
    BenchJob job;
    try {
        job.id = j.at("id").get<std::string>();
        // The id names the job's files (cells/ID.json, ID.failed): a path there would write anywhere.
        if (job.id.size() != kIdHexDigits || job.id.find_first_not_of("0123456789abcdef") != std::string::npos)
            throw Error("'" + job.id + "' is not a job id (" + std::to_string(kIdHexDigits) + " hexadecimal digits)");
        const std::string kind = j.at("kind").get<std::string>();
        if (kind != "cell" && kind != "reference") throw Error("kind '" + kind + "' is not cell or reference");
        job.kind = kind == "cell" ? JobKind::Cell : JobKind::Reference;
        job.scene = j.at("scene").get<std::string>();
        job.sceneName = j.at("scene_name").get<std::string>();
        job.sceneSha256 = j.at("scene_sha256").get<std::string>();
        job.method = j.at("method").get<std::string>();
        job.size = j.at("size").get<std::string>();
        job.setup.lighting = j.at("lighting").get<std::string>();
        job.setup.camera = j.at("camera").get<std::string>();
        job.setup.cameraPos = j.at("camera_pos").get<std::vector<float>>();
        job.setup.lookAt = j.at("look_at").get<std::vector<float>>();
        job.setup.fov = j.at("fov").get<float>();
        job.setup.emitters = j.value("emitters", std::string());
        job.ambient = j.at("ambient").get<std::vector<float>>();
        job.background = j.at("background").get<std::vector<float>>();
        job.environment = j.value("environment", std::string());
        job.environmentSha256 = j.value("environment_sha256", std::string());
        job.environmentRotation = j.value("environment_rotation", 0.0f);
        job.referenceSpp = j.at("reference_spp").get<int>();
        if (job.kind == JobKind::Cell) {
            job.preset = j.at("preset").get<std::string>();
            job.frames = j.at("frames").get<int>();
            job.warmup = j.at("warmup").get<int>();
            job.reference = j.at("reference").get<std::string>();
            job.aoReference = j.value("ao_reference", std::string());
            job.flythrough = j.value("flythrough", false);
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(std::string("not a bench job: ") + e.what());
    }
    return job;
}

void writeManifest(std::ostream& out, const std::vector<BenchJob>& jobs) {
    for (const BenchJob& job : jobs) out << jobToJson(job).dump() << "\n";
}

std::vector<BenchJob> readManifest(const std::string& path) {
    if (path.empty()) throw Error("--manifest FILE is needed (the output of bench --plan)");
    std::ifstream in(path);
    if (!in) throw Error("--manifest '" + path + "': cannot read");
    std::vector<BenchJob> jobs;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        try {
            const nlohmann::json j = parseUserJson(line);
            jobs.push_back(jobFromJson(j));
        } catch (const std::exception& e) {
            throw Error(path + ":" + std::to_string(number) + ": " + e.what());
        }
    }
    if (jobs.empty()) throw Error("--manifest '" + path + "' has no jobs");
    return jobs;
}

const BenchJob& findJob(const std::vector<BenchJob>& jobs, const std::string& id, const std::string& manifest) {
    for (const BenchJob& job : jobs)
        if (job.id == id) return job;
    throw Error("--cell " + id + ": no such id in " + manifest);
}

}  // namespace gis
