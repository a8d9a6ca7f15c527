// Evaluates brdf.glsl at a list of points, for the BRDF tests (tests/brdf): the real GLSL of the
// renderer, run on whatever GL the test has. Not used when rendering.
#include "brdf.glsl"

layout(local_size_x = 64) in;

struct ProbePoint {
    vec4 baseColorMetallic;  // rgb base colour, metallic
    vec4 params;             // roughness, specular factor, diffuse model, specular model
    vec4 n, v, l;            // xyz: unit normal, direction to the viewer, direction to the light
};

layout(std430, binding = B_BRDF_PROBE_POINTS) readonly buffer Points { ProbePoint b_points[]; };
// Two per point: f(l, v) (evaluateBrdf), then f * cos (evaluateBrdfCosine); w unused.
layout(std430, binding = B_BRDF_PROBE_RESULTS) writeonly buffer Results { vec4 b_results[]; };

layout(location = 0) uniform uint u_count;

void main() {
    // 2D dispatch (one dimension is limited to 65535 groups): rows of gl_NumWorkGroups.x groups.
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= u_count) return;
    ProbePoint p = b_points[i];
    SurfaceBrdf s = makeSurfaceBrdf(p.baseColorMetallic.rgb, p.baseColorMetallic.a, p.params.x, p.params.y);
    int diffuseModel = int(p.params.z), specularModel = int(p.params.w);
    b_results[2u * i] = vec4(evaluateBrdf(s, p.n.xyz, p.v.xyz, p.l.xyz, diffuseModel, specularModel), 0.0);
    b_results[2u * i + 1u] = vec4(evaluateBrdfCosine(s, p.n.xyz, p.v.xyz, p.l.xyz, diffuseModel, specularModel), 0.0);
}
