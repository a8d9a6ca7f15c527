// A GI method as the rest of the app sees it: its name, its parameter rows, its presets, how it
// fits the frame and the passes it adds. Every method lives in renderer/gi/<method>/ and is listed
// once in renderer/gi/methods.cpp; the CLI, settings files, viewer panel, bench and `gisandbox
// methods` all read this registry, never a method's name.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "frame.h"
#include "gl/shader.h"

namespace gis {

struct SceneServices;

// How a method fits the frame.
enum class MethodPipeline {
    // Shadows and G-buffer, then the method's passes, then the lighting pass, which consumes what
    // they output under the lighting contract ("indirect.diffuse", "indirect.specular", "ao").
    Deferred,
    // The method writes "radiance" itself (the path tracer, ray-traced AO).
    Standalone,
};

// What the method's image is, so the bench scores it against the right reference.
enum class MethodImage { Radiance, AmbientOcclusion };

// What a method is to the bench and the viewer besides one of the methods compared: app/ asks the
// registry for a role and names no method.
enum class MethodRole {
    Method,       // one of the methods compared
    Reference,    // the ground truth radiance is scored against; its "spp" and "bounces" rows are the
                  // bench's and the viewer's reference controls
    AoReference,  // the ground truth an AO image is scored against; its "spp" row sets its samples
};

struct GiPreset {
    std::string name;            // low, medium, high
    std::string description;     // "8 directions x 2 steps, half resolution"
    ParamValues values;          // "method.key" -> value, overriding the defaults
    int shadowMapSize = 0, shadowCubeSize = 0;  // 0: keep the render's
};

// What addPasses gets: the resolved settings, the scene, shared services, and where to put passes.
struct MethodBuild {
    const Scene& scene;
    const RenderSettings& settings;
    SceneServices& services;
    gl::MemoryLedger& ledger;
    std::vector<std::unique_ptr<Pass>>& passes;
    void add(std::unique_ptr<Pass> pass) { passes.push_back(std::move(pass)); }
};

struct GiMethod {
    std::string name;                       // --gi NAME
    std::string summary;                    // one line for `gisandbox methods`
    MethodPipeline pipeline = MethodPipeline::Deferred;
    MethodImage image = MethodImage::Radiance;
    MethodRole role = MethodRole::Method;
    bool scoredAgainstAo = false;           // its "ao" output is also scored against the AO reference
    bool physicalBrdfsOnly = false;         // refuses wrap/toon/blinn (the path tracer)
    bool benchmarked = true;                // a row in `bench` (not the reference itself)
    // emitters.environment=auto makes the environment a light of the direct pass (its sun's shadow
    // by ReSTIR, the method carrying only its indirect light): for the methods whose pages measured
    // that closer to Cycles on the building, the courtyard and the map-lit atrium.
    bool environmentLightByDefault = false;
    std::vector<ParamDesc> params;
    std::vector<GiPreset> presets;          // low, medium, high
    // Standalone methods: the lighting pass's term views ("direct", "emission") it writes itself.
    std::vector<std::string> termViews;
    std::function<void(MethodBuild&)> addPasses;
    std::function<std::vector<ProgramDesc>()> programs;  // every program its passes may build
    // GPU bytes its passes will hold, by part, estimated from the settings before anything is
    // allocated (renderer/gi/memory_budget.h refuses what cannot fit).
    std::function<std::vector<std::pair<std::string, uint64_t>>(const Scene&, const RenderSettings&)> estimateMemory;
    // Frames a static view needs before the image is final (the bench scores after that many);
    // progressive passes report their own progress and are rendered until converged().
    std::function<int(const RenderSettings&)> framesToConverge;
    // What its rows' ranges cannot say (a power-of-two resolution, a debug level its channel lacks),
    // checked with the ranges by checkParams: before anything is built and whenever a value is set.
    // Throws gis::Error naming the key. Optional.
    std::function<void(const ParamValues&)> checkSettings;
    // Whether its indirect.diffuse holds the lights' direct diffuse light too (a bake of all the
    // light): the frame then draws no light of its own (no shadow maps, no emitter pass, no light
    // loop in the lighting pass). Optional; absent: it does not.
    std::function<bool(const RenderSettings&)> bakesDirectLight;
    // Its own uniform rows, binding points and blocks, emitted into every shader (gl/shader.h).
    ShaderTables shaderTables;

    const ParamDesc* param(const std::string& key) const;
    const GiPreset& preset(const std::string& name) const;  // throws for an unknown name
};

// Every method, in registry order. Built-ins come from renderer/gi/methods.cpp.
const std::vector<GiMethod>& giMethods();
// Adds a method (tests register their own); throws if the name is taken.
void registerGiMethod(GiMethod method);
const GiMethod& giMethod(const std::string& name);   // throws "unknown GI method 'x' (available: ...)"
const GiMethod* findGiMethod(const std::string& name);
// The method registered in `role` (throws naming the role when there is none).
const GiMethod& methodInRole(MethodRole role);
// "method.key" of the method in `role`, for one of its rows ("spp" -> "pathtrace.spp").
std::string roleParamKey(MethodRole role, const std::string& key);
std::string giMethodNames();                         // "none, ssao, ..."
const std::vector<std::string>& presetNames();       // low, medium, high

// Applies `preset` of `method` to s: sets s.gi and the preset's values (as overrides).
void applyPreset(RenderSettings& s, const std::string& method, const std::string& preset);

// Every shared table, in registry order (renderer/gi/methods.cpp).
const std::vector<ParamGroup>& paramGroups();
// True when `fullKey` belongs to a shared table, not to a method.
bool isGroupParam(const std::string& fullKey);

// Resolves "method.key", "group.key" or an alias flag; throws naming the key and the method's keys.
const ParamDesc& findParam(const std::string& fullKey, std::string* methodOut = nullptr);
// Validates every value in s.params against its row (one message format), then each method's
// checkSettings for the methods the values name.
void checkParams(const ParamValues& values);
// Parses and validates "method.key" = text against the registry and stores it in s.params.
void setParam(RenderSettings& s, const std::string& fullKey, const std::string& text);
// The value of "method.key" in s: what s.params holds, else the row's default.
ParamValue getParam(const RenderSettings& s, const std::string& fullKey);

// Throws when `view` (a --view / pane display name) is one that --gi `gi` cannot produce, told
// by the view's name alone (no GL): a method's own view ("sdf.slice") of another method, or a
// lighting term ("direct") that a method without the deferred lighting pass does not write itself. Names neither kind
// (gbuffer.*, ao, final, an unknown name) are left to the renderer's list of its passes' views.
void checkViewOfMethod(const std::string& gi, const std::string& view);

}  // namespace gis
