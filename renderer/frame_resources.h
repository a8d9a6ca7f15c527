// The names of what passes exchange through the Frame, each declared once here: the shadow pass's
// lights and maps, the G-buffer's, the lighting contract's terms (what a GI method gives the
// lighting pass) and the frame's two images. A pass lists what it reads in inputs() and what it
// writes in outputs(); the renderer refuses a pass that reads what no earlier pass writes, and the
// frame refuses any access a pass did not declare (Frame::resource).
#pragma once

namespace gis::resource {

// The shadow pass.
constexpr char kLights[] = "lights";             // buffer: the lights (uniform block or storage)
constexpr char kShadowMaps[] = "shadow.maps";    // 2D array: directional and spot lights
constexpr char kShadowCubes[] = "shadow.cubes";  // 2D array of cube faces: point lights

// The G-buffer.
constexpr char kGbufferDepth[] = "gbuffer.depth";
constexpr char kGbufferBaseColor[] = "gbuffer.baseColor";
constexpr char kGbufferNormal[] = "gbuffer.normal";
constexpr char kGbufferMaterial[] = "gbuffer.material";
constexpr char kGbufferEmissive[] = "gbuffer.emissive";

// The lighting contract: each optional; the lighting pass is compiled for the ones produced.
constexpr char kAo[] = "ao";                               // R: ambient occlusion, 1 = open
constexpr char kIndirectDiffuse[] = "indirect.diffuse";    // RGB: incoming irradiance / pi
constexpr char kIndirectSpecular[] = "indirect.specular";  // RGB: prefiltered incoming radiance

// Emitters as lights of the direct pass (renderer/emitters): their ReSTIR-sampled direct light,
// which the lighting pass adds.
constexpr char kEmittersDirect[] = "emitters.direct";

// The frame's images.
constexpr char kRadiance[] = "radiance";  // linear radiance (or a standalone method's image)
constexpr char kDisplay[] = "display";    // tone-mapped, what is shown and saved as PNG

}  // namespace gis::resource
