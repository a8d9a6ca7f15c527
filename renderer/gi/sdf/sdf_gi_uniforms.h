// Explicit uniform locations of the SDF GI method's shaders (shaders/gi/sdf/): mirrored by
// shaders/gi/sdf/sdf_gi_uniforms.glsl. 420 and up: clear of renderer/uniforms.h, the voxel module
// (100-139) and the distance-field module (400-419).
#pragma once

namespace gis::sdfgi {
enum SdfGiUniform : int {
    UG_INV_VIEW_PROJ = 420,
    UG_CAMERA_POS = 421,
    UG_VOLUME = 422,        // origin xyz, edge length
    UG_RESOLUTION = 423,    // cells per edge
    UG_MARCH = 424,         // hit threshold (cells), relaxation, max steps, start offset (cells)
    UG_RAYS = 425,          // diffuse rays per traced pixel
    UG_FRAME = 426,         // frames rendered before this one (decorrelates the rays)
    UG_ENVIRONMENT = 427,   // radiance of rays that miss
    UG_SPECULAR = 428,      // reflection ray on (0/1), roughness cut-off
    UG_SCALE = 429,         // full-resolution pixels per traced pixel (1 or 2)
    UG_AO = 430,            // soft-occlusion strength
    UG_INTENSITY = 431,
    UG_PREV_VIEW_PROJ = 432,
    UG_TEMPORAL = 433,      // largest history weight, history valid (0/1), camera moved (0/1)
    UG_FILTER = 434,        // filter radius in traced pixels
    UG_PREV_CAMERA_POS = 435,
    UG_DEBUG = 436,         // view (0 slice, 1 steps, 2 normals), slice axis, slice position, max steps
    UG_CASCADES = 437,      // vec4[kMaxCascades] (437-440): origin xyz, edge; finest first
    UG_CASCADE_COUNT = 441,
    UG_SLICE_CASCADE = 442, // the cascade (layer) sdf.slice shows
};
}  // namespace gis::sdfgi
