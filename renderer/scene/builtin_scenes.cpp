// Built-in scenes, built procedurally. The Cornell scenes reproduce shared/assets/reference/scenes/
// exactly (same meshes, vertex order, winding, materials, node transforms, camera and light), so a
// renderer can be compared with the Cycles references without loading a file. brdf-gallery is the
// BRDF chart: spheres of every roughness, dielectric and metal, one row per BRDF combination.
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "scene/mesh_builders.h"
#include "scene/scene_internal.h"
#include "scene/scene_lighting.h"

namespace gis {
namespace {

using namespace detail;

// The Cornell scenes' materials, in the order makeCornell adds them.
enum CornellMaterial { kWhite, kRed, kGreen, kLight };

// Mesh "Walls": floor + ceiling + back wall (white), left wall (red), right wall (green).
// Single-sided quads facing the inside of the box; the box is open at z = +1.
void addCornellWalls(Scene& s) {
    Primitive white;
    white.material = kWhite;
    addQuad(white, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, {0, 1, 0});   // floor
    addQuad(white, {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}}, {0, -1, 0});  // ceiling
    addQuad(white, {{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}}, {0, 0, 1});  // back
    Primitive red;
    red.material = kRed;
    addQuad(red, {{-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1}}, {1, 0, 0});
    Primitive green;
    green.material = kGreen;
    addQuad(green, {{1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}}, {-1, 0, 0});
    s.primitives = {white, red, green};
    for (int i = 0; i < 3; ++i) s.draws.push_back(DrawItem{i, glm::mat4(1.0f)});
}

// Emitter quad just below the ceiling, facing down (-Y), one-sided.
void addCornellEmitter(Scene& s, float emitterSize, int emitterTiles) {
    Primitive quad;
    quad.material = kLight;
    const float y = 1.999f, e = emitterSize > 0.0f ? 0.5f * emitterSize : 0.25f;
    const float step = 2.0f * e / float(emitterTiles);
    for (int i = 0; i < emitterTiles; ++i)
        for (int k = 0; k < emitterTiles; ++k) {
            const float x0 = -e + step * float(i), z0 = -e + step * float(k);
            const float x1 = i + 1 == emitterTiles ? e : x0 + step, z1 = k + 1 == emitterTiles ? e : z0 + step;
            addQuad(quad, {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}}, {0, -1, 0});
        }
    s.primitives.push_back(quad);
    s.draws.push_back(DrawItem{static_cast<int>(s.primitives.size()) - 1, glm::mat4(1.0f)});
}

// emitterSize: the area light's edge in metres, its radiance scaled to keep its power; 0 = the
// reference glTF's 0.5 m quad of radiance 15. emitterTiles: the quad cut into tiles x tiles quads
// (2 tiles^2 emissive triangles, the same light): what the emitters' cost grows with.
Scene makeCornell(bool areaLight, float emitterSize = 0.0f, int emitterTiles = 1) {
    Scene s;
    s.name = areaLight ? "cornell-area" : "cornell";
    s.background = glm::vec3(0.0f);

    s.materials.push_back(lambert("White", {0.73f, 0.73f, 0.73f}));
    s.materials.push_back(lambert("Red", {0.63f, 0.065f, 0.05f}));
    s.materials.push_back(lambert("Green", {0.14f, 0.45f, 0.091f}));
    if (areaLight) {
        Material light = lambert("Light", {0.0f, 0.0f, 0.0f});
        light.emissive = glm::vec3(1.0f) * 15.0f;  // emissiveFactor (1,1,1) * emissiveStrength 15
        if (emitterSize > 0.0f) light.emissive *= (0.5f / emitterSize) * (0.5f / emitterSize);  // equal power
        s.materials.push_back(light);
    }

    addCornellWalls(s);
    if (areaLight) addCornellEmitter(s, emitterSize, emitterTiles);

    // Blocks: unit cubes placed by node TRS (rotation about +Y by +-17 degrees).
    const double half = 0.5 * 17.0 * 3.14159265358979323846 / 180.0;
    const glm::dquat rotPos(std::cos(half), 0.0, std::sin(half), 0.0);
    const glm::dquat rotNeg(std::cos(half), 0.0, -std::sin(half), 0.0);
    s.primitives.push_back(unitCube(kWhite));
    s.draws.push_back(DrawItem{static_cast<int>(s.primitives.size()) - 1,
                               detail::composeTrs({-0.33, 0.6, -0.29}, rotPos, {0.6, 1.2, 0.6})});
    s.primitives.push_back(unitCube(kWhite));
    s.draws.push_back(DrawItem{static_cast<int>(s.primitives.size()) - 1,
                               detail::composeTrs({0.33, 0.3, 0.3}, rotNeg, {0.6, 0.6, 0.6})});

    Camera cam;
    cam.name = "RefCamera";
    cam.cameraToWorld = detail::composeTrs({0.0, 1.0, 3.9}, glm::dquat(1, 0, 0, 0), {1, 1, 1});
    cam.orthographic = false;
    cam.yfov = 0.6981317f;  // 40 degrees, full vertical angle
    cam.znear = 0.01f;
    cam.zfar = 100.0f;
    s.cameras.push_back(cam);

    if (!areaLight) {
        Light l;
        l.name = "PointLight";
        l.type = LightType::Point;
        l.color = glm::vec3(1.0f);
        l.intensity = 1.2f;
        l.range = 0.0f;
        l.position = glm::vec3(0.0f, 1.8f, 0.0f);
        l.direction = glm::vec3(0.0f, 0.0f, -1.0f);
        s.lights.push_back(l);
    }

    finalizeScene(s);
    return s;
}

// ---- brdf-gallery ------------------------------------------------------------------------------

// BRDF model ids as in gis::DiffuseModel / SpecularModel (renderer.h; this library has no GL).
enum GalleryDiffuse { kLambert = 0, kWrap = 1, kToonDiffuse = 2, kBurley = 3 };
enum GallerySpecular { kGgx = 0, kBlinnPhong = 1, kToonSpecular = 2, kNoSpecular = 3 };

// The spheres: one row per BRDF combination, one column per roughness, dielectric then metal.
void addGallerySpheres(Scene& s) {
    // Rows, top of the image (far) to bottom (near): every diffuse and every specular model appears.
    struct Row { const char* name; int diffuse, specular; };
    const Row rows[] = {{"lambert+ggx", kLambert, kGgx},      {"burley+ggx", kBurley, kGgx},
                        {"wrap+ggx", kWrap, kGgx},            {"lambert+blinn", kLambert, kBlinnPhong},
                        {"toon+toon", kToonDiffuse, kToonSpecular}, {"burley+none", kBurley, kNoSpecular}};
    const int rowCount = int(sizeof(rows) / sizeof(rows[0]));
    // Columns, left to right: roughness 0 .. 1 dielectric, then the same for metal.
    const float roughness[5] = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
    const glm::vec3 dielectricColor(0.80f, 0.12f, 0.08f);  // red plastic
    const glm::vec3 metalColor(0.95f, 0.72f, 0.38f);       // gold
    const float radius = 0.4f, spacingX = 1.0f, spacingZ = 1.4f, groupGap = 0.5f;

    const Primitive sphere = uvSphere(radius, 48, 24, 0);
    for (int r = 0; r < rowCount; ++r) {
        const float z = spacingZ * (float(r) - 0.5f * float(rowCount - 1));
        for (int c = 0; c < 10; ++c) {
            const bool metal = c >= 5;
            Material m;
            m.name = std::string(rows[r].name) + (metal ? " metal r" : " dielectric r") +
                     std::to_string(roughness[c % 5]).substr(0, 4);
            m.baseColorFactor = glm::vec4(metal ? metalColor : dielectricColor, 1.0f);
            m.metallicFactor = metal ? 1.0f : 0.0f;
            m.roughnessFactor = roughness[c % 5];
            m.specularFactor = 1.0f;
            m.diffuseModel = rows[r].diffuse;
            m.specularModel = rows[r].specular;
            s.materials.push_back(m);
            Primitive p = sphere;
            p.material = int(s.materials.size()) - 1;
            s.primitives.push_back(p);
            const float x = spacingX * (float(c) - 4.5f) + (metal ? 0.5f : -0.5f) * groupGap;
            s.draws.push_back({int(s.primitives.size()) - 1,
                               glm::translate(glm::mat4(1.0f), glm::vec3(x, radius, z))});
        }
    }
}

// Checkered floor of 0.5 m squares: two Lambert materials, whatever the render's BRDF flags.
void addGalleryFloor(Scene& s) {
    const glm::vec3 checkColor[2] = {glm::vec3(0.45f), glm::vec3(0.18f)};
    Primitive checks[2];
    for (int k = 0; k < 2; ++k) {
        Material m;
        m.name = k == 0 ? "floor light" : "floor dark";
        m.baseColorFactor = glm::vec4(checkColor[k], 1.0f);
        m.metallicFactor = 0.0f;
        m.roughnessFactor = 1.0f;
        m.specularFactor = 0.0f;
        m.diffuseModel = kLambert;
        m.specularModel = kNoSpecular;
        s.materials.push_back(m);
        checks[k].material = int(s.materials.size()) - 1;
    }
    const float check = 0.5f;
    const int nx = 36, nzFar = 36, nzNear = 16;  // x in [-9, 9], z in [-18, 8]
    for (int i = -nx / 2; i < nx / 2; ++i)
        for (int k = -nzFar; k < nzNear; ++k) {
            const float x0 = check * float(i), z0 = check * float(k), x1 = x0 + check, z1 = z0 + check;
            addQuad(checks[(i + k) & 1], {{x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}}, {0, 1, 0});
        }
    for (Primitive& p : checks) {
        s.primitives.push_back(p);
        s.draws.push_back({int(s.primitives.size()) - 1, glm::mat4(1.0f)});
    }
}

Scene makeBrdfGallery() {
    Scene s;
    s.name = "brdf-gallery";
    s.background = glm::vec3(0.02f, 0.025f, 0.03f);

    addGallerySpheres(s);
    addGalleryFloor(s);

    // Key light from the upper left, on the camera's side: highlights face the viewer and the
    // shadows fall back and to the right, between the rows.
    Light key;
    key.name = "Key";
    key.type = LightType::Directional;
    key.intensity = 3.0f;  // W/m^2 at normal incidence
    key.direction = glm::normalize(glm::vec3(0.55f, -1.0f, -0.45f));
    s.lights.push_back(key);

    // Looking down 50 degrees with a long lens, so near and far rows differ little in size. Framed
    // for 4:3 (e.g. --size 1024x768); wider images show more floor, narrower ones crop the sides.
    Camera cam;
    cam.name = "Gallery";
    const glm::vec3 target(0.0f, 0.35f, 0.3f);
    const float elevation = glm::radians(50.0f), distance = 24.0f;
    const glm::vec3 eye = target + distance * glm::vec3(0.0f, std::sin(elevation), std::cos(elevation));
    cam.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    cam.yfov = glm::radians(22.0f);
    cam.znear = 5.0f;
    cam.zfar = 60.0f;
    s.cameras.push_back(cam);

    finalizeScene(s);
    return s;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
    return {"cornell", "cornell-area", "brdf-gallery", "leak", "room", "mirror", "atrium", "building"};
}

Scene makeBuiltinScene(const std::string& spec) {
    // NAME or NAME?key=value&key=value (builtin:leak?thickness=0.01&doorway=1).
    const size_t q = spec.find('?');
    const std::string name = spec.substr(0, q);
    const detail::SceneOptions options = detail::parseSceneOptions(spec, q == std::string::npos ? "" : spec.substr(q + 1));
    if (name == "leak") return detail::makeLeakScene(options);
    if (name == "room") return detail::makeRoomScene(options);
    if (name == "mirror") return detail::makeMirrorScene(options);
    if (name == "atrium") return detail::makeAtriumScene(options);
    if (name == "building") return detail::makeBuildingScene(options);
    if (name == "cornell-area") {
        for (const auto& [key, value] : options)
            if (key != "emitter-size" && key != "emitter-tiles")
                throw Error("builtin:cornell-area: unknown option '" + detail::oneLine(key, 40) +
                            "' (expected emitter-size or emitter-tiles)");
        auto size = options.find("emitter-size"), tiles = options.find("emitter-tiles");
        if (size != options.end() && !(size->second >= 0.01 && size->second <= 2.0))
            throw Error("builtin:cornell-area: emitter-size " + detail::oneLine(std::to_string(size->second), 40) +
                        " is out of range [0.01, 2] (metres)");
        if (tiles != options.end() && !(tiles->second >= 1 && tiles->second <= 100 && tiles->second == std::floor(tiles->second)))
            throw Error("builtin:cornell-area: emitter-tiles " + detail::oneLine(std::to_string(tiles->second), 40) +
                        " is not a whole number in [1, 100]");
        return makeCornell(true, size == options.end() ? 0.0f : float(size->second),
                           tiles == options.end() ? 1 : int(tiles->second));
    }
    if (!options.empty()) throw Error("built-in scene '" + detail::oneLine(name, 80) + "' takes no options");
    if (name == "cornell") return makeCornell(false);
    if (name == "cornell-area") return makeCornell(true);
    if (name == "brdf-gallery") return makeBrdfGallery();
    std::string list;
    for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
    throw Error("unknown built-in scene '" + detail::oneLine(spec, 80) + "' (" + didYouMean(name, builtinSceneNames()) +
                "available: " + list + ")");
}

}  // namespace gis
