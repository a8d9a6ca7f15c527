#include "gi/lightmap/lightmap_settings.h"

#include <cmath>

#include "error.h"
#include "scene/scene.h"

namespace gis {

const ParamTable<LightmapSettings>& lightmapParams() {
    using S = LightmapSettings;
    static const ParamTable<S> table = ParamTable<S>()
        .integer(&S::texels, "texels", "Texels", "texels on all the scene's surfaces together: the density follows "
                 "from their area, so a scene at any scale gets the same lightmap", 256, 1 << 24, ParamUpdate::Rebuild)
        .real(&S::texelsPerMetre, "texels-per-metre", "Texels per metre",
              "texel density on the surfaces, texels per world unit; 0 = from lightmap.texels", 0.0, 1e9,
              ParamUpdate::Rebuild)
        .integer(&S::samples, "samples", "Samples per texel", "paths traced from each texel (a raised count continues "
                 "the bake)", 1, 1 << 20, ParamUpdate::Live)
        .integer(&S::bounces, "bounces", "Bounces", "bounces after the texel's own: 1 = light reflected once by "
                 "another surface", 1, 64, ParamUpdate::Rebuild)
        .boolean(&S::environmentSampling, "env-sampling", "Sample the environment",
                 "true: an --environment map is also sampled by its luminance at the paths' vertices, weighted by MIS "
                 "(as pathtrace.env-sampling); false: BSDF samples alone reach it (the same mean, noisier)",
                 ParamUpdate::Rebuild)
        .boolean(&S::denoise, "denoise", "Denoise", "an edge-aware filter within each chart (never across charts), "
                 "its edges at a few standard errors of the texels' mean", ParamUpdate::Live)
        .boolean(&S::stitch, "stitch", "Stitch seams", "where a smooth surface's charts meet, the texels on both "
                 "sides are moved, as little as possible, until the two sides' lookups agree (no line shows)",
                 ParamUpdate::Live)
        .boolean(&S::cache, "cache", "Cache on disk", "a finished bake is kept on disk by the scene's content id and "
                 "read back instead of baking again (GIS_LIGHTMAP_CACHE names the folder)", ParamUpdate::Live)
        .boolean(&S::directional, "directional", "Directional",
                 "the light's luminance-weighted mean direction per texel too, so a normal map's relief is lit by "
                 "where the light comes from (a first-order spherical-harmonic fit, exact at the surface's own "
                 "normal); 32 more bytes a texel", ParamUpdate::Rebuild)
        .choice(&S::rebake, "rebake", "Re-bake after an edit",
                "auto: a light, object or material edit bakes again at once, the last lightmap shown (marked stale) "
                "until the new one is done; hold: the stale lightmap stays until this is set back to auto",
                {"auto", "hold"}, ParamUpdate::Live)
        .choice(&S::mode, "mode", "Baked light", "indirect: the light the lighting pass does not draw (its lights "
                "stay per frame, with shadow maps and highlights); all: the lights' direct diffuse light too, and the "
                "frame draws no light of its own (the cheapest frame, without the lights' specular highlights)",
                {"indirect", "all"}, ParamUpdate::Rebuild);
    return table;
}

namespace {
double surfaceArea(const std::vector<lightmap::MeshInput>& meshes) {
    double area = 0.0;
    for (const lightmap::MeshInput& m : meshes)
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const glm::dvec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                             c = m.positions[m.indices[t + 2]];
            const double twice = glm::length(glm::cross(b - a, c - a));
            if (std::isfinite(twice)) area += 0.5 * twice;
        }
    return area;
}
}  // namespace

lightmap::Atlas lightmapAtlas(const Scene& scene, const LightmapSettings& s) {
    const std::vector<lightmap::MeshInput> meshes = lightmap::meshesFromScene(scene);
    lightmap::AtlasParams params;
    const bool fromTexels = s.texelsPerMetre <= 0.0f;
    const double area = surfaceArea(meshes);
    if (!(area > 0.0)) return {};  // nothing to light (an empty scene): no atlas, no texels
    params.texelsPerMetre = fromTexels ? float(std::sqrt(double(s.texels) / std::max(area, 1e-300))) : s.texelsPerMetre;
    if (!std::isfinite(params.texelsPerMetre) || params.texelsPerMetre <= 0.0f)
        throw Error("lightmap: the scene's surfaces (area " + std::to_string(area) +
                    ") give no finite texel density; set lightmap.texels-per-metre");
    try {
        return lightmap::buildAtlas(meshes, params);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (set by " +
                    (fromTexels ? "lightmap.texels " + std::to_string(s.texels)
                                : "lightmap.texels-per-metre " + std::to_string(s.texelsPerMetre)) +
                    ")");
    }
}

}  // namespace gis
