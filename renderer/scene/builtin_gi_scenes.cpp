// Built-in scenes that exercise global illumination (builtin:NAME?key=value&...):
//   leak    two rooms sharing one thin wall, light in one: the scene every method's leak number is
//           measured on (thickness, doorway);
//   room    a closed room with saturated walls and the camera inside: multi-bounce energy;
//   mirror  the Cornell box with a mirror sphere and a rough metal sphere: specular GI;
//   atrium  a Sponza-class courtyard (two storeys of arcades, arches, a gallery, cloth banners, a
//           tiled floor) under sun and sky, from ~15k to over 1M triangles (detail);
//   building a 32 m wing with 20 cm walls under sun and sky: a corridor with windows, a hall behind
//           doorways the sun never reaches, and a room with no opening (the leak at building scale).
// Every surface that bounds a room is a box (two-sided by construction), so voxelizers, distance
// fields and the path tracer all see closed geometry.
#include <cmath>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/mesh_builders.h"
#include "scene/scene_internal.h"

namespace gis::detail {

namespace {

constexpr float kPi = 3.14159265358979f;

double option(const SceneOptions& o, const std::string& key, double fallback, double lo, double hi,
              const std::string& scene) {
    auto it = o.find(key);
    if (it == o.end()) return fallback;
    if (!(it->second >= lo && it->second <= hi))
        throw Error("builtin:" + scene + ": " + key + " " + oneLine(std::to_string(it->second), 40) +
                    " is out of range [" + oneLine(std::to_string(lo), 20) + ", " + oneLine(std::to_string(hi), 20) + "]");
    return it->second;
}

void checkKeys(const SceneOptions& o, const std::string& scene, const std::vector<std::string>& keys) {
    for (const auto& [key, value] : o) {
        bool known = false;
        for (const std::string& k : keys) known = known || k == key;
        if (!known) {
            std::string list;
            for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
            throw Error("builtin:" + scene + ": unknown option '" + oneLine(key, 40) + "' (" +
                        (list.empty() ? std::string("it takes none") : "expected " + list) + ")");
        }
    }
}

Camera lookAt(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfovDegrees) {
    Camera c;
    c.name = name;
    c.cameraToWorld = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
    c.yfov = yfovDegrees * kPi / 180.0f;
    c.znear = 0.01f;
    c.zfar = 1000.0f;
    return c;
}

Light pointLight(const std::string& name, glm::vec3 position, float intensity) {
    Light l;
    l.name = name;
    l.type = LightType::Point;
    l.position = position;
    l.intensity = intensity;
    return l;
}

// The outdoor scenes' sun: irradiance 3 of a warm white, from `elevation` degrees above the
// horizon and `azimuth` degrees from +Z towards +X.
Light sunLight(float elevationDegrees, float azimuthDegrees) {
    Light sun;
    sun.name = "Sun";
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    sun.color = glm::vec3(1.0f, 0.95f, 0.85f);
    const float elevation = elevationDegrees * kPi / 180.0f, azimuth = azimuthDegrees * kPi / 180.0f;
    sun.direction = -glm::vec3(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                               std::cos(elevation) * std::cos(azimuth));
    return sun;
}

}  // namespace

SceneOptions parseSceneOptions(const std::string& spec, const std::string& query) {
    SceneOptions o;
    std::stringstream in(query);
    for (std::string item; std::getline(in, item, '&');) {
        const size_t eq = item.find('=');
        char* end = nullptr;
        const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
        // A word value (lamp=panel) is kept as the key "lamp=panel" (1): scenes list the words they take.
        if (eq != std::string::npos && eq > 0 && !value.empty() &&
            value.find_first_not_of("abcdefghijklmnopqrstuvwxyz") == std::string::npos) {
            o[item] = 1.0;
            continue;
        }
        const double v = std::strtod(value.c_str(), &end);
        if (eq == std::string::npos || value.empty() || *end != '\0' || !std::isfinite(v))
            throw Error("builtin:" + oneLine(spec, 80) + ": '" + oneLine(item, 40) + "' is not KEY=NUMBER");
        o[item.substr(0, eq)] = v;
    }
    return o;
}

// Two 2 m rooms side by side (x < 0 lit, x > 0 dark), open at the top so an overhead camera sees
// both floors, sharing a wall of `thickness` metres (default 0.02, down to 0.005), optionally with
// a doorway. The leak number: the dark room's mean radiance over the lit room's.
Scene makeLeakScene(const SceneOptions& o) {
    checkKeys(o, "leak", {"thickness", "doorway"});
    const float t = float(option(o, "thickness", 0.02, 0.005, 1.0, "leak"));
    const bool doorway = option(o, "doorway", 0.0, 0.0, 1.0, "leak") != 0.0;
    Scene s;
    s.name = "leak";
    const int white = addMaterial(s, lambert("White", glm::vec3(0.73f)));
    const int cube = addPrimitive(s, unitCube(white));
    const float w = 0.1f, h = 2.0f, half = 0.5f * t;
    addBox(s, cube, {-2 - w, -w, -1 - w}, {2 + w, 0, 1 + w});        // floor slab under both rooms
    addBox(s, cube, {-2 - w, 0, -1 - w}, {-2, h, 1 + w});            // outer walls
    addBox(s, cube, {2, 0, -1 - w}, {2 + w, h, 1 + w});
    addBox(s, cube, {-2, 0, -1 - w}, {2, h, -1});
    addBox(s, cube, {-2, 0, 1}, {2, h, 1 + w});
    if (doorway) {  // 0.6 m wide, 1.2 m high, in the middle of the shared wall
        addBox(s, cube, {-half, 0, -1}, {half, h, -0.3f});
        addBox(s, cube, {-half, 0, 0.3f}, {half, h, 1});
        addBox(s, cube, {-half, 1.2f, -0.3f}, {half, h, 0.3f});
    } else {
        addBox(s, cube, {-half, 0, -1}, {half, h, 1});
    }
    s.lights.push_back(pointLight("Lamp", {-1.0f, 1.5f, 0.0f}, 4.0f));
    s.cameras.push_back(lookAt("Overhead", {0.0f, 5.5f, 2.6f}, {0.0f, 0.0f, 0.0f}, 50.0f));
    finalizeScene(s);
    return s;
}

// A closed 4 x 2.6 x 5 m room: red, green, blue and yellow walls, white floor and ceiling, a
// white block, a lamp under the ceiling and the camera inside. Light bounces many times before it
// leaves (it never does): the multi-bounce energy check. lamp=panel: the lamp is a 0.4 m emissive
// panel facing down instead, of the point light's power (4 pi I = pi L a^2, so L = 4 I / a^2).
Scene makeRoomScene(const SceneOptions& o) {
    checkKeys(o, "room", {"lamp=point", "lamp=panel"});
    const bool panel = o.count("lamp=panel") > 0;
    Scene s;
    s.name = "room";
    const int white = addMaterial(s, lambert("White", glm::vec3(0.8f)));
    const int red = addMaterial(s, lambert("Red", {0.8f, 0.1f, 0.08f}));
    const int green = addMaterial(s, lambert("Green", {0.1f, 0.7f, 0.12f}));
    const int blue = addMaterial(s, lambert("Blue", {0.1f, 0.15f, 0.8f}));
    const int yellow = addMaterial(s, lambert("Yellow", {0.8f, 0.7f, 0.1f}));
    const float w = 0.1f, X = 2.0f, H = 2.6f, Z = 2.5f;
    auto box = [&s](int material, glm::vec3 lo, glm::vec3 hi) { addBox(s, addPrimitive(s, unitCube(material)), lo, hi); };
    box(white, {-X - w, -w, -Z - w}, {X + w, 0, Z + w});  // floor
    box(white, {-X - w, H, -Z - w}, {X + w, H + w, Z + w});  // ceiling
    box(red, {-X - w, 0, -Z}, {-X, H, Z});
    box(green, {X, 0, -Z}, {X + w, H, Z});
    box(blue, {-X, 0, -Z - w}, {X, H, -Z});
    box(yellow, {-X, 0, Z}, {X, H, Z + w});
    box(white, {-0.9f, 0, -1.4f}, {-0.1f, 0.9f, -0.6f});
    const glm::vec3 lampPosition{0.3f, 2.3f, -0.5f};
    const float lampIntensity = 3.0f;
    if (panel) {
        const float a = 0.4f, e = 0.5f * a, y = H - 0.001f;
        Material m = lambert("Panel", glm::vec3(0.0f));
        m.emissive = glm::vec3(4.0f * lampIntensity / (a * a));
        Primitive quad;
        quad.material = addMaterial(s, m);
        const float x = lampPosition.x, z = lampPosition.z;
        addQuad(quad, {{x - e, y, z - e}, {x + e, y, z - e}, {x + e, y, z + e}, {x - e, y, z + e}}, {0, -1, 0});
        addPrimitive(s, quad);
        s.draws.push_back(DrawItem{int(s.primitives.size()) - 1, glm::mat4(1.0f)});
    } else {
        s.lights.push_back(pointLight("Lamp", lampPosition, lampIntensity));
    }
    s.cameras.push_back(lookAt("Inside", {0.6f, 1.4f, 2.2f}, {-0.3f, 0.9f, -2.5f}, 65.0f));
    finalizeScene(s);
    return s;
}

// The Cornell box (point light) with its blocks replaced by a mirror sphere (metal, roughness 0)
// and a rough metal sphere (roughness 0.35): specular indirect light and, in the path tracer,
// caustics on the floor.
Scene makeMirrorScene(const SceneOptions& o) {
    checkKeys(o, "mirror", {});
    Scene s = makeBuiltinScene("cornell");
    s.name = "mirror";
    s.draws.resize(3);  // the walls; the two blocks go
    Material mirror;
    mirror.name = "Mirror";
    mirror.baseColorFactor = glm::vec4(0.95f, 0.95f, 0.95f, 1.0f);
    mirror.metallicFactor = 1.0f;
    mirror.roughnessFactor = 0.0f;
    Material rough = mirror;
    rough.name = "RoughMetal";
    rough.baseColorFactor = glm::vec4(0.9f, 0.7f, 0.45f, 1.0f);
    rough.roughnessFactor = 0.35f;
    const int sphereMirror = addPrimitive(s, uvSphere(0.35f, 48, 24, addMaterial(s, mirror)));
    const int sphereRough = addPrimitive(s, uvSphere(0.3f, 48, 24, addMaterial(s, rough)));
    s.draws.push_back(DrawItem{sphereMirror, glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.35f, -0.3f))});
    s.draws.push_back(DrawItem{sphereRough, glm::translate(glm::mat4(1.0f), glm::vec3(0.45f, 0.3f, 0.35f))});
    finalizeScene(s);
    return s;
}

// A courtyard 20 x 12 m surrounded by two storeys of arcades (columns every 2 m, semicircular
// arches), a gallery floor and roof slabs behind them, outer walls, coloured banners hanging in the
// upper arcade, a tiled floor; sun and sky. `detail` d in [1, 12] scales every tessellation so
// the triangle count grows as ~12k d^2 (d = 1: ~13k, d = 10: over 1.2M).
Scene makeAtriumScene(const SceneOptions& o) {
    checkKeys(o, "atrium", {"detail"});
    const int d = int(option(o, "detail", 1.0, 1.0, 12.0, "atrium"));
    Scene s;
    s.name = "atrium";
    s.background = glm::vec3(0.35f, 0.45f, 0.6f);  // sky radiance
    const int stone = addMaterial(s, lambert("Stone", {0.72f, 0.68f, 0.6f}));
    const int plaster = addMaterial(s, lambert("Plaster", {0.8f, 0.77f, 0.7f}));
    Material floorMaterial = lambert("Floor", {0.5f, 0.44f, 0.38f});
    floorMaterial.roughnessFactor = 0.6f;
    floorMaterial.specularFactor = 1.0f;
    const int floorTiles = addMaterial(s, floorMaterial);
    const glm::vec3 clothColours[3] = {{0.7f, 0.08f, 0.06f}, {0.08f, 0.15f, 0.6f}, {0.1f, 0.5f, 0.15f}};
    int cloth[3];
    for (int i = 0; i < 3; ++i) {
        Material m = lambert("Cloth" + std::to_string(i), clothColours[i]);
        m.doubleSided = true;
        cloth[i] = addMaterial(s, m);
    }
    const float X = 10.0f, Z = 6.0f, depth = 3.0f, storey = 4.0f, wall = 0.3f;
    const int cube = addPrimitive(s, unitCube(plaster));
    s.draws.push_back(DrawItem{addPrimitive(s, grid({2 * (X + depth), 2 * (Z + depth)}, 44 * d, 30 * d, 0.01f, floorTiles)),
                               glm::mat4(1.0f)});
    // Outer walls behind the arcades, gallery floor and roof over the arcades.
    const float OX = X + depth, OZ = Z + depth, top = 2 * storey;
    addBox(s, cube, {-OX - wall, 0, -OZ - wall}, {-OX, top, OZ + wall});
    addBox(s, cube, {OX, 0, -OZ - wall}, {OX + wall, top, OZ + wall});
    addBox(s, cube, {-OX, 0, -OZ - wall}, {OX, top, -OZ});
    addBox(s, cube, {-OX, 0, OZ}, {OX, top, OZ + wall});
    for (float y : {storey, top}) {
        addBox(s, cube, {-OX, y, -OZ}, {OX, y + 0.3f, -Z});
        addBox(s, cube, {-OX, y, Z}, {OX, y + 0.3f, OZ});
        addBox(s, cube, {-OX, y, -Z}, {-X, y + 0.3f, Z});
        addBox(s, cube, {X, y, -Z}, {OX, y + 0.3f, Z});
    }
    // Columns and arches on the courtyard's edge, both storeys.
    const float radius = 0.25f, shaft = storey - 1.0f - 0.3f;  // the arch rises 1 m above the shaft
    const int column = addPrimitive(s, cylinder(radius, shaft, 12 * d, 2 * d, stone));
    const int arch = addPrimitive(s, archBand(2.0f - 2 * radius, 0.5f, 0.25f, 6 * d, stone));
    const int clothMesh[3] = {addPrimitive(s, banner(1.2f, 2.2f, 10 * d, 20 * d, 0.15f, cloth[0])),
                              addPrimitive(s, banner(1.2f, 2.2f, 10 * d, 20 * d, 0.15f, cloth[1])),
                              addPrimitive(s, banner(1.2f, 2.2f, 10 * d, 20 * d, 0.15f, cloth[2]))};
    auto edge = [&](glm::vec3 from, glm::vec3 step, int count, float yaw, float y) {
        for (int i = 0; i <= count; ++i)
            s.draws.push_back(DrawItem{column, glm::translate(glm::mat4(1.0f), from + step * float(i) + glm::vec3(0, y, 0))});
        for (int i = 0; i < count; ++i) {
            glm::mat4 m = glm::translate(glm::mat4(1.0f), from + step * (float(i) + 0.5f) + glm::vec3(0, y + shaft, 0));
            s.draws.push_back(DrawItem{arch, glm::rotate(m, yaw, glm::vec3(0, 1, 0))});
        }
    };
    for (float y : {0.0f, storey}) {
        edge({-X, 0, -Z}, {2, 0, 0}, 10, 0.0f, y);
        edge({-X, 0, Z}, {2, 0, 0}, 10, 0.0f, y);
        edge({-X, 0, -Z}, {0, 0, 2}, 6, 0.5f * kPi, y);
        edge({X, 0, -Z}, {0, 0, 2}, 6, 0.5f * kPi, y);
    }
    // Banners hang from the upper arches along the long sides, three colours in turn.
    for (int i = 0; i < 8; ++i) {
        const float x = -7.0f + 2.0f * float(i);
        const float z = i % 2 ? Z : -Z;
        glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(x, storey + shaft + 0.9f, z));
        if (z > 0) m = glm::rotate(m, kPi, glm::vec3(0, 1, 0));
        s.draws.push_back(DrawItem{clothMesh[i % 3], m});
    }
    s.lights.push_back(sunLight(55.0f, 35.0f));
    s.cameras.push_back(lookAt("Courtyard", {-6.0f, 1.7f, 4.5f}, {6.0f, 3.5f, -5.0f}, 60.0f));
    finalizeScene(s);
    return s;
}

// A one-storey wing 32 x 11 m (walls and roof 20 cm) on a 40 x 40 m ground, under sun and sky:
//   corridor  z in [2.5, 5.5], the whole length, eight windows in its south wall (+z) that the
//             sun shines through onto the corridor floor;
//   hall      z in [-5.5, 2.3], x in [-16, 4], behind three doorways in the corridor's inner wall
//             and deep enough that the sun never reaches it: lit only by what bounces in;
//   closed    z in [-5.5, 2.3], x in [4.2, 16], walls on every side and no opening: no light
//             reaches it, so whatever a method shows there leaked through a wall.
// Cameras: 0 the corridor, 1 the hall, 2 the closed room; the leak cameras are 2 over 0.
Scene makeBuildingScene(const SceneOptions& o) {
    checkKeys(o, "building", {});
    Scene s;
    s.name = "building";
    s.background = glm::vec3(0.35f, 0.45f, 0.6f);  // sky radiance, as the atrium's
    const int plaster = addPrimitive(s, unitCube(addMaterial(s, lambert("Plaster", {0.75f, 0.73f, 0.7f}))));
    const int floorSlab = addPrimitive(s, unitCube(addMaterial(s, lambert("Floor", {0.45f, 0.4f, 0.35f}))));
    const int ground = addPrimitive(s, unitCube(addMaterial(s, lambert("Ground", {0.25f, 0.3f, 0.2f}))));
    const float w = 0.2f, H = 3.0f, X = 16.0f;         // wall thickness, storey, half length
    const float zs = 5.5f, zi = 2.3f, zn = -5.5f;       // south wall, inner wall, north wall (inner faces)
    const float xc = 4.0f;                              // the hall's east wall (the closed room beyond)
    addBox(s, ground, {-20, -w, -20}, {20, 0, 20});
    addBox(s, floorSlab, {-X, 0, zn}, {X, 0.02f, zs});  // the wing's floor, on the ground slab
    addBox(s, plaster, {-X - w, H, zn - w}, {X + w, H + w, zs + w});  // roof
    addBox(s, plaster, {-X - w, 0, zn - w}, {-X, H, zs + w});         // west and east walls
    addBox(s, plaster, {X, 0, zn - w}, {X + w, H, zs + w});
    addBox(s, plaster, {-X, 0, zn - w}, {X, H, zn});                   // north wall
    addBox(s, plaster, {xc, 0, zn}, {xc + w, H, zi});                  // hall | closed room
    // South wall: a strip under the sills, one over the heads, piers between eight 2 m windows.
    const float sill = 0.9f, head = 2.4f;
    addBox(s, plaster, {-X, 0, zs}, {X, sill, zs + w});
    addBox(s, plaster, {-X, head, zs}, {X, H, zs + w});
    for (int i = 0; i <= 8; ++i) {
        const float lo = i == 0 ? -X : -X + 4.0f * float(i) - 1.0f, hi = i == 8 ? X : -X + 4.0f * float(i) + 1.0f;
        addBox(s, plaster, {lo, sill, zs}, {hi, head, zs + w});
    }
    // Inner wall: doorways 1.2 m wide and 2.2 m high at x = -12, -6 and 0; solid along the closed room.
    const float door = 2.2f, doorways[3] = {-12.0f, -6.0f, 0.0f};
    float from = -X;
    for (float x : doorways) {
        addBox(s, plaster, {from, 0, zi}, {x - 0.6f, H, zi + w});
        addBox(s, plaster, {x - 0.6f, door, zi}, {x + 0.6f, H, zi + w});
        from = x + 0.6f;
    }
    addBox(s, plaster, {from, 0, zi}, {X, H, zi + w});
    // From the south-east, 45 degrees up: through a window head it lands within 2.2 m of the south
    // wall, short of the inner wall, so no sun enters the hall.
    s.lights.push_back(sunLight(45.0f, 25.0f));
    s.cameras.push_back(lookAt("Corridor", {-14.5f, 1.6f, 3.6f}, {6.0f, 1.1f, 4.4f}, 60.0f));
    s.cameras.push_back(lookAt("Hall", {-15.0f, 1.7f, -4.8f}, {2.0f, 0.9f, 1.0f}, 60.0f));
    s.cameras.push_back(lookAt("Closed", {5.0f, 1.7f, -4.8f}, {15.0f, 0.9f, 1.5f}, 60.0f));
    s.leakCameras = {2, 0};
    finalizeScene(s);
    return s;
}

}  // namespace gis::detail
