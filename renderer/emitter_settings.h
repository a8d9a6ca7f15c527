// The emitter lights' settings (emitters.*) and when emissive triangles are lights, apart from
// the ReSTIR pass (renderer/emitters/) so the volume can ask without depending on that pass.
#pragma once

#include "param_table.h"
#include "render_settings.h"
#include "scene/scene.h"

namespace gis {

// How emissive surfaces light the scene (emitters.mode).
enum class EmitterMode {
    Lights = 0,  // direct light by ReSTIR; the GI volume holds no emission (nothing counted twice)
    Gi = 1,      // only through the GI method (voxel emission), as before this module
    Off = 2,     // only the visible emission
    Auto = 3,    // Lights when the scene's emission is bright enough to light it (emissionLightsScene), else Off
};

// Whether the environment is a light of the direct pass (emitters.environment).
enum class EnvironmentLightChoice {
    Auto = 0,   // as the GI method declares (GiMethod::environmentLightByDefault)
    True = 1,
    False = 2,
};

struct EmitterLightSettings {
    int mode = int(EmitterMode::Auto);  // lights measured closer to Cycles than gi (README)
    int candidates = 8;       // M: initial candidates per pixel, drawn by power
    int bsdfCandidates = 1;   // initial candidates per pixel along BSDF directions (a ray each)
    bool temporal = true;     // reuse the reprojected reservoir of the last frame
    int spatial = 3;          // k: neighbours reused
    float radius = 16.0f;     // pixels: the spatial neighbourhood
    bool unbiased = true;     // 1/Z with visibility (one ray per reused reservoir) instead of 1/sum M
    int maxHistory = 20;      // the temporal M cap, in multiples of M
    int accumulate = 64;      // frames a still view averages (0: every frame shows its own estimate)
    int volumeSamples = 16;   // emitter points per voxel lighting the GI volume (voxel light injection)
    int environment = int(EnvironmentLightChoice::Auto);  // the environment is a light of this pass too (environmentIsLight)
    int environmentCandidates = 8;        // candidates per pixel drawn from the environment
    int environmentVolumeSamples = 32;    // environment directions per voxel lighting the GI volume
};
const ParamTable<EmitterLightSettings>& emitterLightParams();
EmitterLightSettings emitterLightSettings(const RenderSettings& settings);

// True when some draw's material emits (before building any GPU resource).
bool sceneHasEmitters(const Scene& scene);
// Emissive triangles are lights here: some draw emits and emitters.mode is `lights`, or `auto` and
// the emission is bright enough to light the scene (the judgement --lighting auto makes; below
// it, emission is a surface detail and ReSTIR would spend its frames for nothing). The direct
// pass then runs ReSTIR and the voxel methods light their volume with the emitters.
bool emittersAreLights(const Scene& scene, const RenderSettings& settings);

// The environment sends light into the scene: a map, or a background (the settings' or the scene's)
// above 0.
bool environmentSendsLight(const Scene& scene, const RenderSettings& settings);
// emitters.environment as the settings' method resolves it (`auto`: the method's default), whether
// or not the environment sends light.
bool environmentLightChosen(const RenderSettings& settings);
// The environment is a light of the direct pass (environmentLightChosen, and it sends light): ReSTIR draws candidates from it with a visibility ray each, so its sun and sky cast
// shadows under every method; the GI methods' rays that leave the scene then see black
// (environment.glsl's environmentMiss*) and their volume is lit by it through injection, so it
// is counted once, as the emitters are under `lights`.
bool environmentIsLight(const Scene& scene, const RenderSettings& settings);
// The direct pass (ReSTIR) runs: emitters or the environment are its lights.
bool directPassHasLights(const Scene& scene, const RenderSettings& settings);

}  // namespace gis
