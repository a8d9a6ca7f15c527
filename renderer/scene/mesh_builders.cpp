// Procedural meshes for the built-in scenes: quads, boxes, spheres, cylinders, arches.
#include "scene/mesh_builders.h"

#include <cmath>

#include "scene/scene_internal.h"

namespace gis::detail {

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

// UV sphere of radius r centred at the origin: `segments` around +Y, `rings` from pole to pole,
// outward normals, CCW seen from outside, tangents along +phi.
Primitive uvSphere(float r, int segments, int rings, int material) {
    Primitive p;
    p.material = material;
    const float pi = 3.14159265358979f;
    for (int i = 0; i <= rings; ++i) {
        const float theta = pi * float(i) / float(rings);  // from +Y down
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * pi * float(j) / float(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            Vertex v;
            v.position = r * n;
            v.normal = n;
            v.tangent = glm::vec4(-std::sin(phi), 0.0f, -std::cos(phi), 1.0f);
            v.uv = glm::vec2(float(j) / float(segments), float(i) / float(rings));
            p.vertices.push_back(v);
        }
    }
    const uint32_t row = uint32_t(segments) + 1;
    for (uint32_t i = 0; i < uint32_t(rings); ++i)
        for (uint32_t j = 0; j < uint32_t(segments); ++j) {
            const uint32_t a = i * row + j, b = a + row;  // b is one ring further down
            if (i != 0) for (uint32_t k : {a, b, a + 1}) p.indices.push_back(k);
            if (i + 1 != uint32_t(rings)) for (uint32_t k : {a + 1, b, b + 1}) p.indices.push_back(k);
        }
    return p;
}

namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

int addMaterial(Scene& s, const Material& m) {
    s.materials.push_back(m);
    return int(s.materials.size()) - 1;
}

int addPrimitive(Scene& s, Primitive p) {
    s.primitives.push_back(std::move(p));
    return int(s.primitives.size()) - 1;
}

void addBox(Scene& s, int cubePrimitive, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-6f));
    glm::mat4 m = glm::mat4(1.0f);
    m[0][0] = size.x, m[1][1] = size.y, m[2][2] = size.z;
    m[3] = glm::vec4(0.5f * (lo + hi), 1.0f);
    s.draws.push_back(DrawItem{cubePrimitive, m});
}

Primitive cylinder(float radius, float height, int segments, int rings, int material) {
    Primitive p;
    p.material = material;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * float(j) / float(segments);
            const glm::vec3 n(std::cos(phi), 0.0f, -std::sin(phi));
            Vertex v;
            v.position = glm::vec3(radius * n.x, height * float(i) / float(rings), radius * n.z);
            v.normal = n;
            v.tangent = glm::vec4(-std::sin(phi), 0.0f, -std::cos(phi), 1.0f);
            v.uv = glm::vec2(float(j) / float(segments), float(i) / float(rings));
            p.vertices.push_back(v);
        }
    const uint32_t row = uint32_t(segments) + 1;
    for (uint32_t i = 0; i < uint32_t(rings); ++i)
        for (uint32_t j = 0; j < uint32_t(segments); ++j) {
            const uint32_t a = i * row + j, b = a + row;  // b is one ring up
            for (uint32_t k : {a, a + 1, b + 1, a, b + 1, b}) p.indices.push_back(k);
        }
    return p;
}

Primitive archBand(float span, float depth, float thickness, int segments, int material) {
    // A semicircular band (the underside of an arch and its front and back faces), spanning x in
    // [-span/2, span/2] at y = 0, rising to span/2, depth along z, centred on z = 0.
    Primitive p;
    p.material = material;
    const float r = 0.5f * span, R = r + thickness, d = 0.5f * depth;
    auto quad = [&p](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 e, glm::vec3 n) {
        const glm::vec3 corners[4] = {a, b, c, e};
        addQuad(p, corners, n);
    };
    for (int i = 0; i < segments; ++i) {
        const float t0 = kPi * float(i) / float(segments), t1 = kPi * float(i + 1) / float(segments);
        const glm::vec2 u0(std::cos(t0), std::sin(t0)), u1(std::cos(t1), std::sin(t1));
        const glm::vec3 in0(r * u0.x, r * u0.y, 0), in1(r * u1.x, r * u1.y, 0);
        const glm::vec3 out0(R * u0.x, R * u0.y, 0), out1(R * u1.x, R * u1.y, 0);
        const glm::vec3 nIn = -glm::normalize(glm::vec3(u0 + u1, 0.0f));
        const glm::vec3 dz(0, 0, d);
        quad(in0 + dz, in1 + dz, in1 - dz, in0 - dz, nIn);               // soffit, facing the opening
        quad(in0 + dz, out0 + dz, out1 + dz, in1 + dz, {0, 0, 1});      // front
        quad(in1 - dz, out1 - dz, out0 - dz, in0 - dz, {0, 0, -1});     // back
    }
    return p;
}

Primitive grid(const glm::vec2& size, int nx, int nz, float bump, int material) {
    // A floor of nx x nz tiles in the XZ plane facing +Y, each tile slightly raised at its centre
    // (a pyramid of height `bump`), so detail costs triangles the way real floors do.
    Primitive p;
    p.material = material;
    const glm::vec2 cell(size.x / float(nx), size.y / float(nz));
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k) {
            const glm::vec3 o(-0.5f * size.x + cell.x * float(i), 0.0f, -0.5f * size.y + cell.y * float(k));
            const glm::vec3 c[4] = {o, o + glm::vec3(0, 0, cell.y), o + glm::vec3(cell.x, 0, cell.y),
                                    o + glm::vec3(cell.x, 0, 0)};
            const glm::vec3 top = o + glm::vec3(0.5f * cell.x, bump, 0.5f * cell.y);
            for (int e = 0; e < 4; ++e) {
                const glm::vec3 a = c[e], b = c[(e + 1) % 4];
                const glm::vec3 n = glm::normalize(glm::cross(b - a, top - a));
                const uint32_t base = uint32_t(p.vertices.size());
                for (const glm::vec3& q : {a, b, top}) {
                    Vertex v;
                    v.position = q;
                    v.normal = n;
                    v.tangent = glm::vec4(0.0f);
                    p.vertices.push_back(v);
                }
                for (uint32_t j : {0u, 1u, 2u}) p.indices.push_back(base + j);
            }
        }
    return p;
}

Primitive banner(float width, float height, int nx, int ny, float sag, int material) {
    // A cloth hanging from y = 0 down to -height in the XY plane, bulging along +Z by `sag` at its
    // middle; double-sided through its material.
    Primitive p;
    p.material = material;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const float u = float(i) / float(nx), v = float(j) / float(ny);
            const float z = sag * std::sin(kPi * u) * std::sin(kPi * v * 0.5f);
            Vertex vert;
            vert.position = glm::vec3((u - 0.5f) * width, -v * height, z);
            vert.normal = glm::vec3(0, 0, 1);
            vert.tangent = glm::vec4(0.0f);
            vert.uv = glm::vec2(u, v);
            p.vertices.push_back(vert);
        }
    const uint32_t row = uint32_t(nx) + 1;
    for (uint32_t j = 0; j < uint32_t(ny); ++j)
        for (uint32_t i = 0; i < uint32_t(nx); ++i) {
            const uint32_t a = j * row + i, b = a + row;
            for (uint32_t k : {a, b, b + 1, a, b + 1, a + 1}) p.indices.push_back(k);
        }
    return p;
}

}  // namespace gis::detail
