// Explicit uniform locations of the distance-field module: shaders/sdf/sdf_uniforms.glsl mirrors
// it. 400 and up, clear of renderer/uniforms.h (0-319 with the AO kernel) and the voxel module
// (100-119), because the SDF method's trace shader includes all three.
#pragma once

namespace gis::sdf {
enum SdfUniform : int {
    US_RESOLUTION = 400,    // cells per edge
    US_JFA_STEP = 401,      // the jump of this flood pass, in cells
    US_ORIGIN = 402,        // world position of the volume's minimum corner
    US_CELL_SIZE = 403,     // world edge of one cell
    US_FAR = 404,           // the value of cells no seed reaches
    US_HAS_NORMALS = 405,   // 1: sign from the seeds' normals; 0: unsigned
    US_COARSE_FACTOR = 406, // fine cells per coarse cell along an edge
    US_LAYER = 407,         // the layer (cascade) of a layered field written by this dispatch
};
}  // namespace gis::sdf
