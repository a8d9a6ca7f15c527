// Helpers for the scene tests: where the shared assets are, reading a glTF's JSON on its own
// (independently of the loader), and building small glTF files in memory.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene.h"

#ifndef GIS_SHARED_DIR
#error "GIS_SHARED_DIR must be defined (tests/CMakeLists.txt)"
#endif

namespace gistest {

inline std::string sharedDir() { return GIS_SHARED_DIR; }
inline std::string gltfDir() { return sharedDir() + "/assets/gltf"; }
inline std::string referenceScene(const std::string& name) {
    return sharedDir() + "/assets/reference/scenes/" + name + "/" + name + ".gltf";
}

inline std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), {});
}

// The JSON of a .gltf or .glb, parsed with nlohmann (not through the loader).
inline nlohmann::json readGltfJson(const std::string& path) {
    std::vector<uint8_t> b = readBytes(path);
    if (b.size() >= 20 && std::memcmp(b.data(), "glTF", 4) == 0) {
        uint32_t len;
        std::memcpy(&len, b.data() + 12, 4);
        return nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + len);
    }
    return nlohmann::json::parse(b.begin(), b.end());
}

inline std::string base64(const std::vector<uint8_t>& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8) | in[i + 2];
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
    }
    if (i + 1 == in.size()) {
        const uint32_t v = uint32_t(in[i]) << 16;
        out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == in.size()) {
        const uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8);
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
    }
    return out;
}

// Builds a small glTF with one embedded (data URI) buffer.
struct GltfBuilder {
    nlohmann::json j = {{"asset", {{"version", "2.0"}}}};
    std::vector<uint8_t> bin;

    int addView(const void* data, size_t bytes) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t off = bin.size();
        const auto* p = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), p, p + bytes);
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", off}, {"byteLength", bytes}});
        return static_cast<int>(j["bufferViews"].size()) - 1;
    }
    int addAccessor(int view, int componentType, size_t count, const char* type,
                    nlohmann::json extra = nlohmann::json::object()) {
        nlohmann::json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (view >= 0) a["bufferView"] = view;
        a.update(extra);
        j["accessors"].push_back(a);
        return static_cast<int>(j["accessors"].size()) - 1;
    }
    int addVec3(const std::vector<glm::vec3>& v) {
        return addAccessor(addView(v.data(), v.size() * 12), 5126, v.size(), "VEC3");
    }
    int addVec2(const std::vector<glm::vec2>& v) {
        return addAccessor(addView(v.data(), v.size() * 8), 5126, v.size(), "VEC2");
    }
    int addIndices(const std::vector<uint32_t>& v) {
        return addAccessor(addView(v.data(), v.size() * 4), 5125, v.size(), "SCALAR");
    }
    // A mesh with one primitive; returns the mesh index.
    int addMesh(nlohmann::json primitive) {
        j["meshes"].push_back({{"primitives", {primitive}}});
        return static_cast<int>(j["meshes"].size()) - 1;
    }
    int addNode(nlohmann::json node) {
        j["nodes"].push_back(node);
        return static_cast<int>(j["nodes"].size()) - 1;
    }
    // Node with the mesh, listed in scene 0.
    int addMeshNode(int mesh, nlohmann::json extra = nlohmann::json::object()) {
        nlohmann::json n = {{"mesh", mesh}};
        n.update(extra);
        const int id = addNode(n);
        j["scenes"][0]["nodes"].push_back(id);
        return id;
    }
    std::string json() {
        nlohmann::json out = j;
        if (!bin.empty())
            out["buffers"] = {{{"byteLength", bin.size()},
                               {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
        return out.dump();
    }
    gis::Scene load() {
        const std::string s = json();
        return gis::loadGltfMemory(reinterpret_cast<const uint8_t*>(s.data()), s.size(), "");
    }
};

inline gis::Scene loadString(const std::string& s) {
    return gis::loadGltfMemory(reinterpret_cast<const uint8_t*>(s.data()), s.size(), "");
}

// The message of the gis::Error that `f` throws ("" if it does not throw one).
template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const gis::Error& e) {
        return e.what();
    }
    return "";
}

inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace gistest
