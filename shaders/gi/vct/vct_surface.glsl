// The surfaces behind VCT's pixels, for the passes that weigh neighbouring samples by whether they
// lie on a pixel's surface (vct_upsample.comp, vct_sky_filter.comp) and for the trace's positions
// (vct_trace.comp). The includer declares s_depth, s_gbufNormal and u_invViewProj.

// A sample whose surface lies farther than this fraction of the pixel's depth off the pixel's
// tangent plane is another surface: it gets no weight, so light never blends across a step.
const float PLANE_TOLERANCE = 0.05;
const float NORMAL_POWER = 8.0;

struct Surface {
    bool valid;  // false: background
    vec3 position, normal;
};

// The world position behind `pixel` whose depth-buffer value is `depth`.
vec3 positionFromDepth(ivec2 pixel, float depth) {
    vec2 uv = (vec2(pixel) + 0.5) / vec2(textureSize(s_depth, 0));
    vec4 world = u_invViewProj * vec4(uv * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    return world.xyz / world.w;
}

Surface surfaceAt(ivec2 pixel) {
    float depth = texelFetch(s_depth, pixel, 0).r;
    return Surface(depth < 1.0, positionFromDepth(pixel, depth), normalize(texelFetch(s_gbufNormal, pixel, 0).xyz));
}

// How much a sample on surface `o` counts for one on `s` seen from `camera`: none off the tangent
// plane by more than PLANE_TOLERANCE of the depth, less the more the normals disagree.
float surfaceWeight(Surface s, Surface o, vec3 camera) {
    float off = abs(dot(o.position - s.position, s.normal)) / distance(s.position, camera);
    return pow(saturate(1.0 - off / PLANE_TOLERANCE), 2.0) * pow(max(dot(o.normal, s.normal), 0.0), NORMAL_POWER);
}
