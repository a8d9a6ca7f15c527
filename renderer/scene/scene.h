// CPU-side scene: what a glTF file (or a built-in scene) becomes before anything touches the GPU.
// No GL here, so the loader can be tested, sanitized and fuzzed on its own.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "error.h"

namespace gis {

struct Aabb {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    bool empty() const { return min.x > max.x; }
    void extend(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }
};

// Decoded texture, always 8-bit RGBA. Colour space is decided by the material slot that uses it
// (baseColor and emissive are sRGB, the others linear); `srgb` records the first such use.
struct Image {
    std::string name;
    int width = 0;
    int height = 0;
    bool srgb = false;
    std::vector<uint8_t> rgba8;  // width * height * 4, rows top to bottom as stored in the file
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF PBR metallic-roughness material. Texture fields index Scene::images, -1 = none.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    glm::vec3 emissive{0.0f};         // emissiveFactor * KHR_materials_emissive_strength: radiance
    float specularFactor = 1.0f;      // KHR_materials_specular; 0 = no specular lobe (ideal Lambert)
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;
    float alphaCutoff = 0.5f;
    AlphaMode alphaMode = AlphaMode::Opaque;
    bool doubleSided = false;
    int baseColorTexture = -1;
    int metallicRoughnessTexture = -1;
    int normalTexture = -1;
    int emissiveTexture = -1;
    int occlusionTexture = -1;
    // Per-material BRDF models (values of gis::DiffuseModel / SpecularModel; -1 = the render's
    // --diffuse / --specular setting). Not read from glTF; built-in scenes such as brdf-gallery set
    // them to show several models in one image. Carried to the lighting pass in the G-buffer.
    int diffuseModel = -1;
    int specularModel = -1;
};

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w = bitangent sign
    glm::vec2 uv{0.0f};
    glm::vec4 color{1.0f};                       // COLOR_0, white when absent
};

// One glTF primitive, triangles only, always indexed (non-indexed input gets 0..n-1).
// Positions are in the mesh's object space; DrawItem places it in the world.
struct Primitive {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // 3 per triangle, every index < vertices.size()
    int material = -1;              // index into Scene::materials; -1 = default material
    Aabb bounds;                    // object space
    // TEXCOORD_1, one per vertex: the file's lightmap UVs (renderer/lightmap/ checks their charts
    // before using them). Empty when the file has none; values kept as read, NaN included.
    std::vector<glm::vec2> uv1;
};

struct DrawItem {
    int primitive = 0;              // index into Scene::primitives
    glm::mat4 world{1.0f};          // object to world (node hierarchy flattened)
};

enum class LightType { Directional, Point, Spot };

// KHR_lights_punctual, in the units of shared/assets/reference/README.md: a point/spot light's
// `intensity` is radiant intensity (W/sr, irradiance I/d^2 facing it); a directional light's is
// irradiance at normal incidence. No photometric 683 lm/W factor anywhere.
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;             // 0 = infinite (no cutoff)
    float innerConeAngle = 0.0f;    // radians, spot only
    float outerConeAngle = 0.7853982f;
    glm::vec3 position{0.0f};       // world
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world, unit, the way the light travels
};

struct Camera {
    std::string name;
    glm::mat4 cameraToWorld{1.0f};  // looks down its local -Z, +Y up (glTF)
    bool orthographic = false;
    float yfov = 0.6981317f;        // full vertical angle, radians (perspective)
    float xmag = 1.0f, ymag = 1.0f; // half extents (orthographic)
    float znear = 0.01f;
    float zfar = 100.0f;            // perspective with zfar == 0 in glTF means infinite; stored as 0
};

struct Scene {
    std::string name;
    std::vector<Image> images;
    std::vector<Material> materials;
    std::vector<Primitive> primitives;
    std::vector<DrawItem> draws;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    glm::vec3 background{0.0f};     // radiance of the environment (constant colour)
    // A scene built to measure light leaking through walls names two of its cameras: one inside a
    // room no light reaches and one in a lit room. Its leak number is the first view's mean
    // radiance over the second's (bench's `leak` column); the truth is 0. -1: not such a scene.
    struct LeakCameras {
        int dark = -1, lit = -1;
    } leakCameras;
    Aabb bounds;                    // world space, over all draws
    std::vector<std::string> warnings;  // unsupported features, each reported once

    size_t triangleCount() const;   // over draws (an instanced primitive counts each time)
};

// "builtin:NAME" or a .gltf/.glb path. Throws gis::Error with a one-line message on bad input.
Scene loadScene(const std::string& spec);
Scene loadGltfFile(const std::string& path);
// Parses glTF from memory (the fuzzer's entry point). `baseDir` resolves external URIs.
Scene loadGltfMemory(const uint8_t* data, size_t size, const std::string& baseDir);
Scene makeBuiltinScene(const std::string& name);
// Writes `scene` as PATH.gltf plus PATH.bin beside it (renderer/scene/gltf_writer.cpp: geometry,
// materials, lights, cameras; no textures, no environment). Throws gis::Error on failure, and
// leaves both files as they were (scene/atomic_file.h).
void writeGltf(const Scene& scene, const std::string& path);
// The bytes writeGltf writes: the .gltf JSON naming `binName` as its buffer, and the buffer.
struct GltfBytes {
    std::string json, bin;
};
GltfBytes serializeGltf(const Scene& scene, const std::string& binName);
std::vector<std::string> builtinSceneNames();

// A perspective camera at `eye` with `znear`, against the scene's bounds: throws gis::Error
// (starting with `what`) when the depth buffer cannot resolve the scene, returns a warning
// (empty when none) when its precision will show. The one check for glTF cameras, settings
// files and the viewer's camera.
std::string checkCameraDepth(const Aabb& bounds, glm::vec3 eye, float znear, const std::string& what);

// After loading: generate missing normals (area-weighted) and, where a normal map is used,
// tangents; compute bounds; reject NaN/Inf positions. Loaders call it; scenes built by hand
// (tests, built-ins) call it too.
void finalizeScene(Scene& scene);

// A camera that frames the scene bounds from +Z (used when the file has none).
Camera defaultCamera(const Aabb& bounds, float aspect);

// --- Light and camera for scenes that bring none (renderer/scene/scene_setup.cpp).

// auto: the scene's own lights and emitters, or the default sun and sky when it has no light and
// no emission strong enough to light it (renderer/scene/scene_lighting.h);
// scene: exactly the scene's (possibly none: a black image); default: the sun and sky instead of
// the scene's lights; none: no punctual light (emission only).
enum class LightingMode { Auto, Scene, Default, None };
LightingMode parseLightingMode(const std::string& s);  // auto, scene, default, none
const char* lightingModeName(LightingMode m);
// The default: a sun of irradiance 3 from 50 degrees elevation, azimuth 30 degrees (from +Z
// towards +X), and a uniform sky of radiance 0.4, Godot's default environment in spirit.
constexpr float kDefaultSunIrradiance = 3.0f;
constexpr float kDefaultSunElevationDegrees = 50.0f;
constexpr float kDefaultSunAzimuthDegrees = 30.0f;
constexpr float kDefaultSkyRadiance = 0.4f;
bool hasOwnLighting(const Scene& scene);  // a punctual light, or emission that lights the scene
// Applies `mode`; returns true when the default sun and sky were added (the caller says so once).
bool applyLighting(Scene& scene, LightingMode mode);
// An environment map is the sky (the shipped one has the default sun in it): under one, auto adds
// no second sun and sky, as `scene` would not.
LightingMode lightingUnderEnvironment(LightingMode mode, bool environmentMap);

// Which camera to render from: the file's camera `index` (-1: the first, or `auto` framing when
// the file has none), `autoFrame` (frame the scene's bounds), or a camera at `position` looking at
// `lookAt` with a vertical field of view of `fovDegrees` (when position is set).
struct CameraRequest {
    int index = -1;
    bool autoFrame = false;
    bool hasPosition = false;
    glm::vec3 position{0.0f}, lookAt{0.0f};
    float fovDegrees = 40.0f;
};
// Resolves `request` to an index into scene.cameras, appending a camera where one is made.
// Throws gis::Error for an index the file does not have (also when it has none).
int resolveCamera(Scene& scene, const CameraRequest& request, float aspect);

}  // namespace gis
