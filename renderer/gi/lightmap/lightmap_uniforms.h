// The lightmap's uniform locations and binding points (gl/uniform_table.h: emitted into every
// shader; the shader-constants test checks no two tables overlap). Its bake also sets the path
// tracer's rows (renderer/uniforms.h), whose paths it traces.
#pragma once

#include "gl/uniform_table.h"

namespace gis::lightmap {
#define GIS_LIGHTMAP_UNIFORMS(X) \
    X(UL_VIEW_PROJ, 900, 1)   /* the apply pass's camera */ \
    X(UL_STEP, 901, 1)        /* the denoiser's a-trous step, texels */ \
    X(UL_SAMPLES, 902, 1)     /* paths in each texel's mean so far */ \
    X(UL_MODE, 903, 1)        /* filter: 0 copy, 1 denoise step, 2 dilate, 3 copy the direction; lookup: the view */ \
    X(UL_TEXEL_SIZE, 904, 1)  /* world units per texel */ \
    X(UL_LAYERS, 905, 1)      /* lightmap.atlas: the atlas array's layers */ \
    X(UL_TARGET_SIZE, 906, 1) /* lightmap.atlas: the view's pixels */ \
    X(UL_BAKE_DIRECT, 907, 1) /* bake: 1 samples the lights at the texel too, MIS against its ray (lightmap.mode=all) */ \
    X(UL_DIRECTIONAL, 908, 1) /* bake, filter, lookup: 1 where the lightmap keeps the light's direction */ \
    X(UL_INV_VIEW_PROJ, 909, 1) /* the cut-outs' lookup: the G-buffer's points from its depth */

enum LightmapUniform : int { GIS_LIGHTMAP_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kLightmapUniforms[] = {GIS_LIGHTMAP_UNIFORMS(GIS_UNIFORM_SLOT)};

// Image units of the bake and its filters (the texels' position and normal, the paths' running
// mean and, directional, the running mean of their luminance times their direction, a filter's
// source and target); the texture units the lookup samples (the lightmap, the texels' positions and
// flags, the light's mean direction and the G-buffer's shading normal).
#define GIS_LIGHTMAP_BINDINGS(X) \
    X(IL_POSITION, 0) \
    X(IL_NORMAL, 1) \
    X(IL_MEAN, 2) \
    X(IL_SOURCE, 3) \
    X(IL_TARGET, 4) \
    X(IL_DIRECTION, 5) \
    X(TL_LIGHTMAP, 1) \
    X(TL_TEXELS, 2) \
    X(TL_DIRECTION, 3) \
    X(TL_SHADING_NORMAL, 4) \
    X(TL_GBUFFER_DEPTH, 5)

enum LightmapBinding : int { GIS_LIGHTMAP_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kLightmapBindings[] = {GIS_LIGHTMAP_BINDINGS(GIS_BINDING_SLOT)};
}  // namespace gis::lightmap
