// Writes a Scene as glTF 2.0 (a .gltf with its .bin beside it), so the built-in scenes can be
// rendered by other renderers (Blender, Godot, three.js) and compared with ours: positions,
// normals and indices per primitive, one node per draw (its world matrix), materials
// (metallic-roughness factors, emission with KHR_materials_emissive_strength, doubleSided,
// KHR_materials_specular's factor), KHR_lights_punctual lights and perspective cameras. Images
// are not written (the built-in scenes have none): a textured scene loses its textures. glTF has
// no environment colour: the sky radiance (atrium's, the default sky) must be set by the reader.
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene/atomic_file.h"
#include "scene/scene.h"
#include "scene/scene_internal.h"

namespace gis {

namespace {

// Appends raw bytes to the buffer, 4-byte aligned, and returns a buffer view over them.
int addView(tinygltf::Model& m, const void* data, size_t bytes, int target) {
    std::vector<unsigned char>& buf = m.buffers[0].data;
    while (buf.size() % 4) buf.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = buf.size();
    v.byteLength = bytes;
    v.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buf.insert(buf.end(), p, p + bytes);
    m.bufferViews.push_back(v);
    return int(m.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& m, int view, int componentType, int type, size_t count) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    m.accessors.push_back(a);
    return int(m.accessors.size()) - 1;
}

void addPrimitive(tinygltf::Model& m, const Primitive& p) {
    std::vector<float> positions, normals;
    std::vector<double> lo(3, 1e300), hi(3, -1e300);
    for (const Vertex& v : p.vertices) {
        for (int c = 0; c < 3; ++c) {
            positions.push_back(v.position[c]);
            normals.push_back(v.normal[c]);
            lo[size_t(c)] = std::min(lo[size_t(c)], double(v.position[c]));
            hi[size_t(c)] = std::max(hi[size_t(c)], double(v.position[c]));
        }
    }
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.material = p.material;
    const int pos = addAccessor(m, addView(m, positions.data(), positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, p.vertices.size());
    m.accessors[size_t(pos)].minValues = lo;  // required for POSITION
    m.accessors[size_t(pos)].maxValues = hi;
    prim.attributes["POSITION"] = pos;
    prim.attributes["NORMAL"] =
        addAccessor(m, addView(m, normals.data(), normals.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, p.vertices.size());
    prim.indices = addAccessor(m, addView(m, p.indices.data(), p.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                               TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, p.indices.size());
    tinygltf::Mesh mesh;
    mesh.primitives.push_back(prim);
    m.meshes.push_back(mesh);
}

tinygltf::Material material(const Material& in) {
    tinygltf::Material out;
    out.name = in.name;
    out.pbrMetallicRoughness.baseColorFactor = {in.baseColorFactor.r, in.baseColorFactor.g, in.baseColorFactor.b,
                                                in.baseColorFactor.a};
    out.pbrMetallicRoughness.metallicFactor = in.metallicFactor;
    out.pbrMetallicRoughness.roughnessFactor = in.roughnessFactor;
    out.doubleSided = in.doubleSided;
    // Emission: the factor holds the colour (at most 1), the strength the rest.
    const float strength = std::max({in.emissive.r, in.emissive.g, in.emissive.b, 1.0f});
    out.emissiveFactor = {in.emissive.r / strength, in.emissive.g / strength, in.emissive.b / strength};
    if (strength > 1.0f) {
        tinygltf::Value::Object e;
        e["emissiveStrength"] = tinygltf::Value(double(strength));
        out.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(e);
    }
    if (in.specularFactor != 1.0f) {
        tinygltf::Value::Object e;
        e["specularFactor"] = tinygltf::Value(double(in.specularFactor));
        out.extensions["KHR_materials_specular"] = tinygltf::Value(e);
    }
    return out;
}

tinygltf::Value light(const Light& l) {
    static const char* const types[] = {"directional", "point", "spot"};
    tinygltf::Value::Object o;
    o["name"] = tinygltf::Value(l.name);
    o["type"] = tinygltf::Value(std::string(types[int(l.type)]));
    o["color"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(l.color.r)),
                                                        tinygltf::Value(double(l.color.g)),
                                                        tinygltf::Value(double(l.color.b))});
    o["intensity"] = tinygltf::Value(double(l.intensity));
    if (l.range > 0.0f) o["range"] = tinygltf::Value(double(l.range));
    if (l.type == LightType::Spot) {
        tinygltf::Value::Object spot;
        spot["innerConeAngle"] = tinygltf::Value(double(l.innerConeAngle));
        spot["outerConeAngle"] = tinygltf::Value(double(l.outerConeAngle));
        o["spot"] = tinygltf::Value(spot);
    }
    return tinygltf::Value(o);
}

// A node placing a light or camera: at `position`, its local -Z along `forward` (glTF's convention).
std::vector<double> poseMatrix(glm::vec3 position, glm::vec3 forward) {
    forward = glm::length(forward) > 0.0f ? glm::normalize(forward) : glm::vec3(0, 0, -1);
    const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 x = glm::normalize(glm::cross(forward, up)), y = glm::cross(x, forward);
    const glm::mat4 m(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(-forward, 0), glm::vec4(position, 1));
    std::vector<double> out;
    for (int c = 0; c < 16; ++c) out.push_back(m[c / 4][c % 4]);
    return out;
}

std::vector<double> matrix(const glm::mat4& m) {
    std::vector<double> out;
    for (int c = 0; c < 16; ++c) out.push_back(m[c / 4][c % 4]);
    return out;
}

}  // namespace

GltfBytes serializeGltf(const Scene& scene, const std::string& binName) {
    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "gisandbox";
    m.buffers.resize(1);
    for (const Material& mat : scene.materials) m.materials.push_back(material(mat));
    for (const Primitive& p : scene.primitives) addPrimitive(m, p);
    tinygltf::Scene root;
    for (const DrawItem& d : scene.draws) {
        tinygltf::Node n;
        n.mesh = d.primitive;
        n.matrix = matrix(d.world);
        m.nodes.push_back(n);
        root.nodes.push_back(int(m.nodes.size()) - 1);
    }
    if (!scene.lights.empty()) {
        tinygltf::Value::Array lights;
        for (size_t i = 0; i < scene.lights.size(); ++i) {
            const Light& l = scene.lights[i];
            lights.push_back(light(l));
            tinygltf::Node n;
            n.name = l.name;
            n.matrix = poseMatrix(l.position, l.direction);
            tinygltf::Value::Object ext;
            ext["light"] = tinygltf::Value(int(i));
            n.extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
            m.nodes.push_back(n);
            root.nodes.push_back(int(m.nodes.size()) - 1);
        }
        tinygltf::Value::Object ext;
        ext["lights"] = tinygltf::Value(lights);
        m.extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
        m.extensionsUsed.push_back("KHR_lights_punctual");
    }
    for (const Camera& c : scene.cameras) {
        tinygltf::Camera cam;
        cam.name = c.name;
        cam.type = "perspective";
        cam.perspective.yfov = c.yfov;
        cam.perspective.znear = c.znear;
        cam.perspective.zfar = c.zfar;
        cam.perspective.aspectRatio = 0.0;  // absent: the viewport's
        m.cameras.push_back(cam);
        tinygltf::Node n;
        n.name = c.name;
        n.camera = int(m.cameras.size()) - 1;
        n.matrix = matrix(c.cameraToWorld);
        m.nodes.push_back(n);
        root.nodes.push_back(int(m.nodes.size()) - 1);
    }
    for (const tinygltf::Material& mat : m.materials)
        for (const auto& [name, value] : mat.extensions)
            if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), name) == m.extensionsUsed.end())
                m.extensionsUsed.push_back(name);
    m.scenes.push_back(root);
    m.defaultScene = 0;
    // Serialized in memory, the buffer left out and added back naming its file: tinygltf's file
    // writer checks none of its writes. Same bytes as that writer gave (indented, members sorted),
    // so the bench's content ids of built-in scenes do not change.
    GltfBytes out;
    out.bin.assign(m.buffers[0].data.begin(), m.buffers[0].data.end());
    m.buffers.clear();
    std::ostringstream json;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&m, json, false, false)) throw Error("cannot serialize the glTF file");
    // nlohmann::json, as tinygltf's writer: members sorted by name.
    nlohmann::json doc = nlohmann::json::parse(json.str());
    nlohmann::json buffer;
    buffer["byteLength"] = out.bin.size();
    buffer["uri"] = binName;
    buffer["name"] = "geometry";
    doc["buffers"] = nlohmann::json::array({buffer});
    out.json = doc.dump(2) + "\n";  // indented and ended as the file writer wrote it
    return out;
}

void writeGltf(const Scene& scene, const std::string& path) {
    const std::string binName = std::filesystem::path(path).stem().string() + ".bin";
    GltfBytes bytes;
    try {
        bytes = serializeGltf(scene, binName);
    } catch (const std::exception& e) {
        throw Error(detail::oneLine(path, 200) + ": " + e.what());
    }
    const std::string bin = (std::filesystem::path(path).parent_path() / binName).string();
    // Both or neither: a .gltf naming a .bin of another export would load wrong geometry.
    writeFilesAtomically({{bin, bytes.bin}, {path, bytes.json}});
}

}  // namespace gis
