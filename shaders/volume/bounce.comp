// A further bounce: each occupied voxel gathers the incoming radiance of the current chain with the
// diffuse cones around its mean normal and adds albedo * (E / pi) to what injection gave it
// (direct light and emission, in s_direct). A slab voxel (a wall thinner than a voxel,
// volume/voxel_faces.glsl) gathers for each of its two faces apart, into its room, and keeps their
// difference in the sides as injection does: gathered around the mean normal, one face's light
// (a sunlit roof's sky) reached the room on the other side.
#include "common.glsl"
#ifndef BOUNCE_RAYS
#define BOUNCE_RAYS 0
#endif
#if BOUNCE_RAYS
#define CONE_RAYS
#endif
#include "volume/cone_trace.glsl"
#include "volume/voxel_faces.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = TV_BOUNCE_ALBEDO) uniform sampler3D s_albedo;
layout(binding = TV_BOUNCE_NORMAL) uniform sampler3D s_normal;
layout(binding = TV_BOUNCE_DIRECT) uniform sampler3D s_direct;
layout(binding = TV_BOUNCE_DIRECT_SIDES) uniform sampler3D s_directSides;  // inject.comp's i_sides
layout(rgba16f, binding = IV_BOUNCE_RADIANCE) uniform writeonly image3D i_radiance;
layout(rgba16f, binding = IV_BOUNCE_SIDES) uniform writeonly image3D i_sides;

layout(location = UV_RESOLUTION) uniform int u_resolution;
layout(location = UV_CONE_SET) uniform int u_coneSet;
ConeTraceBlock u_cones;
layout(location = UV_ANISOTROPIC) uniform int u_anisotropic;

#if BOUNCE_RAYS
// The cones' rays (vct.sky-rays), as the pixels' (gi/vct/vct_trace.comp), from off the voxel's face.
#include "ray_scene.glsl"
layout(location = UV_VOXEL_TO_WORLD) uniform mat4 u_voxelToWorld;
layout(location = UV_WORLD_TO_VOXEL) uniform mat4 u_worldToVoxel;
#include "volume/cone_rays.glsl"
#endif

// The diffuse cones' gather for a face through `centre` (voxel units) facing n: E / pi, and the
// share of its rays or cones that met something (1 - what reached the sky).
vec4 gatherAround(vec3 centre, vec3 n) {
#if BOUNCE_RAYS
    // Half a voxel out along an axis clears both faces of a slab; sqrt(3)/2 clears any plane
    // through the voxel facing n.
    float clearance = abs(n.x) + abs(n.y) + abs(n.z) > 1.001 ? 0.87 : 0.5;
    g_coneRays = ConeRaySource((u_voxelToWorld * vec4(centre + n * clearance, 1.0)).xyz,
                               fract(dot(centre, vec3(0.7548776, 0.5698403, 0.3846154))), u_cones.skyRays, true,
                               vec3(0.0));
#endif
    ConeTracer t = makeConeTracer(u_resolution, u_cones.stepFactor, u_cones.maxDistance, u_anisotropic);
    return traceDiffuse(t, centre + n * u_cones.offset, n, u_coneSet, 1.0, 0.0);
}

// Closer than this in how much of the sky they see, two sides of a junction are as enclosed.
#define JUNCTION_SKY_TIE 0.1
#if BOUNCE_RAYS
// The rays over the sphere by which a junction's side measures how much sky it sees.
#define JUNCTION_SKY_RAYS 16

// The share of JUNCTION_SKY_RAYS rays over the whole sphere (a spherical Fibonacci set about +Y)
// from p (voxel units) that leave the scene. A face's own gather is no measure of it: a ceiling's
// gather looks down, and beside a room, under the sky, it sees the ground as a room's floor.
float skyShare(vec3 p) {
    vec3 origin = (u_voxelToWorld * vec4(p, 1.0)).xyz;
    int open = 0;
    for (int i = 0; i < JUNCTION_SKY_RAYS; ++i) {
        vec2 u = vec2((float(i) + 0.5) / float(JUNCTION_SKY_RAYS), fract(float(i) * 0.381966));  // golden angle
        Hit h;
        if (!traceRay(origin, uniformSphereDirection(u).xzy, 1e30, true, h)) ++open;
    }
    return float(open) / float(JUNCTION_SKY_RAYS);
}
#endif

// A slab face's gather. Where a junction's wall crosses the slab (volume/voxel_faces.glsl), the
// voxel's centre may lie beyond that wall from where the face is seen: the floor or the ceiling at
// a room's outer wall, gathered from outside it, showed the room the sky. There the face gathers on
// both sides of the junction's wall and keeps the side that sees less sky (a building's inside,
// whose floor and ceiling are what the rays that meet them see; with rays, measured over the whole
// sphere, skyShare; with cones, the share of the gather's cones that met something); between two
// rooms, each as enclosed as the other, the mean of the two. A side where most rays start inside a
// solid (a wall's face below the floor it stands on) is no side: the other one's. `plusShare`: how
// much of the result is the + side's (1 without a junction).
vec3 faceGather(ivec3 v, vec4 normalTexel, vec3 centre, vec3 n, out float plusShare) {
    plusShare = 1.0;
    if (voxelJunctionAxis(normalTexel) < 0) return gatherAround(centre, n).rgb;
    vec4 side[2];
    bool inside[2];
    float sky[2];
    for (int i = 0; i < 2; ++i) {
        vec3 p = voxelJunctionSide(v, normalTexel, centre, i == 0 ? 1.0 : -1.0);
#if BOUNCE_RAYS
        g_raysStartedInside = 0;
#endif
        side[i] = gatherAround(p, n);
#if BOUNCE_RAYS
        inside[i] = 2 * g_raysStartedInside > g_coneRays.count * diffuseConeCount(u_coneSet);
        sky[i] = skyShare(p + n * 0.5);
#else
        inside[i] = false;
        sky[i] = 1.0 - side[i].a;
#endif
    }
    if (inside[0] != inside[1]) plusShare = inside[0] ? 0.0 : 1.0;
    else if (abs(sky[0] - sky[1]) < JUNCTION_SKY_TIE) plusShare = 0.5;
    else plusShare = sky[0] < sky[1] ? 1.0 : 0.0;
    return mix(side[1].rgb, side[0].rgb, plusShare);
}

#if BOUNCE_RAYS
// The punctual lights' light on a junction slab's face facing n where it gathered (plusShare of it
// on the junction's + side), lit as injection lights a face, its shadow one voxel in front: lit at
// the voxel's centre, the wall under a sunlit roof's edge took the roof top's sun and showed it to
// the hall below (builtin:building).
vec3 junctionFacePunctual(ivec3 v, vec4 normalTexel, vec3 centre, vec3 n, float plusShare, vec3 albedo) {
    vec3 irradiance = vec3(0.0);
    for (int s = 0; s < 2; ++s) {
        float share = s == 0 ? plusShare : 1.0 - plusShare;
        if (share <= 0.0) continue;
        vec3 c = voxelJunctionSide(v, normalTexel, centre, s == 0 ? 1.0 : -1.0);
        vec3 P = (u_voxelToWorld * vec4(c, 1.0)).xyz, Ps = (u_voxelToWorld * vec4(c + n, 1.0)).xyz;
        irradiance += share * hitPunctualIrradiance(P, Ps, n);
    }
    return albedo * INV_PI * irradiance;
}
#endif

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(v, ivec3(u_resolution)))) return;
    vec4 direct = texelFetch(s_direct, v, 0);
    vec4 sides = texelFetch(s_directSides, v, 0);
    vec4 albedo = texelFetch(s_albedo, v, 0);
    vec4 normalTexel = texelFetch(s_normal, v, 0);
    vec3 meanNormal = normalTexel.xyz * 2.0 - 1.0;
    float len = length(meanNormal);
    int slab = voxelSlabAxis(sides);
    // direct.a 0 on a surface voxel: an unlit outside left out of the volume (exterior.comp).
    if (albedo.a == 0.0 || (slab < 0 && len < VOXEL_TWO_SIDED) || direct.a == 0.0) {
        imageStore(i_radiance, v, direct);
        imageStore(i_sides, v, sides);
        return;
    }
    vec3 centre = vec3(v) + 0.5;
    vec3 radiance = direct.rgb;
    if (slab >= 0) {
        vec3 axis = vec3(0.0);
        axis[slab] = 1.0;
        float frontPlus, backPlus;
        vec3 front = albedo.rgb * faceGather(v, normalTexel, centre, axis, frontPlus);
        vec3 back = albedo.rgb * faceGather(v, normalTexel, centre, -axis, backPlus);
#if BOUNCE_RAYS
        if (voxelJunctionAxis(normalTexel) >= 0) {
            // The punctual share relit where the faces gathered, where that is darker: the light
            // carried across the junction's wall goes, and none comes in that the shadow looked up
            // a coarse voxel in front lets through a window beside the face.
            vec3 punctual = texelFetch(s_voxelPunctual, v, 0).rgb;
            vec3 frontLit = junctionFacePunctual(v, normalTexel, centre, axis, frontPlus, albedo.rgb);
            vec3 backLit = junctionFacePunctual(v, normalTexel, centre, -axis, backPlus, albedo.rgb);
            if (luminance(frontLit) > luminance(punctual + sides.rgb)) frontLit = punctual + sides.rgb;
            if (luminance(backLit) > luminance(punctual - sides.rgb)) backLit = punctual - sides.rgb;
            radiance += 0.5 * (frontLit + backLit) - punctual;
            sides.rgb = 0.5 * (frontLit - backLit);
        }
#endif
        radiance += 0.5 * (front + back);
        sides.rgb += 0.5 * (front - back);
    } else {
        radiance += albedo.rgb * gatherAround(centre, meanNormal / len).rgb;
    }
    imageStore(i_radiance, v, vec4(min(finiteOrZero(radiance), vec3(MAX_HALF_FLOAT)), direct.a));
    imageStore(i_sides, v, vec4(clamp(finiteOrZero(sides.rgb), vec3(-MAX_HALF_FLOAT), vec3(MAX_HALF_FLOAT)), sides.a));
}
