// The lightmap's parameters: one row each in lightmapParams() (names scripts and checks use:
// lightmap.texels, lightmap.texels-per-metre, lightmap.samples, lightmap.bounces,
// lightmap.env-sampling, lightmap.denoise, lightmap.stitch, lightmap.cache, lightmap.mode,
// lightmap.directional, lightmap.rebake), defaults in the initialisers below.
#pragma once

#include <string>

#include "lightmap/atlas.h"
#include "param_table.h"

namespace gis {

struct Scene;

// lightmap.mode: what the bake holds. Indirect: the light the lighting pass does not draw itself
// (its lights' direct light stays per frame, shadow-mapped, with its specular highlights). All: the
// lights' direct diffuse light too, ray-traced, and the frame then draws no light of its own (no
// shadow maps, no emitter pass, no light loop): the cheapest frame, without the lights' specular
// highlights, as a static light in Godot's LightmapGI.
enum LightmapMode : int { kLightmapIndirect = 0, kLightmapAll = 1 };
// lightmap.rebake: after an edit the last lightmap stays on show, marked stale; auto bakes the new
// one at once (in the background), hold waits until it is set back to auto (a bake costs seconds
// to minutes: a user placing several lights bakes once).
enum LightmapRebake : int { kRebakeAuto = 0, kRebakeHold = 1 };

struct LightmapSettings {
    int texels = 16384;            // lightmap.texels: texels on all surfaces together (rebuild)
    float texelsPerMetre = 0.0f;   // lightmap.texels-per-metre: 0 = from texels and the surfaces' area (rebuild)
    int samples = 64;              // lightmap.samples: paths per texel (live: more continue the bake)
    int bounces = 16;              // lightmap.bounces: bounces after the texel's first, as pathtrace.bounces (rebuild)
    bool environmentSampling = true;  // lightmap.env-sampling: a map sampled as a light too (rebuild)
    bool denoise = true;           // lightmap.denoise: the edge-aware filter within each chart (live)
    bool stitch = true;            // lightmap.stitch: the two sides of a seam made to agree (live)
    bool cache = true;             // lightmap.cache: read and write finished bakes on disk (live)
    bool directional = false;      // lightmap.directional: the light's mean direction kept too (rebuild)
    int rebake = kRebakeAuto;      // lightmap.rebake: auto or hold (live)
    int mode = kLightmapIndirect;  // lightmap.mode: indirect or all (rebuild: the frame's passes follow it)
};

const ParamTable<LightmapSettings>& lightmapParams();

// The atlas a scene gets under these settings: the density from texels-per-metre, else from
// `texels` over the surfaces' world area, so a scene scaled by any factor gets the same texels.
// A scene without surfaces gets an empty atlas. Throws gis::Error naming lightmap.texels or lightmap.texels-per-metre when the atlas cannot hold it.
lightmap::Atlas lightmapAtlas(const Scene& scene, const LightmapSettings& s);

}  // namespace gis
