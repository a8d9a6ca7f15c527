// Unit tests: finalizeScene (normals, tangents, degenerate input), defaultCamera, loadScene, and
// loader behaviour on small hand-made glTF files (strips/fans, errors, lights, sparse, limits).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <stb_image_write.h>

#include "test_util.h"

using namespace gistest;
using gis::Scene;
using gis::Vertex;

namespace {

gis::Primitive quad(bool withNormals) {
    gis::Primitive p;
    const glm::vec3 pos[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        Vertex v;
        v.position = pos[i];
        v.uv = uv[i];
        v.normal = withNormals ? glm::vec3(0, 0, 1) : glm::vec3(0);
        v.tangent = glm::vec4(0);  // missing
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

Scene sceneWith(gis::Primitive p, bool normalMap) {
    Scene s;
    gis::Material m;
    if (normalMap) {
        gis::Image img;
        img.width = img.height = 1;
        img.rgba8 = {128, 128, 255, 255};
        s.images.push_back(img);
        m.normalTexture = 0;
    }
    s.materials.push_back(m);
    p.material = 0;
    s.primitives.push_back(p);
    s.draws.push_back(gis::DrawItem{0, glm::mat4(1.0f)});
    return s;
}

void expectUnitFinite(const Scene& s) {
    for (const auto& p : s.primitives)
        for (const auto& v : p.vertices) {
            ASSERT_TRUE(finite(v.normal));
            ASSERT_TRUE(finite(glm::vec3(v.tangent)));
            EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
            EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-4f);
            EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0f, 1e-4f);
            EXPECT_TRUE(v.tangent.w == 1.0f || v.tangent.w == -1.0f);
        }
}

}  // namespace

TEST(Finalize, GeneratesNormalsForHandMadeQuad) {
    Scene s = sceneWith(quad(false), false);
    gis::finalizeScene(s);
    for (const auto& v : s.primitives[0].vertices) {
        EXPECT_NEAR(v.normal.x, 0.0f, 1e-6f);
        EXPECT_NEAR(v.normal.y, 0.0f, 1e-6f);
        EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);  // CCW seen from +Z
    }
    expectUnitFinite(s);
    EXPECT_EQ(s.bounds.min, glm::vec3(0, 0, 0));
    EXPECT_EQ(s.bounds.max, glm::vec3(1, 1, 0));
    EXPECT_EQ(s.triangleCount(), 2u);
}

TEST(Finalize, AreaWeightedNormalOnSharedVertex) {
    // Vertex 0 is shared by a big triangle in the XY plane and a small one in the XZ plane.
    gis::Primitive p;
    for (glm::vec3 pos : {glm::vec3(0, 0, 0), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0),
                          glm::vec3(0, 0, -1), glm::vec3(1, 0, 0)}) {
        Vertex v;
        v.position = pos;
        v.normal = glm::vec3(0);
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2, 0, 3, 4};  // normals +Z (area 8) and +Y... (area 0.5)
    Scene s = sceneWith(p, false);
    gis::finalizeScene(s);
    const glm::vec3 n = s.primitives[0].vertices[0].normal;
    const glm::vec3 expected = glm::normalize(glm::vec3(0, 0, 16) + glm::cross(glm::vec3(0, 0, -1), glm::vec3(1, 0, 0)));
    EXPECT_NEAR(glm::dot(n, expected), 1.0f, 1e-5f);
    EXPECT_GT(n.z, 0.9f);
}

TEST(Finalize, KeepsGivenNormalsNormalised) {
    gis::Primitive p = quad(true);
    for (auto& v : p.vertices) v.normal = glm::vec3(0, 0, 5);
    Scene s = sceneWith(p, false);
    gis::finalizeScene(s);
    for (const auto& v : s.primitives[0].vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
}

TEST(Finalize, TangentsFromUvs) {
    Scene s = sceneWith(quad(true), true);
    gis::finalizeScene(s);
    for (const auto& v : s.primitives[0].vertices) {
        EXPECT_NEAR(v.tangent.x, 1.0f, 1e-5f);  // +U along +X
        EXPECT_EQ(v.tangent.w, 1.0f);           // +V along +Y = cross(N, T)
    }
    // Mirrored V: the bitangent flips, so w = -1.
    gis::Primitive mirrored = quad(true);
    for (auto& v : mirrored.vertices) v.uv.y = 1.0f - v.uv.y;
    Scene m = sceneWith(mirrored, true);
    gis::finalizeScene(m);
    for (const auto& v : m.primitives[0].vertices) {
        EXPECT_NEAR(v.tangent.x, 1.0f, 1e-5f);
        EXPECT_EQ(v.tangent.w, -1.0f);
    }
    expectUnitFinite(m);
}

TEST(Finalize, DegenerateTrianglesGiveNoNaN) {
    gis::Primitive p;
    // Triangle 0: three identical points; triangle 1: collinear; triangle 2: fine geometry but
    // all UVs equal (degenerate UV mapping); triangle 3: huge coordinates (cross product would
    // overflow in float).
    const glm::vec3 pos[] = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1},  {0, 0, 0},     {1, 1, 1},
                             {2, 2, 2}, {0, 0, 0}, {1, 0, 0},  {0, 1, 0},     {-3e38f, 0, 0},
                             {3e38f, 0, 0}, {0, 3e38f, 0}};
    for (const glm::vec3& q : pos) {
        Vertex v;
        v.position = q;
        v.normal = glm::vec3(0);
        v.tangent = glm::vec4(0);
        v.uv = glm::vec2(0.5f);
        p.vertices.push_back(v);
    }
    for (uint32_t i = 0; i < 12; ++i) p.indices.push_back(i);
    Scene s = sceneWith(p, true);  // normal map: tangent generation runs
    ASSERT_NO_THROW(gis::finalizeScene(s));
    expectUnitFinite(s);
    // The good triangle still gets its real normal.
    EXPECT_NEAR(s.primitives[0].vertices[6].normal.z, 1.0f, 1e-6f);
}

TEST(Finalize, NaNNormalsInInputAreReplaced) {
    gis::Primitive p = quad(true);
    p.vertices[1].normal = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    p.vertices[2].tangent = glm::vec4(std::numeric_limits<float>::infinity());
    Scene s = sceneWith(p, true);
    gis::finalizeScene(s);
    expectUnitFinite(s);
    EXPECT_NEAR(s.primitives[0].vertices[1].normal.z, 1.0f, 1e-6f);
}

TEST(Finalize, RejectsNaNPosition) {
    gis::Primitive p = quad(true);
    p.vertices[2].position.y = std::numeric_limits<float>::quiet_NaN();
    Scene s = sceneWith(p, false);
    const std::string msg = errorOf([&] { gis::finalizeScene(s); });
    EXPECT_NE(msg.find("non-finite position"), std::string::npos) << msg;
}

TEST(Finalize, RejectsOutOfRangeIndex) {
    gis::Primitive p = quad(true);
    p.indices[4] = 7;
    Scene s = sceneWith(p, false);
    const std::string msg = errorOf([&] { gis::finalizeScene(s); });
    EXPECT_NE(msg.find("out of range"), std::string::npos) << msg;
}

TEST(Finalize, InstancedPrimitiveCountsPerDraw) {
    Scene s = sceneWith(quad(true), false);
    glm::mat4 shifted(1.0f);
    shifted[3] = glm::vec4(10, 0, 0, 1);
    s.draws.push_back(gis::DrawItem{0, shifted});
    gis::finalizeScene(s);
    EXPECT_EQ(s.triangleCount(), 4u);
    EXPECT_FLOAT_EQ(s.bounds.max.x, 11.0f);
}

TEST(DefaultCamera, FramesBoundsFromPlusZRaised) {
    gis::Aabb b;
    b.extend({-1, -1, -1});
    b.extend({1, 1, 1});
    const gis::Camera c = gis::defaultCamera(b, 1.5f);
    const glm::vec3 pos(c.cameraToWorld[3]);
    const float dist = glm::length(pos), r = std::sqrt(3.0f);
    EXPECT_NEAR(pos.x, 0.0f, 1e-6f);
    EXPECT_GT(pos.z, 0.0f);
    EXPECT_NEAR(pos.y / dist, std::sin(glm::radians(20.0f)), 1e-5f);  // raised: a ground plane is not edge-on
    const glm::vec3 forward = -glm::vec3(c.cameraToWorld[2]);
    EXPECT_NEAR(glm::dot(glm::normalize(forward), -pos / dist), 1.0f, 1e-5f);  // looks at the centre
    EXPECT_GT(c.znear, 0.0f);
    EXPECT_LT(c.znear, dist - r);
    EXPECT_GT(c.zfar, dist + r);
    // The bounding sphere fits the vertical field of view.
    EXPECT_LE(r / dist, std::sin(0.5f * c.yfov) + 1e-5f);
    const gis::Camera e = gis::defaultCamera(gis::Aabb{}, 0.0f);  // empty scene, bad aspect
    EXPECT_TRUE(finite(glm::vec3(e.cameraToWorld[3])));
    EXPECT_GT(e.zfar, e.znear);
}

TEST(LoadScene, UnknownBuiltinListsNames) {
    const std::string msg = errorOf([] { gis::loadScene("builtin:nope"); });
    EXPECT_NE(msg.find("nope"), std::string::npos);
    EXPECT_NE(msg.find("cornell, cornell-area"), std::string::npos) << msg;
    EXPECT_EQ(gis::loadScene("builtin:cornell").name, "cornell");
}

TEST(LoadScene, MissingFileNamesIt) {
    const std::string msg = errorOf([] { gis::loadScene("/nonexistent/dir/cornell.gltf"); });
    EXPECT_EQ(msg.rfind("/nonexistent/dir/cornell.gltf: ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
}

// --- Loader on hand-made glTF ------------------------------------------------------------------

namespace {

// Zig-zag strip in the XY plane: 0(0,0) 1(0,1) 2(1,0) 3(1,1) 4(2,0).
GltfBuilder stripBuilder(int mode) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}, {"mode", mode}}));
    return g;
}

}  // namespace

TEST(Loader, TriangleStripToList) {
    Scene s = stripBuilder(5).load();
    ASSERT_EQ(s.primitives.size(), 1u);
    const auto& idx = s.primitives[0].indices;
    EXPECT_EQ(idx, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
    // Consistent winding: every face normal points the same way (+Z here).
    for (const auto& v : s.primitives[0].vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
}

TEST(Loader, TriangleFanToList) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}, {"mode", 6}}));
    Scene s = g.load();
    EXPECT_EQ(s.primitives[0].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    for (const auto& v : s.primitives[0].vertices) EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
}

TEST(Loader, IndexedStrip) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const int ind = g.addIndices({0, 1, 2, 3});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}, {"mode", 5}}));
    EXPECT_EQ(g.load().triangleCount(), 2u);
}

TEST(Loader, PointsAndLinesAreErrorsNamingModeAndMesh) {
    for (int mode : {0, 1, 2, 3, 7}) {
        const std::string msg = errorOf([&] { stripBuilder(mode).load(); });
        EXPECT_NE(msg.find("mesh 0 primitive 0"), std::string::npos) << msg;
        EXPECT_NE(msg.find("mode " + std::to_string(mode)), std::string::npos) << msg;
    }
}

TEST(Loader, NaNPositionRejected) {
    GltfBuilder g;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const int pos = g.addVec3({{0, 0, 0}, {1, nan, 0}, {0, 1, 0}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}}));
    const std::string msg = errorOf([&] { g.load(); });
    EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("<memory>: ", 0), 0u) << msg;
}

TEST(Loader, CycleDetected) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int mesh = g.addMesh({{"attributes", {{"POSITION", pos}}}});
    g.addNode({{"mesh", mesh}, {"children", {1}}});
    g.addNode({{"children", {2}}});
    g.addNode({{"children", {0}}});
    g.j["scenes"] = {{{"nodes", {0}}}};
    const std::string msg = errorOf([&] { g.load(); });
    EXPECT_NE(msg.find("cycle"), std::string::npos) << msg;
    // Self-loop too.
    g.j["nodes"] = {{{"mesh", mesh}, {"children", {0}}}};
    EXPECT_NE(errorOf([&] { g.load(); }).find("cycle"), std::string::npos);
}

TEST(Loader, NodeHierarchyFlattened) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int mesh = g.addMesh({{"attributes", {{"POSITION", pos}}}});
    g.addNode({{"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}});
    g.addNode({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 5, 0, 1}}});
    g.j["scenes"] = {{{"nodes", {0}}}};
    Scene s = g.load();
    ASSERT_EQ(s.draws.size(), 1u);
    EXPECT_FLOAT_EQ(s.bounds.min.x, 10.0f);
    EXPECT_FLOAT_EQ(s.bounds.min.y, 10.0f);  // (0,5,0) scaled by 2
    EXPECT_FLOAT_EQ(s.bounds.max.x, 12.0f);
}

TEST(Loader, OutOfRangeIndexRejected) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int ind = g.addIndices({0, 1, 3});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}, {"indices", ind}}));
    const std::string msg = errorOf([&] { g.load(); });
    EXPECT_NE(msg.find("index 3 at position 2 is out of range (3 vertices)"), std::string::npos) << msg;
}

TEST(Loader, AccessorPastBufferEndRejectedWithoutHugeAllocation) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}}));
    g.j["accessors"][0]["count"] = 4;
    EXPECT_NE(errorOf([&] { g.load(); }).find("reads past the end of bufferView 0 (needs 48 bytes, has 36"),
              std::string::npos)
        << errorOf([&] { g.load(); });
    g.j["accessors"][0]["count"] = 4000000000000ull;  // hostile count: must not allocate
    EXPECT_NE(errorOf([&] { g.load(); }), "");
    g.j["accessors"][0]["count"] = 3;
    g.j["bufferViews"][0]["byteLength"] = 1000;  // view past the end of the buffer
    EXPECT_NE(errorOf([&] { g.load(); }).find("reads past the end of buffer 0"), std::string::npos);
}

TEST(Loader, SparseAccessorApplied) {
    GltfBuilder g;
    const int base = g.addView(std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}.data(), 36);
    const uint16_t sidx[1] = {2};
    const glm::vec3 sval[1] = {{0, 5, 0}};
    const int iv = g.addView(sidx, 2);
    const int vv = g.addView(sval, 12);
    const int pos = g.addAccessor(base, 5126, 3, "VEC3",
                                  {{"sparse", {{"count", 1},
                                               {"indices", {{"bufferView", iv}, {"componentType", 5123}}},
                                               {"values", {{"bufferView", vv}}}}}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}}}}));
    Scene s = g.load();
    EXPECT_FLOAT_EQ(s.primitives[0].vertices[2].position.y, 5.0f);
    g.j["accessors"][pos]["sparse"]["count"] = 9;  // more than the accessor has
    EXPECT_NE(errorOf([&] { g.load(); }), "");
}

TEST(Loader, AttributesColorsAndNormalizedUvs) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const uint8_t rgb[9] = {255, 0, 0, 0, 255, 0, 0, 0, 255};
    const int col = g.addAccessor(g.addView(rgb, 9), 5121, 3, "VEC3", {{"normalized", true}});
    const uint16_t uv[6] = {0, 0, 65535, 0, 0, 65535};
    const int tc = g.addAccessor(g.addView(uv, 12), 5123, 3, "VEC2", {{"normalized", true}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}, {"COLOR_0", col}, {"TEXCOORD_0", tc}}}}));
    Scene s = g.load();
    const auto& v = s.primitives[0].vertices;
    EXPECT_EQ(v[0].color, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(v[2].color, glm::vec4(0, 0, 1, 1));
    EXPECT_EQ(v[1].uv, glm::vec2(1, 0));
    g.j["accessors"][tc].erase("normalized");  // integer UVs must be normalized
    EXPECT_NE(errorOf([&] { g.load(); }).find("TEXCOORD_0"), std::string::npos);
}

// The lightmap (renderer/lightmap/) needs the file's second UV set per primitive, aligned with
// its vertices; a file without one leaves uv1 empty so the atlas is generated instead.
TEST(Loader, SecondUvSetIsKeptPerPrimitive) {
    GltfBuilder g;
    const int pos = g.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int tc0 = g.addVec2({{0, 0}, {1, 0}, {0, 1}});
    const int tc1 = g.addVec2({{0.25f, 0.5f}, {0.75f, 0.5f}, {0.25f, 1.0f}});
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tc0}, {"TEXCOORD_1", tc1}}}}));
    g.addMeshNode(g.addMesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tc0}}}}));
    Scene s = g.load();
    ASSERT_EQ(s.primitives.size(), 2u);
    const auto& p = s.primitives[0];
    ASSERT_EQ(p.uv1.size(), p.vertices.size());
    EXPECT_EQ(p.uv1[0], glm::vec2(0.25f, 0.5f));
    EXPECT_EQ(p.uv1[2], glm::vec2(0.25f, 1.0f));
    EXPECT_EQ(p.vertices[1].uv, glm::vec2(1, 0));  // TEXCOORD_0 is not replaced by the second set
    EXPECT_TRUE(s.primitives[1].uv1.empty());
    // Same element-count rule as every attribute.
    g.j["accessors"][tc1]["count"] = 2;
    EXPECT_NE(errorOf([&] { g.load(); }).find("TEXCOORD_1"), std::string::npos);
}

TEST(Loader, LightsAndCamerasFromNodes) {
    GltfBuilder g;
    g.j["extensionsUsed"] = {"KHR_lights_punctual"};
    g.j["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "directional"}, {"color", {1, 0.5, 0.25}}, {"intensity", 3}},
        {{"type", "point"}, {"intensity", 2}, {"range", 5}},
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.4}}}}};
    const double s = std::sqrt(0.5);
    // Rotated -90 degrees about X: local -Z becomes world -Y.
    g.addNode({{"rotation", {-s, 0, 0, s}}, {"translation", {1, 2, 3}},
               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    g.addNode({{"translation", {0, 4, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    g.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    g.j["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 3}, {"znear", 0.1}, {"zfar", 50}}}}};
    g.addNode({{"camera", 0}, {"translation", {0, 0, 9}}});
    g.j["scenes"] = {{{"nodes", {0, 1, 2, 3}}}};
    Scene sc = g.load();
    ASSERT_EQ(sc.lights.size(), 3u);
    EXPECT_EQ(sc.lights[0].type, gis::LightType::Directional);
    EXPECT_NEAR(sc.lights[0].direction.y, -1.0f, 1e-6f);
    EXPECT_EQ(sc.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(sc.lights[0].intensity, 3.0f);
    EXPECT_EQ(sc.lights[1].type, gis::LightType::Point);
    EXPECT_EQ(sc.lights[1].position, glm::vec3(0, 4, 0));
    EXPECT_EQ(sc.lights[1].range, 5.0f);
    EXPECT_EQ(sc.lights[2].type, gis::LightType::Spot);
    EXPECT_NEAR(sc.lights[2].outerConeAngle, 0.4f, 1e-7f);
    EXPECT_NEAR(sc.lights[2].direction.z, -1.0f, 1e-7f);
    ASSERT_EQ(sc.cameras.size(), 1u);
    EXPECT_TRUE(sc.cameras[0].orthographic);
    EXPECT_EQ(sc.cameras[0].ymag, 3.0f);
    EXPECT_EQ(glm::vec3(sc.cameras[0].cameraToWorld[3]), glm::vec3(0, 0, 9));
    g.j["nodes"][2]["extensions"]["KHR_lights_punctual"]["light"] = 7;
    EXPECT_NE(errorOf([&] { g.load(); }).find("light 7"), std::string::npos);
}

TEST(Loader, ExtensionsWarnOrFail) {
    GltfBuilder g = stripBuilder(4);
    g.j["extensionsUsed"] = {"KHR_texture_transform", "EXT_fancy"};
    Scene s = g.load();
    int tt = 0, fancy = 0;
    for (const auto& w : s.warnings) {
        tt += w.find("KHR_texture_transform") != std::string::npos;
        fancy += w.find("EXT_fancy") != std::string::npos;
    }
    EXPECT_EQ(tt, 1);
    EXPECT_EQ(fancy, 1);
    g.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    EXPECT_NE(errorOf([&] { g.load(); }).find("requires extension KHR_draco_mesh_compression"),
              std::string::npos);
}

TEST(Loader, UndecodableTextureIsWarningNotError) {
    GltfBuilder g = stripBuilder(4);
    std::vector<uint8_t> bad = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 1, 2, 3, 4, 5};
    g.j["images"] = {{{"uri", "data:image/png;base64," + base64(bad)}}};
    g.j["textures"] = {{{"source", 0}}};
    g.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    Scene s = g.load();
    EXPECT_EQ(s.materials[0].baseColorTexture, -1);
    EXPECT_TRUE(s.images.empty());
    bool warned = false;
    for (const auto& w : s.warnings) warned = warned || w.find("image 0") != std::string::npos;
    EXPECT_TRUE(warned);
}

// A PNG whose first data chunk is empty (the fuzzer's find, 2026-12-07): stb_image copies zero
// bytes into its not yet allocated buffer, memcpy(NULL, p, 0), which UBSan stops on. The sanitized
// builds leave that one check out of stb's translation unit (tests/scene/CMakeLists.txt,
// fuzz/CMakeLists.txt); the image is a warning, the scene loads.
TEST(Loader, APngWithAnEmptyFirstDataChunkIsAWarning) {
    auto chunk = [](std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data) {
        const uint32_t n = uint32_t(data.size());
        for (int shift : {24, 16, 8, 0}) png.push_back(uint8_t(n >> shift));
        png.insert(png.end(), type, type + 4);
        png.insert(png.end(), data.begin(), data.end());
        png.insert(png.end(), 4, 0);  // CRC: stb_image does not check it
    };
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    chunk(png, "IHDR", {0, 0, 0, 2, 0, 0, 0, 2, 8, 2, 0, 0, 0});  // 2x2, 8-bit RGB
    chunk(png, "IDAT", {});
    chunk(png, "IEND", {});
    GltfBuilder g = stripBuilder(4);
    g.j["images"] = {{{"uri", "data:image/png;base64," + base64(png)}}};
    g.j["textures"] = {{{"source", 0}}};
    g.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    const Scene s = g.load();
    EXPECT_EQ(s.materials[0].baseColorTexture, -1);
    bool warned = false;
    for (const auto& w : s.warnings) warned = warned || w.find("image 0 cannot be decoded") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(Loader, GreyPngBecomesRgba8AndSrgbMarked) {
    const uint8_t grey[4] = {0, 100, 200, 255};
    std::vector<uint8_t> png;
    stbi_write_png_to_func(
        [](void* ctx, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(ctx);
            out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
        },
        &png, 2, 2, 1, grey, 2);
    ASSERT_FALSE(png.empty());
    GltfBuilder g = stripBuilder(4);
    g.j["images"] = {{{"uri", "data:image/png;base64," + base64(png)}}};
    g.j["textures"] = {{{"source", 0}}};
    g.j["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                         {"normalTexture", {{"index", 0}, {"scale", 0.5}}}}};
    g.j["meshes"][0]["primitives"][0]["material"] = 0;
    Scene s = g.load();
    ASSERT_EQ(s.images.size(), 1u);  // decoded once, shared by both slots
    EXPECT_TRUE(s.images[0].srgb);
    EXPECT_EQ(s.images[0].width, 2);
    EXPECT_EQ(s.images[0].rgba8, (std::vector<uint8_t>{0, 0, 0, 255, 100, 100, 100, 255, 200, 200, 200, 255,
                                                        255, 255, 255, 255}));
    EXPECT_EQ(s.materials[0].normalTexture, 0);
    EXPECT_FLOAT_EQ(s.materials[0].normalScale, 0.5f);
}

TEST(Loader, HostileInputsAreCleanErrors) {
    // Deep nesting, truncated JSON, not JSON, truncated GLB, GLB v1, chunk past the end.
    std::string deep = "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[') +
                       std::string(100000, ']') + "}";
    EXPECT_NE(errorOf([&] { loadString(deep); }).find("nested deeper"), std::string::npos);
    EXPECT_NE(errorOf([&] { loadString("{\"asset\":{\"version\":\"2.0\""); }), "");
    EXPECT_NE(errorOf([&] { loadString("hello"); }), "");
    EXPECT_NE(errorOf([&] { loadString(""); }), "");
    const std::string glbHead("glTF\x02\x00\x00\x00\x40\x00\x00\x00", 12);
    EXPECT_NE(errorOf([&] { loadString(glbHead); }).find("truncated"), std::string::npos);
    std::string v1 = glbHead;
    v1[4] = 1;
    EXPECT_NE(errorOf([&] { loadString(v1); }).find("version 1"), std::string::npos);
    std::string json = "{\"asset\":{\"version\":\"2.0\"}}";
    std::string glb = std::string("glTF\x02\x00\x00\x00", 8);
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    glb += u32(12 + 8 + 28 + 8) + u32(28) + "JSON" + json + u32(100) + "BIN\0";
    glb.resize(12 + 8 + 28 + 8);
    EXPECT_NE(errorOf([&] { loadString(glb); }).find("runs past the end"), std::string::npos)
        << errorOf([&] { loadString(glb); });
    // One-line messages even when names contain newlines.
    GltfBuilder g = stripBuilder(9);
    g.j["meshes"][0]["name"] = "evil\nname";
    const std::string msg = errorOf([&] { g.load(); });
    EXPECT_EQ(msg.find('\n'), std::string::npos);
    EXPECT_NE(msg.find("evil name"), std::string::npos) << msg;
}

TEST(Loader, ExternalFilesOnlyUnderTheBaseDirectory) {
    const std::string dir = gltfDir() + "/Box/glTF";
    std::vector<uint8_t> json = readBytes(dir + "/Box.gltf");
    std::string text(json.begin(), json.end());
    EXPECT_NO_THROW(gis::loadGltfMemory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), dir));
    // Same buffer reached by an absolute path or through '..': refused.
    for (const std::string& uri : {dir + "/Box0.bin", std::string("../glTF/Box0.bin")}) {
        std::string evil = text;
        const size_t at = evil.find("\"Box0.bin\"");
        ASSERT_NE(at, std::string::npos);
        evil.replace(at, 10, "\"" + uri + "\"");
        const std::string msg = errorOf([&] {
            gis::loadGltfMemory(reinterpret_cast<const uint8_t*>(evil.data()), evil.size(), dir);
        });
        EXPECT_NE(msg, "") << uri;
    }
}

TEST(Loader, UnbackedAccessorCountIsBounded) {
    GltfBuilder g = stripBuilder(4);
    g.j["accessors"][0].erase("bufferView");
    g.j["accessors"][0]["count"] = 5000000;   // zeros, not backed by any buffer bytes
    EXPECT_NE(errorOf([&] { g.load(); }).find("no bufferView"), std::string::npos);
}

TEST(Loader, EmptySceneLoads) {
    Scene s = loadString("{\"asset\":{\"version\":\"2.0\"}}");
    EXPECT_EQ(s.triangleCount(), 0u);
    EXPECT_TRUE(s.bounds.empty());
}
