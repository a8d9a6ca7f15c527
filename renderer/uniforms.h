// Explicit uniform locations and uniform blocks of the core passes and the methods without a table
// of their own (gl/uniform_table.h, gl/uniform_block.h: emitted into every shader).
#pragma once

#include "gl/uniform_block.h"
#include "gl/uniform_table.h"

namespace gis {

// Directions the hemisphere AO kernel's uniform array holds (GLSL's MAX_AO_KERNEL).
constexpr int kSsaoMaxKernel = 256;
#define GIS_UNIFORMS(X) \
    /* per draw (scene geometry) */ \
    X(U_MODEL, 0, 1) \
    X(U_NORMAL_MATRIX, 1, 1) \
    X(U_VIEW_PROJ, 2, 1) \
    X(U_BASE_COLOR_FACTOR, 3, 1) \
    X(U_METALLIC, 4, 1) \
    X(U_EMISSIVE, 5, 1) \
    X(U_ALPHA_CUTOFF, 6, 1) /* alphaMode MASK's cutoff; < 0: opaque */ \
    X(U_BRDF_OVERRIDE, 7, 1) /* the material's diffuse, specular model (-1: the render's setting) */ \
    X(U_ROUGHNESS, 60, 1) \
    X(U_SPECULAR_FACTOR, 61, 1) \
    X(U_OCCLUSION_STRENGTH, 62, 1) \
    X(U_NORMAL_SCALE, 63, 1) \
    X(U_DOUBLE_SIDED, 64, 1) \
    /* lighting pass */ \
    X(U_INV_VIEW_PROJ, 20, 1) \
    X(U_CAMERA_POS, 21, 1) \
    X(U_LIGHT_COUNT, 22, 1) \
    X(U_AMBIENT, 23, 1) \
    X(U_BRDF_MODELS, 25, 1) /* diffuse model, specular model */ \
    X(U_SHADOWS_ENABLED, 26, 1) \
    X(U_MAX_RADIANCE, 27, 1) /* largest value the radiance target can hold */ \
    /* path tracer */ \
    X(U_SAMPLE_INDEX, 40, 1) \
    X(U_SEED, 41, 1) \
    X(U_MAX_BOUNCES, 42, 1) \
    X(U_EMITTER_COUNT, 43, 1) \
    X(U_RR_START, 44, 1) \
    X(U_CAUSTICS, 45, 1) /* 0: no light through glossy bounces after a diffuse one */ \
    X(U_PT_TERM, 46, 1) /* the term a path accumulates: 0 all, 1 direct, 2 emission, 3 indirect, 4/5 its diffuse/specular split */ \
    X(U_ENV_SAMPLING, 47, 1) /* 1: an environment map is sampled as a light (MIS) */ \
    /* ambient occlusion (SSAO, its blur and temporal passes, the ray-traced reference) */ \
    X(U_AO_RADIUS, 50, 1) \
    X(U_PROJ, 52, 1) \
    X(U_INV_PROJ, 53, 1) \
    X(U_VIEW, 54, 1) \
    X(U_AO_KERNEL_SIZE, 55, 1) \
    X(U_PREV_VIEW_PROJ, 57, 1) \
    X(U_AO_KERNEL, 600, kSsaoMaxKernel) /* a vec4 per direction; past every table, within GL's 1024 */ \
    /* the G-buffer's emission resolve (passes/gbuffer_pass.cpp): this pass's index, the pass count */ \
    X(U_EMISSION_PASS, 561, 1) \
    /* environment prefilter (renderer/environment_gpu.cpp) */ \
    X(U_ENV_ROUGHNESS, 560, 1) /* the GGX roughness of the level being filtered */ \
    /* tonemap pass */ \
    X(U_EXPOSURE, 30, 1) \
    X(U_TONEMAPPER, 31, 1) \
    /* debug displays (view_debug.frag) */ \
    X(U_DISPLAY_CHANNEL, 570, 1) \
    X(U_DISPLAY_INV_VIEW_PROJ, 571, 1) \
    X(U_DISPLAY_CAMERA_POS, 572, 1) \
    X(U_DISPLAY_MAX_DISTANCE, 573, 1) \
    X(U_DISPLAY_HAS_DEPTH, 574, 1) /* 0: no G-buffer, every pixel is shown */

enum UniformLocation : int { GIS_UNIFORMS(GIS_UNIFORM_ENUM) };
inline constexpr gl::UniformSlot kUniforms[] = {GIS_UNIFORMS(GIS_UNIFORM_SLOT)};

// Texture and image units of the same passes (gl/uniform_table.h's binding rows).
#define GIS_BINDINGS(X) \
    /* G-buffer draws: the material's textures (material.glsl) */ \
    X(T_MATERIAL_BASE_COLOR, 0) \
    X(T_MATERIAL_METALLIC_ROUGHNESS, 1) \
    X(T_MATERIAL_NORMAL, 2) \
    X(T_MATERIAL_EMISSIVE, 3) \
    X(T_MATERIAL_OCCLUSION, 4) \
    /* the G-buffer's emission resolve (emission_resolve.comp) */ \
    X(T_EMISSION_SAMPLES, 0) \
    X(I_EMISSION, 0) \
    /* lighting pass (lighting.frag): the G-buffer, shadow maps and what methods and emitters output */ \
    X(T_LIGHTING_DEPTH, 0) \
    X(T_LIGHTING_BASE_COLOR, 1) \
    X(T_LIGHTING_NORMAL, 2) \
    X(T_LIGHTING_MATERIAL, 3) \
    X(T_LIGHTING_EMISSIVE, 4) \
    X(T_LIGHTING_SHADOW_MAPS, 5) \
    X(T_LIGHTING_SHADOW_CUBES, 6) \
    X(T_LIGHTING_AO, 7) \
    X(T_LIGHTING_INDIRECT_DIFFUSE, 8) \
    X(T_LIGHTING_INDIRECT_SPECULAR, 9) \
    X(T_LIGHTING_EMITTERS_DIRECT, 10) \
    /* tonemap pass and debug displays */ \
    X(T_TONEMAP_RADIANCE, 0) \
    X(T_DISPLAY_SOURCE, 0) \
    X(T_DISPLAY_DEPTH, 1) \
    /* the BRDF probe (brdf_probe.comp, the BRDF tests) */ \
    X(B_BRDF_PROBE_POINTS, 0) \
    X(B_BRDF_PROBE_RESULTS, 1) \
    /* the progressive ray passes' running sum and mean (SampleAccumulator: pathtrace.comp, ao_reference.comp) */ \
    X(I_ACCUMULATION_SUM, 0) \
    X(I_ACCUMULATION_MEAN, 1) \
    /* the environment's precomputation (environment_prefilter.comp, environment_brdf_lut.comp) */ \
    X(I_ENVIRONMENT_PREFILTER_LEVEL, 0) \
    X(I_ENVIRONMENT_BRDF_TABLE, 0)

enum BindingPoint : int { GIS_BINDINGS(GIS_BINDING_ENUM) };
inline constexpr gl::BindingSlot kBindings[] = {GIS_BINDINGS(GIS_BINDING_SLOT)};

// Screen-space AO's samples (ssao.frag's hemisphere kernel and gtao.frag's slices).
#define GIS_SSAO_BLOCK(M, A) \
    M(float, bias)          /* fraction of the radius */ \
    M(float, power)         /* AO is raised to it */ \
    M(int, steps)           /* per direction */ \
    M(int, noiseOffset)     /* 0..15: the noise tile's shift this frame */
GIS_UNIFORM_BLOCK(SsaoBlock, 9, GIS_SSAO_BLOCK)

// SSAO's temporal accumulation (ssao_temporal.frag).
#define GIS_SSAO_TEMPORAL_BLOCK(M, A) \
    M(float, maxFrames)      /* the running mean's longest window */ \
    M(int, hasHistory) \
    M(float, depthTolerance) /* relative: history further than this from the surface is rejected */
GIS_UNIFORM_BLOCK(SsaoTemporalBlock, 10, GIS_SSAO_TEMPORAL_BLOCK)
}  // namespace gis
