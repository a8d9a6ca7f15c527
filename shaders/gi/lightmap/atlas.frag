// lightmap.atlas: the atlas itself, its layers side by side across the image (each as large as the
// image's height allows, texels square): the baked light of every texel on a chart, normalised by
// the brightest channel so dim charts show, the charts' border texels in magenta, the dilated
// gutter dimmed and the texels inside geometry (classify.comp) in cyan.
#include "gi/lightmap/lightmap_texels.glsl"

in vec2 v_uv;

layout(binding = TL_LIGHTMAP) uniform sampler2DArray s_lightmap;
layout(binding = TL_TEXELS) uniform sampler2DArray s_texels;    // position, w = 1 + flags
layout(location = UL_STEP) uniform int u_side;                   // the atlas array's side, texels
layout(location = UL_LAYERS) uniform int u_layers;
layout(location = UL_TARGET_SIZE) uniform vec2 u_targetSize;     // pixels
layout(location = 0) out vec4 o_colour;

bool onChart(ivec2 texel, int layer) {
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(u_side)))) return false;
    return texelOnChart(texelFetch(s_texels, ivec3(texel, layer), 0).w);
}

void main() {
    // Pixels per layer square: the layers in one row, as large as fits.
    float square = min(u_targetSize.y, u_targetSize.x / float(u_layers));
    vec2 pixel = vec2(v_uv.x * u_targetSize.x, (1.0 - v_uv.y) * u_targetSize.y);  // top-left origin
    int layer = int(floor(pixel.x / square));
    if (layer >= u_layers || pixel.y >= square) {
        o_colour = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    ivec2 texel = ivec2(vec2(pixel.x - float(layer) * square, pixel.y) / square * float(u_side));
    texel = clamp(texel, ivec2(0), ivec2(u_side - 1));
    vec4 light = texelFetch(s_lightmap, ivec3(texel, layer), 0);
    vec3 shown = light.rgb / max(max(light.r, max(light.g, light.b)), 1e-30);
    vec4 position = texelFetch(s_texels, ivec3(texel, layer), 0);
    if (!texelOnChart(position.w)) {
        shown *= 0.15;  // the gutter: what dilation spread, dimmed
    } else if ((texelFlags(position.w) & TEXEL_INSIDE) != 0) {
        shown = vec3(0.0, 1.0, 1.0);
    } else {
        for (int i = 0; i < 4; ++i)
            if (!onChart(texel + TEXEL_NEIGHBOURS[i], layer)) shown = vec3(1.0, 0.0, 1.0);
    }
    o_colour = vec4(shown, 1.0);
}
