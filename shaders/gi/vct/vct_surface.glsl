// The surfaces behind VCT's pixels and traced texels, for the passes that weigh traced texels by
// whether they lie on a pixel's surface (vct_upsample.comp, vct_sky_filter.comp). The includer
// declares s_depth, s_gbufNormal, u_invViewProj and u_traceJitter.

// A sample whose surface lies farther than this fraction of the pixel's depth off the pixel's
// tangent plane is another surface: it gets no weight, so light never blends across a step.
const float PLANE_TOLERANCE = 0.05;
const float NORMAL_POWER = 8.0;

struct Surface {
    bool valid;  // false: background
    vec3 position, normal;
};

Surface surfaceAt(ivec2 pixel) {
    ivec2 size = textureSize(s_depth, 0);
    float depth = texelFetch(s_depth, pixel, 0).r;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return Surface(depth < 1.0, world.xyz / world.w, normalize(texelFetch(s_gbufNormal, pixel, 0).xyz));
}

// The full-resolution pixel traced texel `texel` stands for this frame.
ivec2 tracedPixel(ivec2 texel) {
    return min(texel * u_traceJitter.x + u_traceJitter.yz, textureSize(s_depth, 0) - 1);
}

// How much a sample on surface `o` counts for one on `s` seen from `camera`: none off the tangent
// plane by more than PLANE_TOLERANCE of the depth, less the more the normals disagree.
float surfaceWeight(Surface s, Surface o, vec3 camera) {
    float off = abs(dot(o.position - s.position, s.normal)) / distance(s.position, camera);
    return pow(saturate(1.0 - off / PLANE_TOLERANCE), 2.0) * pow(max(dot(o.normal, s.normal), 0.0), NORMAL_POWER);
}
