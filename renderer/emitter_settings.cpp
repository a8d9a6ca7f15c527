#include "emitter_settings.h"

#include <algorithm>

#include "gi/method.h"
#include "scene/scene_lighting.h"

namespace gis {

const ParamTable<EmitterLightSettings>& emitterLightParams() {
    using S = EmitterLightSettings;
    static const ParamTable<S> table = ParamTable<S>()
        .choice(&S::mode, "mode", "Emitters",
                "lights: emissive triangles are lights of the direct pass (ReSTIR) and the GI volume holds no "
                "emission; gi: they reach the image only through the GI method; off: only the visible emission; "
                "auto: lights when the emission is bright enough to light the scene (as --lighting auto judges), "
                "else off",
                {"lights", "gi", "off", "auto"}, ParamUpdate::Rebuild)
        .integer(&S::candidates, "candidates", "Candidates", "initial candidates per pixel (M), drawn by power", 1, 64,
                 ParamUpdate::Live)
        .integer(&S::bsdfCandidates, "bsdf-candidates", "BSDF candidates",
                 "initial candidates per pixel along directions drawn from the BRDF, a ray each (0 = none): they "
                 "keep mirrors and glossy metals, and surfaces close to an emitter, from spiking",
                 0, 8, ParamUpdate::Live)
        .boolean(&S::temporal, "temporal", "Temporal reuse", "reuse the last frame's reprojected reservoir",
                 ParamUpdate::Live)
        .integer(&S::spatial, "spatial", "Spatial neighbours", "neighbours reused per pixel (k; 0 = no spatial reuse)", 0,
                 8, ParamUpdate::Live)
        .real(&S::radius, "radius", "Spatial radius", "radius of the spatial neighbourhood, pixels", 1.0, 64.0,
              ParamUpdate::Live)
        .boolean(&S::unbiased, "unbiased", "Unbiased",
                 "count only reservoirs that can produce the sample (1/Z, a visibility ray each); false: 1/sum M, "
                 "cheaper, darkens contact shadows",
                 ParamUpdate::Live)
        .integer(&S::maxHistory, "max-history", "History cap", "temporal M cap in multiples of the candidates", 1, 1000,
                 ParamUpdate::Live)
        .integer(&S::accumulate, "accumulate", "Accumulate frames",
                 "frames a still view averages (0 = each frame its own estimate)", 0, 1 << 16, ParamUpdate::Live)
        .integer(&S::volumeSamples, "volume-samples", "Volume samples",
                 "emitter points per voxel when the voxel methods light their volume with the emitters (0 = none)", 0,
                 256, ParamUpdate::Rebuild)
        .choice(&S::environment, "environment", "Environment as a light",
                "true: the environment (a map or a background) is a light of this pass too, with a visibility ray "
                "per sample, so it casts shadows under every method; the GI methods then carry only its indirect "
                "light; auto: as the GI method declares (`gisandbox methods NAME` says; true where its page measured it "
                "closer to Cycles)",
                {"auto", "true", "false"}, ParamUpdate::Rebuild)
        .integer(&S::environmentCandidates, "environment-candidates", "Environment candidates",
                 "initial candidates per pixel drawn from the environment (by luminance for a map, by cosine for a "
                 "constant)",
                 1, 64, ParamUpdate::Live)
        .integer(&S::environmentVolumeSamples, "environment-volume-samples", "Environment volume samples",
                 "environment directions per voxel (not on walls thinner than a voxel, README), a ray each, when the voxel methods light their volume with "
                 "the environment",
                 1, 1024, ParamUpdate::Rebuild);
    return table;
}

EmitterLightSettings emitterLightSettings(const RenderSettings& settings) {
    return emitterLightParams().read("emitters", settings.params);
}

ParamGroup emitterParamGroup() {
    return {"emitters", "emissive triangles as lights of the direct pass (ReSTIR DI), for every deferred method",
            emitterLightParams().rows};
}

bool sceneHasEmitters(const Scene& scene) {
    for (const DrawItem& d : scene.draws) {
        const int material = scene.primitives[d.primitive].material;
        if (material < 0 || material >= int(scene.materials.size())) continue;
        const glm::vec3 e = scene.materials[material].emissive;
        if (std::max({e.r, e.g, e.b}) > 0.0f) return true;
    }
    return false;
}

bool emittersAreLights(const Scene& scene, const RenderSettings& settings) {
    switch (EmitterMode(emitterLightSettings(settings).mode)) {
        case EmitterMode::Lights: return sceneHasEmitters(scene);
        case EmitterMode::Auto: return emissionLightsScene(scene);
        default: return false;
    }
}

bool environmentSendsLight(const Scene& scene, const RenderSettings& settings) {
    const glm::vec3 background = settings.background.value_or(scene.background);
    return !settings.environment.empty() || std::max({background.r, background.g, background.b}) > 0.0f;
}

bool environmentLightChosen(const RenderSettings& settings) {
    switch (EnvironmentLightChoice(emitterLightSettings(settings).environment)) {
        case EnvironmentLightChoice::True: return true;
        case EnvironmentLightChoice::False: return false;
        default: {
            const GiMethod* method = findGiMethod(settings.gi);
            return method && method->environmentLightByDefault;
        }
    }
}

bool environmentIsLight(const Scene& scene, const RenderSettings& settings) {
    return environmentLightChosen(settings) && environmentSendsLight(scene, settings);
}

bool directPassHasLights(const Scene& scene, const RenderSettings& settings) {
    return emittersAreLights(scene, settings) || environmentIsLight(scene, settings);
}

}  // namespace gis
