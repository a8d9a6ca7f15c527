// Explicit uniform locations of the voxel module and the VCT method: mirrors
// renderer/voxel/voxel_uniforms.h. A range of their own (100..139) so they never collide with
// renderer/uniforms.h.
#define UV_WORLD_TO_VOXEL 100
#define UV_RESOLUTION 101
#define UV_CONSERVATIVE 102
#define UV_EMISSION_SCALE 103
#define UV_VOXEL_TO_WORLD 104
#define UV_VOXEL_SIZE 105
#define UV_LIGHT_COUNT 106
#define UV_SHADOWS_ENABLED 107
#define UV_MIP_LEVEL 108
#define UV_DIRECTION 109
#define UV_INV_VIEW_PROJ 110
#define UV_CAMERA_POS 111
#define UV_CONE_SET 112
#define UV_TRACE_PARAMS 113
#define UV_ENVIRONMENT 114
#define UV_ANISOTROPIC 115
#define UV_INTENSITY 116
#define UV_DEBUG_PARAMS 117
#define UV_BOUNCE 118
#define UV_NORMAL_WEIGHT 119
#define UV_EMISSION_WEIGHT 120
#define UV_EMITTER_SAMPLES 121
