// Explicit uniform locations of the SDF GI method: mirrors renderer/gi/sdf/sdf_gi_uniforms.h.
#define UG_INV_VIEW_PROJ 420
#define UG_CAMERA_POS 421
#define UG_VOLUME 422
#define UG_RESOLUTION 423
#define UG_MARCH 424
#define UG_RAYS 425
#define UG_FRAME 426
#define UG_ENVIRONMENT 427
#define UG_SPECULAR 428
#define UG_SCALE 429
#define UG_AO 430
#define UG_INTENSITY 431
#define UG_PREV_VIEW_PROJ 432
#define UG_TEMPORAL 433
#define UG_FILTER 434
#define UG_PREV_CAMERA_POS 435
#define UG_DEBUG 436
