// Cone tracing through the voxel radiance (renderer/volume/voxel_radiance.h), for every method that
// gathers light from the voxels. Positions and distances are in voxel units ([0, resolution]^3).
// The light's seven chains are where SceneVolume::bind() puts them (renderer/volume/volume_slots.h):
// from VOLUME_RADIANCE_UNIT the isotropic chain, then the six directional chains +X -X +Y -Y +Z -Z,
// which start at half resolution, then the slab voxels' sides (volume/voxel_faces.glsl).
#include "environment.glsl"
#include "volume/voxel_faces.glsl"

layout(binding = VOLUME_RADIANCE_UNIT + 0) uniform sampler3D s_voxelRadiance;
layout(binding = VOLUME_RADIANCE_UNIT + 1) uniform sampler3D s_voxelPosX;
layout(binding = VOLUME_RADIANCE_UNIT + 2) uniform sampler3D s_voxelNegX;
layout(binding = VOLUME_RADIANCE_UNIT + 3) uniform sampler3D s_voxelPosY;
layout(binding = VOLUME_RADIANCE_UNIT + 4) uniform sampler3D s_voxelNegY;
layout(binding = VOLUME_RADIANCE_UNIT + 5) uniform sampler3D s_voxelPosZ;
layout(binding = VOLUME_RADIANCE_UNIT + 6) uniform sampler3D s_voxelNegZ;
layout(binding = VOLUME_RADIANCE_UNIT + 7) uniform sampler3D s_voxelSides;

// Where an includer casts rays through the scene's triangles (VCT's `vct.sky-rays`,
// volume/cone_rays.glsl), the diffuse gather is theirs: voxels coarser than the walls let a cone's
// march through a thin wall and, once its footprint is wider than a room, mix in the light beyond
// the room's walls; a ray stops at the first surface. traceDiffuseRays casts as many as `cones`
// cones would, spread over the hemisphere around n by cosine, and returns E / pi and the occluded
// fraction, or a negative fraction where no rays are cast.
#ifdef CONE_RAYS
vec4 traceDiffuseRays(vec3 n, int cones);
#else
vec4 traceDiffuseRays(vec3 n, int cones) { return vec4(-1.0); }
#endif

struct ConeTracer {
    float resolution;   // voxels per edge
    float stepFactor;   // step length as a fraction of the cone's diameter there
    float maxDistance;  // voxels
    bool anisotropic;
    // Lift samples off the surface the cone leaves (below). Off where the directional chains
    // already leave out the voxels a cone sees from behind (VOXEL_CULL_BACKFACES): the cone's
    // own surface is then invisible to it and lifting would only bend the cone towards the normal.
    bool lift;
};

// The mip modes (UV_ANISOTROPIC; VoxelRadiance::mipMode): isotropic mips (0), directional mips
// (1), directional mips without back faces (2).
#define VOXEL_ISOTROPIC 0
#define VOXEL_CULL_BACKFACES 2
ConeTracer makeConeTracer(int resolution, float stepFactor, float maxDistance, int mips) {
    return ConeTracer(float(resolution), stepFactor, maxDistance, mips != VOXEL_ISOTROPIC, mips != VOXEL_CULL_BACKFACES);
}

// Level 0 around p as seen travelling dir: the voxel p lies in, if a slab, shows the face dir meets.
vec4 sampleLevel0(ConeTracer t, vec3 p, vec3 dir) {
    ivec3 v = clamp(ivec3(floor(p)), ivec3(0), ivec3(int(t.resolution) - 1));
    return voxelLightSeen(textureLod(s_voxelRadiance, p / t.resolution, 0.0), texelFetch(s_voxelSides, v, 0), -dir);
}

// Radiance and opacity seen through the voxels around p (voxel units) at level lod, travelling dir.
vec4 sampleVoxels(ConeTracer t, vec3 p, vec3 dir, float lod) {
    vec3 uvw = p / t.resolution;
    if (lod <= 0.0) return sampleLevel0(t, p, dir);
    if (!t.anisotropic) return textureLod(s_voxelRadiance, uvw, lod);
    // The directional chains start one level up; blend in from the shared finest level.
    float dlod = max(lod - 1.0, 0.0);
    vec3 w = dir * dir;
    vec4 sx = dir.x > 0.0 ? textureLod(s_voxelPosX, uvw, dlod) : textureLod(s_voxelNegX, uvw, dlod);
    vec4 sy = dir.y > 0.0 ? textureLod(s_voxelPosY, uvw, dlod) : textureLod(s_voxelNegY, uvw, dlod);
    vec4 sz = dir.z > 0.0 ? textureLod(s_voxelPosZ, uvw, dlod) : textureLod(s_voxelNegZ, uvw, dlod);
    // Opacities combine as transmittances, (1 - a) = prod (1 - a_axis)^w_axis: a cone crossing a
    // surface obliquely is stopped by it as long as the chain along the surface's normal sees it;
    // a weighted mean would let (1 - w_normal) of the cone through the surface. Radiance is the
    // opacity-weighted mean of the three chains.
    vec3 a = clamp(vec3(sx.a, sy.a, sz.a), 0.0, 0.9999);
    float alpha = 1.0 - exp(dot(w, log(1.0 - a)));
    float weight = dot(w, a);
    vec3 radiance = weight > 1e-6 ? (w.x * sx.rgb + w.y * sy.rgb + w.z * sz.rgb) / weight : vec3(0.0);
    vec4 s = vec4(radiance * alpha, alpha);
    return lod < 1.0 ? mix(sampleLevel0(t, p, dir), s, lod) : s;
}

// The fraction of the segment a -> b (a inside [lo, hi]^3) at which it leaves that box.
float boundaryCrossing(vec3 a, vec3 b, float lo, float hi) {
    vec3 d = b - a;
    vec3 bound = mix(vec3(lo), vec3(hi), greaterThan(d, vec3(0.0)));
    vec3 f = mix(vec3(1.0), (bound - a) / d, greaterThan(abs(d), vec3(1e-6)));
    return clamp(min(f.x, min(f.y, f.z)), 0.0, 1.0);
}

// The light a surface that a ray from `from` travelling `dir` met at `hit` (voxel units) sends
// back along the ray: the voxel that holds the surface, if a slab the face on the side of it the ray
// came from (judged from where the slab lies in the voxel, voxelSlabCentre: a ray from the room
// that meets the wall just under the roof, in the voxel that holds both, gets the roof's underside,
// not the sunlit top its direction's tiny upward part would pick). One voxel, not a blend: a
// trilinear blend reaches the voxels behind a wall thinner than one. Where the surface's fragments
// went to the voxel in front (a surface on a voxel boundary), that one.
vec3 surfaceLight(float resolution, vec3 from, vec3 hit, vec3 dir, out ivec3 v) {
    ivec3 last = ivec3(int(resolution) - 1);
    v = clamp(ivec3(floor(hit + dir * 0.05)), ivec3(0), last);
    vec4 light = texelFetch(s_voxelRadiance, v, 0);
    if (light.a <= 0.0) {
        v = clamp(ivec3(floor(hit - dir * 0.5)), ivec3(0), last);
        light = texelFetch(s_voxelRadiance, v, 0);
    }
    vec4 sides = texelFetch(s_voxelSides, v, 0);
    light = voxelLightSeen(light, sides, from - voxelSlabCentre(v, sides));
    return light.a > 1e-6 ? light.rgb / light.a : vec3(0.0);
}

// Front-to-back accumulation along a cone from `origin` (voxel units) with tan(half aperture)
// `tanHalf`, starting `start` voxels out. `surfaceNormal` (unit, or 0 for none) is the normal of
// the surface the cone leaves: with t.lift each sample is lifted along it until the sample's
// footprint (about one diameter around its centre, what a trilinear mip lookup blends) clears the
// surface's tangent plane, so a wide cone filters in less of the surface's own voxels (a lit
// floor lighting itself; it still sees them over part of its footprint, see renderer/gi/vct/README.md). Returns
// premultiplied radiance and opacity; `escaped` says the cone left the volume (the caller adds the
// environment for what is left); a cone that runs out of distance inside the volume adds nothing
// more (indoors, the environment would leak).
vec4 traceCone(ConeTracer t, vec3 origin, vec3 dir, float tanHalf, float start, vec3 surfaceNormal, out bool escaped) {
    vec4 acc = vec4(0.0);
    float dist = start, previousDist = 0.0;
    vec3 previous = origin;
    escaped = false;
    bool last = false;
    for (int i = 0; i < 4096 && !last && acc.a < 0.99; ++i) {
        // The step that overshoots the cone's length is cut back to it: a wide cone's steps double
        // its distance (four 90-degree cones: 1, 2, 4 ... 64 voxels) and ended exactly at the
        // length, inside the volume, so an open floor saw no sky at all.
        if (dist >= t.maxDistance) {
            dist = t.maxDistance;
            last = true;
        }
        float diameter = max(1.0, 2.0 * tanHalf * dist);
        float height = dot(dir, surfaceNormal) * dist;
        vec3 p = origin + dir * dist + (t.lift ? surfaceNormal * max(diameter - height, 0.0) : vec3(0.0));
        // Leaving the volume: one last sample where the path from the previous sample crosses the
        // boundary (half a voxel inside), so a surface in the outermost voxels (the scene's bounds
        // are fitted tightly) is not stepped over, and nothing off the cone's path is sampled.
        bool leaving = any(lessThan(p, vec3(0.0))) || any(greaterThan(p, vec3(t.resolution)));
        if (leaving) {
            float f = boundaryCrossing(previous, p, 0.5, t.resolution - 0.5);
            p = clamp(mix(previous, p, f), vec3(0.5), vec3(t.resolution - 0.5));
            diameter = max(1.0, 2.0 * tanHalf * mix(previousDist, dist, f));
        }
        float stepLength = max(diameter * t.stepFactor, 0.05);
        vec4 s = sampleVoxels(t, p, dir, log2(diameter));
        // A mip's opacity is for a path one diameter long; this step covers stepLength. The sample
        // at the boundary stands for the rest of the cone inside the volume, at least a diameter:
        // scaled down to a short step, a wall in the outermost texels let part of every cone that
        // reached it out to the environment (a closed box lost light at every gather,
        // Vct.ClosedEmissiveBoxIsAFurnace).
        float path = leaving ? max(stepLength, diameter) : stepLength;
        float alpha = 1.0 - pow(1.0 - clamp(s.a, 0.0, 0.9999), path / diameter);
        vec3 radiance = s.a > 1e-6 ? s.rgb / s.a : vec3(0.0);
        acc.rgb += (1.0 - acc.a) * alpha * radiance;
        acc.a += (1.0 - acc.a) * alpha;
        if (leaving) {
            escaped = true;
            break;
        }
        previous = p;
        previousDist = dist;
        dist += stepLength;
    }
    return acc;
}

// The radiance a cone along `dir` brings from its march `c` (premultiplied voxel light and
// opacity) and the environment for what the voxels let through where the cone left the volume;
// none where it ran out of distance inside (indoors, the environment would leak).
vec3 coneRadiance(vec4 c, vec3 dir, float tanHalf, bool escaped) {
    return c.rgb + (escaped ? 1.0 - c.a : 0.0) * environmentMissCone(dir, coneSteradians(tanHalf));
}

// The diffuse cone sets (vct.cones). Weights sum to 1: for uniform incoming radiance L the result
// is L, i.e. the cosine-weighted mean radiance E / pi.
//   0 six: 6 cones of 60 degrees, one along the normal weighing 0.25 and five at 60 degrees from
//     it, 0.15 each (the set Godot's voxel GI uses);
//   1 four: 4 cones of 90 degrees at 45 degrees from the normal, 0.25 each;
//   2 many: 32 cones of about 14 degrees half-angle whose axes are spread by cosine (a Fibonacci
//     spiral over the unit disk lifted onto the hemisphere, Malley's method), so each stands for an
//     equal share of E and weighs 1/32; their solid angles together are the hemisphere's 2 pi. They
//     are narrow enough that a cone rarely grows wider than part of a room (where the directional
//     chains mix walls and ceiling by direction alone) and sample a small bright source from more
//     directions: 8x the trace of the six (renderer/gi/vct/README.md, measured).
const int MANY_CONES = 32;
int diffuseConeCount(int coneSet) { return coneSet == 0 ? 6 : coneSet == 1 ? 4 : MANY_CONES; }

void diffuseCone(int coneSet, int i, out vec3 dirTangent, out float tanHalf, out float weight) {
    if (coneSet == 0) {
        tanHalf = 0.57735;  // tan(30 degrees)
        if (i == 0) {
            dirTangent = vec3(0.0, 0.0, 1.0);
            weight = 0.25;
            return;
        }
        float phi = float(i - 1) * (2.0 * 3.14159265 / 5.0);
        dirTangent = vec3(0.866025 * cos(phi), 0.866025 * sin(phi), 0.5);
        weight = 0.15;
        return;
    }
    if (coneSet == 1) {
        tanHalf = 1.0;  // tan(45 degrees)
        float phi = float(i) * (3.14159265 / 2.0) + 3.14159265 / 4.0;
        dirTangent = vec3(0.707107 * cos(phi), 0.707107 * sin(phi), 0.707107);
        weight = 0.25;
        return;
    }
    float u = (float(i) + 0.5) / float(MANY_CONES);  // equal areas of the unit disk
    float r = sqrt(u), phi = float(i) * 2.39996323;   // the golden angle
    dirTangent = vec3(r * cos(phi), r * sin(phi), sqrt(1.0 - u));
    tanHalf = tan(sqrt(2.0 / float(MANY_CONES)));     // pi * halfAngle^2 = 2 pi / MANY_CONES
    weight = 1.0 / float(MANY_CONES);
}

// An orthonormal basis around n whose first tangent points as far up (+Y) as the surface allows.
// Five or four cones cannot be symmetric under every rotation: tied to "up", mirror-image
// surfaces (the two side walls of a room) get mirror-image cones and so the same light.
mat3 tangentFrame(vec3 n) {
    vec3 up = abs(n.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, -1.0);
    vec3 t = normalize(up - n * dot(n, up));
    return mat3(t, cross(n, t), n);
}

// Cosine-weighted mean incoming radiance (E / pi) at a surface point with normal n, and the
// occlusion (mean opacity) of the cones. Cones that leave the volume see the environment
// (environment.glsl, averaged over the cone's solid angle). The cone
// set is turned about n by `rotation` (a fraction of a full turn; for methods that vary it over
// pixels or frames and filter, which a fixed set of a few cones otherwise aliases).
vec4 traceDiffuse(ConeTracer t, vec3 origin, vec3 n, int coneSet, float start, float rotation) {
    vec4 rays = traceDiffuseRays(n, diffuseConeCount(coneSet));
    if (rays.a >= 0.0) return rays;
    mat3 frame = tangentFrame(n);
    float angle = rotation * 6.2831853;
    frame = mat3(frame[0] * cos(angle) + frame[1] * sin(angle), -frame[0] * sin(angle) + frame[1] * cos(angle), frame[2]);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < diffuseConeCount(coneSet); ++i) {
        vec3 d;
        float tanHalf, weight;
        diffuseCone(coneSet, i, d, tanHalf, weight);
        bool escaped;
        vec4 c = traceCone(t, origin, frame * d, tanHalf, start, n, escaped);
        c.rgb = coneRadiance(c, frame * d, tanHalf, escaped);
        sum += weight * c;
    }
    return sum;
}
