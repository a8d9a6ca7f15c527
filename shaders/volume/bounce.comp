// A further bounce: each occupied voxel gathers the incoming radiance of the current chain with the
// diffuse cones around its mean normal and adds albedo * (E / pi) to what injection gave it
// (direct light and emission, in s_direct).
#include "common.glsl"
#include "volume/cone_trace.glsl"
#include "volume/voxel_faces.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0) uniform sampler3D s_albedo;
layout(binding = 1) uniform sampler3D s_normal;
layout(binding = 2) uniform sampler3D s_direct;
layout(rgba16f, binding = 0) uniform writeonly image3D i_radiance;

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_CONE_SET) uniform int u_coneSet;
ConeTraceBlock u_cones;
layout(location = UV_ANISOTROPIC) uniform int u_anisotropic;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(u_resolution)))) return;
    vec4 direct = texelFetch(s_direct, v, 0);
    vec4 albedo = texelFetch(s_albedo, v, 0);
    vec3 meanNormal = texelFetch(s_normal, v, 0).xyz * 2.0 - 1.0;
    float len = length(meanNormal);
    // direct.a 0 on a surface voxel: an unlit outside left out of the volume (exterior.comp).
    if (albedo.a == 0.0 || len < VOXEL_TWO_SIDED || direct.a == 0.0) {
        imageStore(i_radiance, v, direct);
        return;
    }
    ConeTracer t = makeConeTracer(u_resolution, u_cones.stepFactor, u_cones.maxDistance, u_anisotropic);
    vec3 n = meanNormal / len;
    vec3 origin = vec3(v) + 0.5 + n * u_cones.offset;
    vec4 gathered = traceDiffuse(t, origin, n, u_coneSet, 1.0, 0.0);
    vec3 radiance = direct.rgb + albedo.rgb * gathered.rgb;
    imageStore(i_radiance, v, vec4(min(finiteOrZero(radiance), vec3(MAX_HALF_FLOAT)), direct.a));
}
