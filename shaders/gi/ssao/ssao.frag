// Screen-space ambient occlusion over the G-buffer (after Crytek, Mittring 2007, with a
// normal-oriented hemisphere): for each of u_kernelSize cosine-distributed directions around the
// normal, a few points along it out to u_aoRadius (denser near the centre) are tested against the
// depth buffer; a direction is occluded if the march crosses a visible surface, i.e. one of its
// points lies behind the depth buffer by less than the step that brought it there (the range
// check: surfaces farther in front are other objects the direction passes behind - no halos). AO = unoccluded directions / usable directions, which estimates the same
// cosine-weighted visibility the ray-traced reference computes. Directions that leave the screen
// before hitting anything carry no information and are left out (no darkening at the borders).
#include "gi/ssao/ssao_common.glsl"

layout(location = U_AO_KERNEL_SIZE) uniform int u_kernelSize;
layout(location = U_AO_KERNEL) uniform vec4 u_kernel[MAX_AO_KERNEL];  // xyz unit direction (+Z = normal)

in vec2 v_uv;
layout(location = 0) out vec4 o_ao;   // r = AO, g = view-space depth (for the bilateral blur)

void main() {
    float depth = texture(s_depth, v_uv).r;
    if (depth >= 1.0) {
        o_ao = vec4(1.0, -1e30, 0.0, 1.0);
        return;
    }
    vec3 P = viewPosition(v_uv, depth);
    vec3 N = normalize(mat3(u_view) * texture(s_gbufNormal, v_uv).xyz);
    // Rotate the kernel about the normal by the tiled noise: banding becomes 4x4 noise the blur removes.
    vec3 r = vec3(noiseRotation(), 0.0);
    vec3 T = r - N * dot(r, N);
    T = dot(T, T) > 1e-8 ? normalize(T) : normalize(abs(N.y) < 0.99 ? cross(N, vec3(0, 1, 0)) : cross(N, vec3(1, 0, 0)));
    vec3 B = cross(N, T);

    float radius = max(u_aoRadius, 1e-30);
    float bias = u_ao.bias * radius;
    int steps = max(u_ao.steps, 1);
    int usable = 0, occluded = 0;
    for (int i = 0; i < min(u_kernelSize, MAX_AO_KERNEL); ++i) {
        vec3 dir = T * u_kernel[i].x + B * u_kernel[i].y + N * u_kernel[i].z;
        bool hit = false, offScreen = false;
        for (int s = 1; s <= steps && !hit; ++s) {
            float t = float(s) / float(steps);
            // Quadratic spacing: denser near the centre. The march starts one bias above the surface
            // so points along near-tangent directions are not compared against the surface
            // itself (streaks on surfaces seen at grazing angles).
            vec3 q = P + N * bias + dir * (radius * t * t);
            vec4 clip = u_proj * vec4(q, 1.0);
            if (clip.w <= 0.0) { offScreen = true; break; }
            vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
            if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) { offScreen = true; break; }
            // Bilinear depth (the pass binds a linear sampler): window-space depth is linear across
            // a plane, so this is the surface's exact depth at q's position, not the nearest pixel
            // centre's - which on surfaces seen at grazing angles differs by more than any bias.
            float sceneDepth = texture(s_depth, uv).r;
            // Across a silhouette the bilinear value is a surface that does not exist (between the
            // plate and the floor behind it); there take the farthest of the four texels instead.
            vec4 corners = textureGather(s_depth, uv, 0);
            float nearest = min(min(corners.x, corners.y), min(corners.z, corners.w));
            float farthest = max(max(corners.x, corners.y), max(corners.z, corners.w));
            if (farthest < 1.0 && viewPosition(uv, nearest).z - viewPosition(uv, farthest).z > 0.5 * radius)
                sceneDepth = farthest;
            if (sceneDepth >= 1.0) continue;
            vec3 S = viewPosition(uv, sceneDepth);  // the surface the camera sees there
            float inFront = S.z - q.z;               // > 0: that surface is nearer the camera than q
            // Range check: that surface occludes if the march crossed it within the last step, or
            // if it lies within the radius of P (a wall seen at a grazing angle is deep in view
            // depth yet close). A surface that is neither is another object the direction
            // passes behind - no halo around a floating plate.
            float prev = float(s - 1) / float(steps);
            bool crossed = inFront < radius * (t * t - prev * prev) + bias;
            hit = inFront > bias && (crossed || distance(S, P) < radius);
        }
        if (offScreen && !hit) continue;
        ++usable;
        if (hit) ++occluded;
    }
    float ao = usable > 0 ? 1.0 - float(occluded) / float(usable) : 1.0;
    o_ao = vec4(pow(saturate(ao), max(u_ao.power, 1e-3)), P.z, 0.0, 1.0);
}
