// Built-in scenes, built procedurally. They reproduce shared/assets/reference/scenes/ exactly
// (same meshes, vertex order, winding, materials, node transforms, camera and light), so a
// renderer can be compared with the Cycles references without loading a file.
#include <cmath>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_internal.h"

namespace gis {
namespace {

// One quad (two triangles 0-1-2, 0-2-3 as in the reference generator) with a constant normal.
void addQuad(Primitive& p, const glm::vec3 (&c)[4], const glm::vec3& n) {
    const uint32_t base = static_cast<uint32_t>(p.vertices.size());
    for (const glm::vec3& pos : c) {
        Vertex v;
        v.position = pos;
        v.normal = n;
        v.tangent = glm::vec4(0.0f);  // missing: finalizeScene derives one from the normal
        p.vertices.push_back(v);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) p.indices.push_back(base + i);
}

Material lambert(const std::string& name, const glm::vec3& albedo) {
    Material m;
    m.name = name;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 1.0f;
    m.specularFactor = 0.0f;  // KHR_materials_specular.specularFactor = 0: ideal Lambert
    m.doubleSided = false;
    return m;
}

// Unit cube centred at the origin, faces +Z, -Z, +X, -X, +Y, -Y, outward, CCW.
Primitive unitCube(int material) {
    Primitive p;
    p.material = material;
    const float h = 0.5f;
    addQuad(p, {{-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}}, {0, 0, 1});
    addQuad(p, {{-h, -h, -h}, {-h, h, -h}, {h, h, -h}, {h, -h, -h}}, {0, 0, -1});
    addQuad(p, {{h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h}}, {1, 0, 0});
    addQuad(p, {{-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h}}, {-1, 0, 0});
    addQuad(p, {{-h, h, -h}, {-h, h, h}, {h, h, h}, {h, h, -h}}, {0, 1, 0});
    addQuad(p, {{-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}}, {0, -1, 0});
    return p;
}

Scene makeCornell(bool areaLight) {
    Scene s;
    s.name = areaLight ? "cornell-area" : "cornell";
    s.background = glm::vec3(0.0f);

    enum { kWhite, kRed, kGreen, kLight };
    s.materials.push_back(lambert("White", {0.73f, 0.73f, 0.73f}));
    s.materials.push_back(lambert("Red", {0.63f, 0.065f, 0.05f}));
    s.materials.push_back(lambert("Green", {0.14f, 0.45f, 0.091f}));
    if (areaLight) {
        Material light = lambert("Light", {0.0f, 0.0f, 0.0f});
        light.emissive = glm::vec3(1.0f) * 15.0f;  // emissiveFactor (1,1,1) * emissiveStrength 15
        s.materials.push_back(light);
    }

    // Mesh "Walls": floor + ceiling + back wall (white), left wall (red), right wall (green).
    // Single-sided quads facing the inside of the box; the box is open at z = +1.
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

    if (areaLight) {
        // Emitter quad just below the ceiling, facing down (-Y), one-sided.
        Primitive quad;
        quad.material = kLight;
        const float y = 1.999f, e = 0.25f;
        addQuad(quad, {{-e, y, -e}, {e, y, -e}, {e, y, e}, {-e, y, e}}, {0, -1, 0});
        s.primitives.push_back(quad);
        s.draws.push_back(DrawItem{static_cast<int>(s.primitives.size()) - 1, glm::mat4(1.0f)});
    }

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

}  // namespace

std::vector<std::string> builtinSceneNames() { return {"cornell", "cornell-area"}; }

Scene makeBuiltinScene(const std::string& name) {
    if (name == "cornell") return makeCornell(false);
    if (name == "cornell-area") return makeCornell(true);
    std::string list;
    for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
    throw Error("unknown built-in scene '" + detail::oneLine(name, 80) + "' (available: " + list +
                ")");
}

}  // namespace gis
