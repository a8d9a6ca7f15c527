// Explicit uniform locations of the emitter-light module: mirrors renderer/emitters/emitter_uniforms.h.
#define UE_VIEW_PROJ 200
#define UE_PREV_VIEW_PROJ 201
#define UE_INV_VIEW_PROJ 202
#define UE_CAMERA_POS 203
#define UE_EMITTER_COUNT 204
#define UE_BRDF_MODELS 205
#define UE_FRAME 206
#define UE_REUSE 207
#define UE_HISTORY 208
