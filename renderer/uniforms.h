// Explicit uniform locations shared by C++ and GLSL (shaders/uniforms.glsl mirrors this file).
// Fixed locations mean no glGetUniformLocation lookups and no silent name mismatches.
#pragma once

namespace gis {
enum UniformLocation : int {
    // per draw (scene geometry)
    U_MODEL = 0,
    U_NORMAL_MATRIX = 1,
    U_VIEW_PROJ = 2,
    U_BASE_COLOR_FACTOR = 3,
    U_MATERIAL_PARAMS = 4,   // metallic, roughness, specularFactor, occlusionStrength
    U_EMISSIVE = 5,
    U_ALPHA_PARAMS = 6,      // alpha cutoff (<0: opaque), normal scale, has normal map, double sided
    U_BRDF_OVERRIDE = 7,     // the material's diffuse, specular model (-1: the render's setting)
    // shadow pass
    U_LIGHT_POS_FAR = 10,    // point light position, 1/far
    // lighting pass
    U_INV_VIEW_PROJ = 20,
    U_CAMERA_POS = 21,
    U_LIGHT_COUNT = 22,
    U_AMBIENT = 23,
    U_BACKGROUND = 24,
    U_BRDF_MODELS = 25,      // diffuse model, specular model
    U_SHADOWS_ENABLED = 26,
    U_MAX_RADIANCE = 27,     // largest value the radiance target can hold
    // path tracer
    U_SAMPLE_INDEX = 40,
    U_SEED = 41,
    U_MAX_BOUNCES = 42,
    U_EMITTER_COUNT = 43,
    U_RR_START = 44,
    U_CAUSTICS = 45,        // 0: no light through glossy bounces after a diffuse one
    // ambient occlusion (SSAO, its blur and temporal passes, the ray-traced reference)
    U_AO_RADIUS = 50,
    U_AO_PARAMS = 51,        // bias (fraction of radius), power, steps per direction, noise offset
    U_PROJ = 52,
    U_INV_PROJ = 53,
    U_VIEW = 54,
    U_AO_KERNEL_SIZE = 55,
    U_FRAME_INDEX = 56,
    U_PREV_VIEW_PROJ = 57,
    U_TEMPORAL_PARAMS = 58,  // max frames, has history, depth tolerance
    U_AO_KERNEL = 64,        // array of 256 vec4: locations 64..319
    // tonemap pass
    U_EXPOSURE = 30,
    U_TONEMAPPER = 31,
};
}  // namespace gis
