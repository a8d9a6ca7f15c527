// The rays that stand in for the diffuse cones' march where a method casts them (vct.sky-rays;
// volume/cone_trace.glsl): `count` rays per cone from one origin through the scene's triangles,
// spread over the hemisphere by cosine and turned by `rotation` (noise rather than bands where a
// window's edge crosses a fixed set). A ray that leaves the scene brings the environment; one
// that meets a surface brings that surface's light from the voxels (surfaceLight). From off a voxel
// (the bounces), one whose first hit is the back of a one-sided triangle started inside a solid (a
// voxel where a wall meets the roof: off the wall's face is inside the roof) and brings nothing,
// neither the solid's far side nor the sky beyond it; from a pixel's surface it met the back of an
// open surface, which the path tracer, as Cycles, lights from both sides. The includer defines
// CONE_RAYS before volume/cone_trace.glsl, includes ray_scene.glsl, declares u_worldToVoxel and
// u_resolution, binds the ray scene and the volume, and sets g_coneRays before gathering. A pixel's
// ray's hit lights itself with the punctual lights (volume/hit_light.glsl) unless it lies in a slab,
// whose faces are lit apart already; the voxels' bounces keep their voxels' light (lit there too,
// the atrium measured the same and the bounces cost 40% more: renderer/gi/vct/README.md).
#include "volume/hit_light.glsl"
struct ConeRaySource {
    vec3 origin;          // world, off the surface
    float rotation;       // every cone's turn of its rays, in [0, 1)
    int count;            // rays per cone; 0: the cones march
    bool mayStartInside;  // off a voxel, not a surface: a first hit on a back face brings nothing
    // The surface's own plane (0 for none): a ray around a normal-mapped shading normal that points
    // under it would meet the surface it leaves, and is mirrored above it.
    vec3 geometricNormal;
};
ConeRaySource g_coneRays;
// The rays since the includer last reset it that started inside a solid (mayStartInside; what
// they brought is no light of the place they were cast for).
int g_raysStartedInside = 0;

vec3 aboveSurface(vec3 d) {
    float below = dot(d, g_coneRays.geometricNormal);
    return below < 0.0 ? d - 2.0 * below * g_coneRays.geometricNormal : d;
}

// What the ray along d brings: a surface's light, nothing where it started inside a solid, or the
// environment (over `steradians` around d) where it leaves the scene; a = 1 where it met something.
vec4 rayLight(vec3 d, float steradians, vec3 from) {
    d = aboveSurface(d);
    Hit h;
    if (!traceRay(g_coneRays.origin, d, 1e30, false, h)) return vec4(environmentMissCone(d, steradians), 0.0);
    if (g_coneRays.mayStartInside && !hitGeometry(h, d).frontFace && bvhTriangleIsSingleSided(h.triangle)) {
        ++g_raysStartedInside;
        return vec4(0.0, 0.0, 0.0, 1.0);
    }
    vec3 hit = (u_worldToVoxel * vec4(g_coneRays.origin + d * h.t, 1.0)).xyz;
    ivec3 v;
    vec3 light = surfaceLight(float(u_resolution), from, hit, d, v);
    bool fromPixel = !g_coneRays.mayStartInside;
    if (fromPixel && voxelSlabAxis(texelFetch(s_voxelSides, v, 0)) < 0) {
        RayHitGeometry g = hitGeometry(h, d);
        light = withHitPunctualLight(light, texelFetch(s_voxelPunctual, v, 0), g.position, g.geometricNormal,
                                     hitBaseColor(h, g));
    }
    return vec4(light, 1.0);
}

// The diffuse gather: count x cones rays by cosine over the hemisphere around n (Malley's method
// on a golden-angle spiral over the disk, turned by the rotation), each an equal share of E / pi.
// Cones' apertures and weights stand for the cosine lobe over their footprints; single rays in a
// wide cone's cap would sample it uniformly, and the four 90-degree cones' caps reach the horizon.
vec4 traceDiffuseRays(vec3 n, int cones) {
    int total = g_coneRays.count * cones;
    if (total <= 0) return vec4(-1.0);
    mat3 frame = tangentFrame(n);
    float steradians = 2.0 * PI / float(total);
    vec3 from = (u_worldToVoxel * vec4(g_coneRays.origin, 1.0)).xyz;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < total; ++i) {
        float u = (float(i) + 0.5) / float(total);
        float r = sqrt(u), phi = 6.2831853 * fract(float(i) * 0.381966 + g_coneRays.rotation);
        sum += rayLight(frame * vec3(r * cos(phi), r * sin(phi), sqrt(1.0 - u)), steradians, from);
    }
    return sum / float(total);
}
