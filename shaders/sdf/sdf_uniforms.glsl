// Explicit uniform locations of the distance-field module: mirrors renderer/sdf/sdf_uniforms.h.
#define US_RESOLUTION 400
#define US_JFA_STEP 401
#define US_ORIGIN 402
#define US_CELL_SIZE 403
#define US_FAR 404
#define US_HAS_NORMALS 405
#define US_COARSE_FACTOR 406
#define US_LAYER 407
