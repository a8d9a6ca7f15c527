// Explicit uniform locations of probe GI: mirrors renderer/gi/probes/probe_uniforms.h. 500 and up,
// clear of renderer/uniforms.h, the voxel module (100-119) and the distance field (400-406).
#define UP_GRID_FIRST 500
#define UP_GRID_STEP 501
#define UP_GRID_COUNTS 502
#define UP_STORAGE 503
#define UP_RAYS 504
#define UP_FIRST_PROBE 505
#define UP_ROTATION 506
#define UP_ENVIRONMENT 507
#define UP_VOLUME 508
#define UP_SDF_RESOLUTION 509
#define UP_BLEND_PARAMS 510
#define UP_INV_VIEW_PROJ 511
#define UP_CAMERA_POS 512
#define UP_SHADE_PARAMS 513
#define UP_MODE 514
#define UP_VIEW_PROJ 515
#define UP_SLOT_OFFSET 516
