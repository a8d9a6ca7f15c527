// How the G-buffer carries a material's BRDF model override to the lighting pass: both models in
// the normal target's w (RGBA16F holds these small integers exactly). 0, the clear value, means
// "the render's --diffuse / --specular"; otherwise (diffuse + 1) + 16 * (specular + 1), each part
// 0 when that model is not overridden.
float encodeBrdfOverride(ivec2 models) {
    ivec2 m = clamp(models, ivec2(-1), ivec2(14)) + 1;
    return float(m.x + 16 * m.y);
}

// The models to use at a pixel: the override where there is one, else `global`.
ivec2 decodeBrdfOverride(float encoded, ivec2 global) {
    int e = int(round(encoded));
    int d = (e & 15) - 1, s = ((e >> 4) & 15) - 1;
    return ivec2(d >= 0 ? d : global.x, s >= 0 ? s : global.y);
}

// The world position of full-resolution pixel `pixel` of a depth target of `size`, through the
// inverse view-projection; false where no surface was drawn (the background).
bool gbufferPosition(sampler2D depth, mat4 invViewProj, ivec2 pixel, out vec3 position) {
    ivec2 size = textureSize(depth, 0);
    float d = texelFetch(depth, pixel, 0).r;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec4 world = invViewProj * vec4(uv * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
    position = world.xyz / world.w;
    return d < 1.0;
}
