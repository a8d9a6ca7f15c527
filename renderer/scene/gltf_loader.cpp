// glTF 2.0 (.gltf / .glb) -> gis::Scene, through tinygltf for the JSON, with every buffer access
// done here and bounds-checked. Hostile input must end in a gis::Error (one line, naming the
// file and the problem) or a loaded scene with warnings; never a crash, hang or huge allocation.
//
// tinygltf 2.7 (Debian) trusts some offsets itself, so before handing it a file we
//   * re-pack a .glb into a canonical JSON + BIN container after checking every chunk bound,
//   * parse the JSON once with a nesting limit (tinygltf recurses on extras/extensions),
//   * check that images stored in bufferViews lie inside their buffers,
//   * allow at most one GLB buffer without a uri (each would copy the whole BIN chunk),
// and give it our own file callbacks (regular files only, size-capped) and image callback
// (keeps the encoded bytes; we decode with stb_image ourselves, with size limits).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include "scene/limits.h"
#include "scene/scene.h"
#include "scene/scene_internal.h"

namespace gis {
namespace {

using detail::oneLine;

// --- Limits against hostile input ----------------------------------------------------------
constexpr uint64_t kMaxFileBytes = 1ull << 30;           // one file: .gltf/.glb/.bin/image
constexpr uint64_t kMaxTotalReadBytes = 4ull << 30;      // all external files of one load
constexpr uint64_t kMaxInputBytes = (1ull << 31) - 1;    // tinygltf takes an unsigned int length
constexpr uint64_t kMaxImagePixels = 1ull << 26;         // 64 Mpixel (256 MiB RGBA8) per image
constexpr uint64_t kMaxTotalImagePixels = 1ull << 28;    // 1 GiB of RGBA8 per scene
constexpr uint64_t kMaxTotalVertices = 1ull << 24;       // 1 GiB of gis::Vertex per scene
constexpr uint64_t kMaxTotalIndices = 1ull << 26;        // 256 MiB of indices per scene
constexpr int kMaxJsonDepth = 64;

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

// Extensions we read.
const std::set<std::string> kSupportedExtensions = {
    "KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_specular"};

// Extensions that, when ignored, still leave geometry and textures readable (the picture is
// only approximate), so even a file that *requires* them loads, with a warning.
bool ignorableExtension(const std::string& e) {
    return e == "KHR_texture_transform" || e.rfind("KHR_materials_", 0) == 0 ||
           e == "KHR_lights_punctual" || e == "MSFT_lod" || e == "KHR_xmp_json_ld" ||
           e == "KHR_materials_variants" || e == "KHR_animation_pointer";
}

std::string str(uint64_t v) { return std::to_string(v); }
std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

std::string quoted(const std::string& name) {
    return name.empty() ? std::string() : " ('" + oneLine(name, 60) + "')";
}

uint32_t readU32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

void writeU32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// --- File access (also tinygltf's callbacks) -----------------------------------------------
struct FsState {
    std::string baseDir;
    uint64_t totalRead = 0;
};

// External files must lie under the base directory: a relative URI without '..' segments
// (glTF URIs are relative references). Absolute paths and escapes like ../../etc/passwd are
// refused, so a downloaded file cannot read arbitrary files into its buffers or textures.
bool allowedPath(const std::string& path, const FsState* st) {
    std::string rest = path;
    const std::string& base = st ? st->baseDir : std::string();
    if (!base.empty()) {
        const std::string prefix = base.back() == '/' ? base : base + "/";
        if (path.compare(0, prefix.size(), prefix) != 0) return false;
        rest = path.substr(prefix.size());
    }
    if (rest.empty() || rest[0] == '/') return false;
    size_t start = 0;
    while (start <= rest.size()) {
        size_t end = rest.find('/', start);
        if (end == std::string::npos) end = rest.size();
        if (rest.compare(start, end - start, "..") == 0 && end - start == 2) return false;
        start = end + 1;
    }
    return true;
}

// Reads a regular file of at most kMaxFileBytes. On failure returns false with a reason.
bool readRegularFile(const std::string& path, std::vector<unsigned char>& out, std::string& why,
                     FsState* state) {
    // O_NONBLOCK: opening a FIFO for reading blocks until a writer appears, so the
    // regular-file check must come before a blocking open. Checking the descriptor we opened
    // (not a stat of the path beforehand) leaves no window to swap the file.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        why = std::strerror(errno);
        return false;
    }
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        why = "not a regular file";
        return false;
    }
    FILE* f = ::fdopen(fd, "rb");
    if (!f) {
        why = std::strerror(errno);
        ::close(fd);
        return false;
    }
    const uint64_t size = static_cast<uint64_t>(st.st_size);
    if (size > kMaxFileBytes) {
        std::fclose(f);
        why = "file is too large (" + str(size) + " bytes, limit " + str(kMaxFileBytes) + ")";
        return false;
    }
    if (state) {
        if (state->totalRead + size > kMaxTotalReadBytes) {
            std::fclose(f);
            why = "external files of this glTF exceed " + str(kMaxTotalReadBytes) + " bytes in total";
            return false;
        }
        state->totalRead += size;
    }
    out.resize(static_cast<size_t>(size));
    size_t got = size ? std::fread(out.data(), 1, out.size(), f) : 0;
    std::fclose(f);
    if (got != out.size()) {
        why = "read error";
        out.clear();
        return false;
    }
    return true;
}

bool fsFileExists(const std::string& path, void* user) {
    struct stat st {};
    return allowedPath(path, static_cast<FsState*>(user)) && stat(path.c_str(), &st) == 0 &&
           S_ISREG(st.st_mode);
}

std::string fsExpandFilePath(const std::string& path, void*) { return path; }  // no expansion

bool fsReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user) {
    std::string why;
    if (!allowedPath(path, static_cast<FsState*>(user))) {
        if (err) *err += path + ": outside the glTF's directory\n";
        return false;
    }
    if (!readRegularFile(path, *out, why, static_cast<FsState*>(user))) {
        if (err) *err += path + ": " + why + "\n";
        return false;
    }
    return true;
}

bool fsWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
    if (err) *err += "writing is disabled\n";
    return false;
}

// Keeps the encoded bytes of images given by uri; images in bufferViews are read later by us
// (with bounds checks). Decoding happens only for images that materials use.
bool keepImageBytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                    const unsigned char* bytes, int size, void*) {
    image->as_is = true;
    if (image->bufferView >= 0) return true;
    if (bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// --- Pre-validation with nlohmann::json ----------------------------------------------------

bool asUnsigned(const nlohmann::json& obj, const char* key, uint64_t& out, bool required) {
    auto it = obj.find(key);
    if (it == obj.end()) return !required;
    if (!it->is_number_unsigned()) return false;
    out = it->get<uint64_t>();
    return true;
}

// The data: URI headers tinygltf 2.7 decodes (IsDataURI); anything else it treats as a path.
const char* const kDataUriHeaders[] = {
    "data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,",
    "data:image/jpeg;base64,", "data:image/png;base64,", "data:image/bmp;base64,",
    "data:image/gif;base64,", "data:text/plain;base64,"};

// Bytes tinygltf's base64_decode yields: it stops at the first '=' or non-alphabet character.
uint64_t base64DecodedSize(const std::string& s, size_t from) {
    uint64_t n = 0;
    for (size_t i = from; i < s.size(); ++i) {
        const char c = s[i];
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/')) break;
        ++n;
    }
    return n / 4 * 3 + (n % 4 ? n % 4 - 1 : 0);
}

// Percent-decoding as tinygltf applies it to buffer URIs ('+' is a space there too).
std::string urlDecode(const std::string& s) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '+') {
            out += ' ';
        } else if (s[i] == '%' && i + 2 < s.size()) {
            out += static_cast<char>((hex(s[i + 1]) << 4) | hex(s[i + 2]));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

// A URI short enough to quote in a one-line message.
std::string shortUri(const std::string& uri) {
    if (uri.size() <= 60) return oneLine(uri, 60);
    return oneLine(uri.substr(0, 40), 40) + "...(" + str(uri.size()) + " chars)";
}

// tinygltf's error text as one short line: its lines deduplicated (it reports some twice), long
// URIs shortened, at most 200 characters.
std::string tinygltfReason(const std::string& err) {
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < err.size()) {
        size_t end = err.find('\n', start);
        if (end == std::string::npos) end = err.size();
        std::string line = oneLine(err.substr(start, end - start), 1000);
        start = end + 1;
        for (const char* scheme : {"data:", "http://", "https://"}) {
            const size_t at = line.find(scheme);
            if (at == std::string::npos) continue;
            size_t stop = line.find_first_of(" '\"", at);
            if (stop == std::string::npos) stop = line.size();
            line = line.substr(0, at) + shortUri(line.substr(at, stop - at)) + line.substr(stop);
        }
        if (!line.empty() && std::find(lines.begin(), lines.end(), line) == lines.end()) lines.push_back(line);
    }
    std::string joined;
    for (const std::string& l : lines) joined += (joined.empty() ? "" : "; ") + l;
    return oneLine(joined, 200);
}

class Loader {
public:
    explicit Loader(std::string label) : label_(std::move(label)) {}

    Scene load(const uint8_t* data, size_t size, const std::string& baseDir);

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(oneLine(label_ + ": " + what, 700));
    }
    void warn(const std::string& w) {
        const std::string line = oneLine(w, 300);
        if (warned_.insert(line).second) scene_.warnings.push_back(line);
    }

    struct GlbChunks {
        const char* json = nullptr;
        size_t jsonLen = 0;
        const uint8_t* bin = nullptr;
        uint64_t binLen = 0;
        bool haveBin = false;
    };
    GlbChunks readGlbChunks(const uint8_t* data, size_t size);
    std::vector<uint8_t> canonicalGlb(const GlbChunks& chunks);
    void parseModel(bool binary, const std::vector<uint8_t>& glb, const char* json, size_t jsonLen,
                    const std::string& baseDir);

    void prevalidate(const char* json, size_t len, bool binary);
    nlohmann::json parseJsonObject(const char* json, size_t len);
    const nlohmann::json* jsonArray(const nlohmann::json& doc, const char* key);
    void requireKeys(const nlohmann::json& obj, const std::string& what, std::initializer_list<const char*> keys);
    void checkAsset(const nlohmann::json& doc);
    void checkBufferUris(const nlohmann::json& buffers, bool binary);
    void checkBufferUri(const std::string& what, const std::string& uri, const nlohmann::json& buffer);
    void checkRequiredProperties(const nlohmann::json& doc, const nlohmann::json* buffers,
                                 const nlohmann::json* views, const nlohmann::json* images);
    void checkSkinJoints(const nlohmann::json& skins);
    void checkBinChunkBuffers(const nlohmann::json& buffers);
    void checkByteStrides(const nlohmann::json& views);
    void noteBadCameras(const nlohmann::json& cameras);
    void checkLights(const nlohmann::json& doc);
    void checkImageBufferViews(const nlohmann::json& images, const nlohmann::json* views,
                               const nlohmann::json* buffers);

    void checkExtensions();
    void checkCameraDepthRange();
    void buildNodes();
    std::vector<int> nodeParents();
    std::vector<int> sceneRoots(const std::vector<int>& parent);
    glm::mat4 nodeLocalTransform(const tinygltf::Node& node, const std::string& where);
    void convertMaterials();
    glm::vec3 emittedRadiance(const tinygltf::Material& src, const std::string& where);
    int textureImage(int textureIndex, int texCoord, const tinygltf::ExtensionMap& ext,
                     const std::string& where, bool srgb);
    int decodeImage(int imageIndex);
    int primitiveFor(int mesh, int prim);
    Primitive convertPrimitive(int mesh, int prim, const std::string& where);
    void readPositions(const tinygltf::Primitive& src, const std::string& where, Primitive& p);
    void readVertexAttributes(const tinygltf::Primitive& src, const std::string& where, Primitive& p);
    std::vector<uint32_t> triangleList(const tinygltf::Primitive& src, int mode, const std::string& where,
                                       size_t nv);
    void addNodeContent(int node, const glm::mat4& world);
    Camera nodeCamera(int cameraIndex, const std::string& where, const glm::mat4& world);
    Light nodeLight(const tinygltf::Value& ext, const std::string& where, const glm::mat4& world);

    struct AccessorData {
        std::vector<glm::vec4> values;  // for attributes
        std::vector<uint32_t> indices;  // for index accessors
    };
    struct AccessorSource {
        const uint8_t* first = nullptr;  // nullptr: no bufferView, the elements are zeros
        uint64_t stride = 0;
    };
    struct SparseSource {
        const uint8_t* indices = nullptr;
        const uint8_t* values = nullptr;
        int indexType = 0, indexSize = 0;
        int count = 0;
    };
    const tinygltf::BufferView& checkedBufferView(int bv, const std::string& what,
                                                  const uint8_t** base);
    AccessorSource accessorSource(const tinygltf::Accessor& acc, const std::string& name, uint64_t count,
                                  uint64_t elemSize);
    SparseSource sparseSource(const tinygltf::Accessor& acc, const std::string& name, uint64_t count,
                              uint64_t elemSize);
    void readAccessor(int index, const std::string& what, bool asIndices, AccessorData& out);
    std::vector<uint8_t> bufferViewBytes(int bv, const std::string& what);

    std::string label_;
    std::string baseDir_;
    Scene scene_;
    tinygltf::Model model_;
    std::set<std::string> warned_;
    std::map<std::pair<int, int>, int> primitiveIndex_;  // (mesh, primitive) -> scene primitive
    std::vector<int> imageIndex_;                         // glTF image -> scene image, -1 failed
    uint64_t totalVertices_ = 0, totalIndices_ = 0, totalPixels_ = 0;
    // Spec violations seen in the JSON, refused when a node uses the camera/light.
    std::map<int, std::string> badCameras_, badLights_;
};

// Deepest nesting of arrays/objects in `json`, stopping early past `limit`. One linear scan:
// nlohmann 3.11's callback parser (the obvious way to limit depth) rescans the parent container
// after every element, which made 10^5 nodes take seconds and 10^6 nodes minutes. Malformed JSON
// (unbalanced brackets, unterminated strings) is left to the real parser to report.
int jsonNestingDepth(const char* json, size_t len, int limit) {
    int depth = 0, deepest = 0;
    bool inString = false;
    for (size_t i = 0; i < len; ++i) {
        const char c = json[i];
        if (inString) {
            if (c == '\\')
                ++i;  // the escaped character cannot end the string
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) return deepest;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

void Loader::checkBufferUri(const std::string& what, const std::string& uri, const nlohmann::json& buffer) {
    if (uri.compare(0, 5, "data:") == 0) {
        const char* header = nullptr;
        for (const char* h : kDataUriHeaders)
            if (uri.compare(0, std::strlen(h), h) == 0) header = h;
        if (!header)
            fail(what + ".uri: data URI '" + shortUri(uri) +
                 "' is not supported (base64 with media type application/octet-stream or application/gltf-buffer)");
        const uint64_t bytes = base64DecodedSize(uri, std::strlen(header));
        uint64_t byteLength = 0;
        if (asUnsigned(buffer, "byteLength", byteLength, true) && bytes != byteLength)
            fail(what + ": byteLength is " + str(byteLength) + " but its data: URI decodes to " + str(bytes) +
                 " bytes");
        return;
    }
    const size_t colon = uri.find(':'), slash = uri.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
        fail(what + ".uri '" + shortUri(uri) + "' is not a relative file path (network and absolute URIs are not read)");
    if (uri.empty()) fail(what + ".uri is empty");
    // The file as tinygltf will look for it (percent-decoded, joined to the base directory),
    // so that a missing .bin is reported with its buffer instead of as "File not found : x".
    const std::string decoded = urlDecode(uri);
    const std::string path = baseDir_.empty() ? decoded
                             : baseDir_.back() == '/' ? baseDir_ + decoded : baseDir_ + "/" + decoded;
    FsState st;
    st.baseDir = baseDir_;
    if (!allowedPath(path, &st))
        fail(what + ".uri '" + shortUri(uri) + "' lies outside the glTF's directory (absolute or '..')");
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0)
        fail(what + ".uri '" + shortUri(uri) + "': " + std::strerror(errno));
    if (!S_ISREG(info.st_mode)) fail(what + ".uri '" + shortUri(uri) + "' is not a regular file");
}

// The document, its nesting bounded before it is parsed; refused unless its root is an object.
nlohmann::json Loader::parseJsonObject(const char* json, size_t len) {
    // tinygltf recurses on extras/extensions: bound the nesting before anything parses it.
    if (jsonNestingDepth(json, len, kMaxJsonDepth) > kMaxJsonDepth)
        fail("JSON is nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(json, json + len, nullptr, true);
    } catch (const std::exception& e) {
        // "[json.exception.parse_error.101] parse error at ..." without the library's tag.
        std::string what = e.what();
        if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos)
            what = what.substr(what.find("] ") + 2);
        fail("invalid JSON: " + what);
    }
    if (!doc.is_object()) fail("invalid glTF: the JSON root is not an object");
    return doc;
}

// doc[key], nullptr when absent; refused when it is not an array.
const nlohmann::json* Loader::jsonArray(const nlohmann::json& doc, const char* key) {
    auto it = doc.find(key);
    if (it == doc.end()) return nullptr;
    if (!it->is_array()) fail(std::string("invalid glTF: '") + key + "' is not an array");
    return &*it;
}

void Loader::requireKeys(const nlohmann::json& obj, const std::string& what,
                         std::initializer_list<const char*> keys) {
    for (const char* k : keys)
        if (obj.find(k) == obj.end()) fail(what + ": '" + k + "' is missing (required)");
}

void Loader::checkAsset(const nlohmann::json& doc) {
    auto asset = doc.find("asset");
    if (asset == doc.end() || !asset->is_object())
        fail("asset: missing or not an object (a glTF needs \"asset\": {\"version\": \"2.0\"})");
    auto version = asset->find("version");
    if (version == asset->end() || !version->is_string())
        fail("asset.version: missing or not a string (a glTF needs \"asset\": {\"version\": \"2.0\"})");
}

void Loader::checkBufferUris(const nlohmann::json& buffers, bool binary) {
    for (size_t i = 0; i < buffers.size(); ++i) {
        const auto& b = buffers[i];
        if (!b.is_object()) continue;  // tinygltf names the type error
        const std::string what = "buffers[" + str(i) + "]";
        auto u = b.find("uri");
        if (u == b.end()) {
            if (!binary) fail(what + ": no uri (only a .glb's buffer may omit it, for the BIN chunk)");
            continue;
        }
        if (!u->is_string()) continue;
        checkBufferUri(what, u->get_ref<const std::string&>(), b);
    }
}

// Required properties and element types tinygltf checks without saying which element failed
// ("'componentType' property is missing in Accessor.", "`materials' does not contain an JSON
// object."): the same checks, naming the element.
void Loader::checkRequiredProperties(const nlohmann::json& doc, const nlohmann::json* buffers,
                                     const nlohmann::json* views, const nlohmann::json* images) {
    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                            "meshes", "nodes", "samplers", "scenes", "skins", "textures"}) {
        auto it = doc.find(key);
        const nlohmann::json* list = it != doc.end() && it->is_array() ? &*it : nullptr;  // tinygltf skips others
        for (size_t i = 0; list && i < list->size(); ++i)
            if (!(*list)[i].is_object())
                fail(std::string(key) + "[" + str(i) + "] is " + oneLine((*list)[i].dump(), 30) + ", not an object");
    }
    auto eachOf = [&](const char* key, std::initializer_list<const char*> keys) {
        auto it = doc.find(key);
        if (it != doc.end() && it->is_array())
            for (size_t i = 0; i < it->size(); ++i) requireKeys((*it)[i], std::string(key) + "[" + str(i) + "]", keys);
    };
    eachOf("accessors", {"componentType", "count", "type"});
    eachOf("bufferViews", {"buffer", "byteLength"});
    eachOf("buffers", {"byteLength"});
    eachOf("cameras", {"type"});
    if (views)
        for (size_t i = 0; i < views->size(); ++i) {
            auto bl = (*views)[i].find("byteLength");
            if (!bl->is_number_unsigned())
                fail("bufferViews[" + str(i) + "].byteLength is " + oneLine(bl->dump(), 30) +
                     "; it must be a non-negative integer");
        }
    if (buffers)
        for (size_t i = 0; i < buffers->size(); ++i) {
            auto bl = (*buffers)[i].find("byteLength");
            if (!bl->is_number_unsigned() || bl->get<uint64_t>() == 0)
                fail("buffers[" + str(i) + "].byteLength is " + oneLine(bl->dump(), 30) + "; it must be a positive integer");
        }
    if (const nlohmann::json* anims = jsonArray(doc, "animations"))
        for (size_t a = 0; a < anims->size(); ++a)
            for (const char* part : {"channels", "samplers"}) {
                auto list = (*anims)[a].find(part);
                if (list == (*anims)[a].end() || !list->is_array()) continue;
                for (size_t i = 0; i < list->size(); ++i)
                    requireKeys((*list)[i], "animations[" + str(a) + "]." + part + "[" + str(i) + "]",
                                part[0] == 'c' ? std::initializer_list<const char*>{"sampler", "target"}
                                               : std::initializer_list<const char*>{"input", "output"});
            }
    if (images)
        for (size_t i = 0; i < images->size(); ++i)
            if ((*images)[i].find("uri") == (*images)[i].end() && (*images)[i].find("bufferView") == (*images)[i].end())
                fail("images[" + str(i) + "]: neither 'uri' nor 'bufferView' is given (one is required)");
}

void Loader::checkSkinJoints(const nlohmann::json& skins) {
    for (size_t i = 0; i < skins.size(); ++i) {
        const auto& sk = skins[i];
        if (!sk.is_object()) continue;
        auto j = sk.find("joints");
        if (j == sk.end()) fail("skins[" + str(i) + "]: 'joints' is missing (required)");
        if (!j->is_array()) fail("skins[" + str(i) + "].joints is not an array of node indices");
        for (const auto& n : *j)
            if (!n.is_number_unsigned())
                fail("skins[" + str(i) + "].joints holds " + oneLine(n.dump(), 30) + ", not a node index");
    }
}

// Every buffer without a uri would get its own copy of the whole BIN chunk.
void Loader::checkBinChunkBuffers(const nlohmann::json& buffers) {
    size_t noUri = 0;
    for (const auto& b : buffers)
        if (b.is_object() && b.find("uri") == b.end()) ++noUri;
    if (noUri > 1)
        fail("binary glTF has " + str(noUri) +
             " buffers without a uri; only one may refer to the BIN chunk");
}

void Loader::checkByteStrides(const nlohmann::json& views) {
    for (size_t i = 0; i < views.size(); ++i) {
        const auto& view = views[i];
        auto it = view.is_object() ? view.find("byteStride") : view.end();
        if (!view.is_object() || it == view.end()) continue;
        const std::string what = "bufferViews[" + str(i) + "].byteStride";
        if (!it->is_number_unsigned() || it->get<uint64_t>() > 252 ||
            it->get<uint64_t>() % 4 != 0)
            fail(what + " is " + oneLine(it->dump(), 40) +
                 "; it must be a multiple of 4 from 4 to 252 (spec)");
        if (it->get<uint64_t>() == 0)
            warn(what + " is 0, below the spec's minimum 4 (read as tightly packed)");
    }
}

bool positiveIfPresent(const nlohmann::json& obj, const char* key) {
    if (!obj.is_object()) return true;
    auto it = obj.find(key);
    return it == obj.end() || (it->is_number() && it->get<double>() > 0.0);
}

// Noted, not refused: a camera no node uses does not stop the load.
void Loader::noteBadCameras(const nlohmann::json& cameras) {
    for (size_t i = 0; i < cameras.size(); ++i) {
        const auto& cam = cameras[i];
        if (!cam.is_object()) continue;
        auto p = cam.find("perspective");
        if (p != cam.end() && !positiveIfPresent(*p, "aspectRatio"))
            badCameras_[int(i)] = "cameras[" + str(i) + "].perspective.aspectRatio is " +
                                  oneLine((*p)["aspectRatio"].dump(), 40) +
                                  "; it must be > 0 when given (spec)";
    }
}

// KHR_lights_punctual's required properties; a bad range is noted, refused only when a node
// uses the light.
void Loader::checkLights(const nlohmann::json& doc) {
    auto ext = doc.find("extensions");
    if (ext == doc.end() || !ext->is_object()) return;
    auto lp = ext->find("KHR_lights_punctual");
    if (lp == ext->end() || !lp->is_object()) return;
    auto lights = lp->find("lights");
    if (lights == lp->end() || !lights->is_array()) return;
    for (size_t i = 0; i < lights->size(); ++i) {
        const std::string lw = "KHR_lights_punctual.lights[" + str(i) + "]";
        if (!(*lights)[i].is_object()) fail(lw + " is not an object");
        requireKeys((*lights)[i], lw, {"type"});
        if ((*lights)[i]["type"] == "spot") requireKeys((*lights)[i], lw, {"spot"});
        if (!positiveIfPresent((*lights)[i], "range"))
            badLights_[int(i)] = "KHR_lights_punctual.lights[" + str(i) + "].range is " +
                                 oneLine((*lights)[i]["range"].dump(), 40) +
                                 "; it must be > 0 when given (absent = infinite)";
    }
}

// tinygltf hands &buffer.data[view.byteOffset] for images in bufferViews to the image
// callback without a bounds check: verify the chain first.
void Loader::checkImageBufferViews(const nlohmann::json& images, const nlohmann::json* views,
                                   const nlohmann::json* buffers) {
    for (size_t i = 0; i < images.size(); ++i) {
        const auto& img = images[i];
        if (!img.is_object()) continue;  // tinygltf rejects it
        auto bvIt = img.find("bufferView");
        if (bvIt == img.end()) continue;
        const std::string what = "image " + str(i);
        if (!bvIt->is_number_unsigned() || !views || bvIt->get<uint64_t>() >= views->size())
            fail(what + ": bufferView does not exist");
        const auto& view = (*views)[bvIt->get<size_t>()];
        uint64_t buffer = 0, offset = 0, length = 0, bufLen = 0;
        if (!view.is_object() || !asUnsigned(view, "buffer", buffer, true) ||
            !asUnsigned(view, "byteOffset", offset, false) ||
            !asUnsigned(view, "byteLength", length, true))
            fail(what + ": bufferView " + str(bvIt->get<uint64_t>()) + " is malformed");
        if (!buffers || buffer >= buffers->size() || !(*buffers)[buffer].is_object() ||
            !asUnsigned((*buffers)[buffer], "byteLength", bufLen, true))
            fail(what + ": bufferView " + str(bvIt->get<uint64_t>()) +
                 " refers to a missing or malformed buffer");
        if (offset > bufLen || length > bufLen - offset)
            fail(what + ": bufferView " + str(bvIt->get<uint64_t>()) +
                 " lies outside buffer " + str(buffer) + " (needs " + str(offset) + "+" +
                 str(length) + " bytes, has " + str(bufLen) + ")");
    }
}

void Loader::prevalidate(const char* json, size_t len, bool binary) {
    const nlohmann::json doc = parseJsonObject(json, len);
    const nlohmann::json* buffers = jsonArray(doc, "buffers");
    const nlohmann::json* views = jsonArray(doc, "bufferViews");
    const nlohmann::json* images = jsonArray(doc, "images");

    // What tinygltf reports badly: "JSON string too short." for {}, "File not found :" with no
    // name for a buffer without uri, "File not found" for data: URIs it cannot decode and for
    // http:// URIs, "Failed to decode 'uri'" plus the whole URI for a byteLength mismatch, and
    // nothing at all for a skin without joints. Each gets a message naming the element here.
    checkAsset(doc);
    if (buffers) checkBufferUris(*buffers, binary);
    checkRequiredProperties(doc, buffers, views, images);
    if (const nlohmann::json* skins = jsonArray(doc, "skins")) checkSkinJoints(*skins);
    if (binary && buffers) checkBinChunkBuffers(*buffers);

    // Values tinygltf reads as "absent" although the spec forbids them: without a look at the
    // JSON a byteStride of -12 becomes tightly packed data, and a range or aspectRatio of 0 the
    // same as none given (infinite range, the viewport's aspect).
    if (views) checkByteStrides(*views);
    if (const nlohmann::json* cameras = jsonArray(doc, "cameras")) noteBadCameras(*cameras);
    checkLights(doc);

    if (images) checkImageBufferViews(*images, views, buffers);
}

// Walks a .glb's chunks, checking every bound: the first must be JSON, a BIN chunk may follow.
Loader::GlbChunks Loader::readGlbChunks(const uint8_t* data, size_t size) {
    if (size < 12) fail("binary glTF header is truncated (" + str(size) + " bytes)");
    const uint32_t version = readU32(data + 4);
    if (version != 2)
        fail("binary glTF version " + str(version) + " is not supported (only glTF 2.0)");
    const uint64_t length = readU32(data + 8);
    if (length > size)
        fail("binary glTF is truncated (header says " + str(length) + " bytes, got " +
             str(size) + ")");
    if (length < size) warn("binary glTF: " + str(size - length) + " trailing bytes ignored");
    GlbChunks chunks;
    uint64_t off = 12;
    int chunk = 0;
    while (off < length) {
        if (length - off < 8)
            fail("binary glTF chunk " + std::to_string(chunk) + " header at byte " + str(off) +
                 " is truncated");
        const uint64_t clen = readU32(data + off);
        const uint32_t ctype = readU32(data + off + 4);
        if (clen > length - off - 8)
            fail("binary glTF chunk " + std::to_string(chunk) + " (" + str(clen) +
                 " bytes at byte " + str(off) + ") runs past the end of the file (" +
                 str(length) + " bytes)");
        if (chunk == 0) {
            if (ctype != kChunkJson) fail("binary glTF: the first chunk is not JSON");
            chunks.json = reinterpret_cast<const char*>(data + off + 8);
            chunks.jsonLen = static_cast<size_t>(clen);
        } else if (chunk == 1 && ctype == kChunkBin) {
            chunks.bin = data + off + 8;
            chunks.binLen = clen;
            chunks.haveBin = true;
        } else {
            warn("binary glTF: unknown chunk type ignored");
        }
        off += 8 + clen;
        ++chunk;
    }
    if (!chunks.json) fail("binary glTF has no JSON chunk");
    return chunks;
}

// Canonical container: header, JSON chunk (space padded), BIN chunk (zero padded,
// omitted when empty) - the layout tinygltf's own chunk checks accept.
std::vector<uint8_t> Loader::canonicalGlb(const GlbChunks& chunks) {
    const uint64_t jsonPadded = (chunks.jsonLen + 3) & ~uint64_t(3);
    const uint64_t binPadded = (chunks.binLen + 3) & ~uint64_t(3);
    const bool writeBin = chunks.haveBin && chunks.binLen > 0;
    const uint64_t total = 12 + 8 + jsonPadded + (writeBin ? 8 + binPadded : 0);
    if (total > kMaxInputBytes) fail("binary glTF is too large");
    std::vector<uint8_t> glb;
    glb.reserve(static_cast<size_t>(total));
    writeU32(glb, kGlbMagic);
    writeU32(glb, 2);
    writeU32(glb, static_cast<uint32_t>(total));
    writeU32(glb, static_cast<uint32_t>(jsonPadded));
    writeU32(glb, kChunkJson);
    glb.insert(glb.end(), chunks.json, chunks.json + chunks.jsonLen);
    glb.resize(glb.size() + static_cast<size_t>(jsonPadded - chunks.jsonLen), ' ');
    if (writeBin) {
        writeU32(glb, static_cast<uint32_t>(binPadded));
        writeU32(glb, kChunkBin);
        glb.insert(glb.end(), chunks.bin, chunks.bin + chunks.binLen);
        glb.resize(glb.size() + static_cast<size_t>(binPadded - chunks.binLen), 0);
    }
    return glb;
}

// tinygltf reads the checked input into model_, with our file and image callbacks; its
// errors and warnings become ours.
void Loader::parseModel(bool binary, const std::vector<uint8_t>& glb, const char* json, size_t jsonLen,
                        const std::string& baseDir) {
    tinygltf::TinyGLTF parser;
    FsState fsState;
    fsState.baseDir = baseDir;
    tinygltf::FsCallbacks fs;
    fs.FileExists = &fsFileExists;
    fs.ExpandFilePath = &fsExpandFilePath;
    fs.ReadWholeFile = &fsReadWholeFile;
    fs.WriteWholeFile = &fsWriteWholeFile;
    fs.user_data = &fsState;
    parser.SetFsCallbacks(fs);
    parser.SetImageLoader(&keepImageBytes, nullptr);
    std::string err, twarn;
    bool ok = false;
    try {
        if (binary)
            ok = parser.LoadBinaryFromMemory(&model_, &err, &twarn, glb.data(),
                                             static_cast<unsigned int>(glb.size()), baseDir);
        else
            ok = parser.LoadASCIIFromString(&model_, &err, &twarn, json,
                                            static_cast<unsigned int>(jsonLen), baseDir);
    } catch (const std::bad_alloc&) {
        fail("out of memory while parsing");
    } catch (const std::exception& e) {
        fail(std::string("invalid glTF: ") + e.what());
    }
    if (!ok)
        fail("invalid glTF: " + (err.empty() ? std::string("tinygltf rejected it without a reason (a required "
                                                            "property may be missing or of the wrong type)")
                                             : tinygltfReason(err)));
    for (const std::string* text : {&err, &twarn}) {
        size_t start = 0;
        while (start < text->size()) {
            size_t end = text->find('\n', start);
            if (end == std::string::npos) end = text->size();
            const std::string line = oneLine(text->substr(start, end - start));
            if (!line.empty()) warn("glTF: " + line);
            start = end + 1;
        }
    }
}

Scene Loader::load(const uint8_t* data, size_t size, const std::string& baseDir) {
    baseDir_ = baseDir;
    if (!data && size) fail("no data");
    if (size > kMaxInputBytes) fail("file is too large (" + str(size) + " bytes)");
    if (size == 0) fail("file is empty");

    const bool binary = size >= 4 && readU32(data) == kGlbMagic;
    std::vector<uint8_t> glb;  // canonical copy of a binary glTF
    const char* json = nullptr;
    size_t jsonLen = 0;
    if (binary) {
        const GlbChunks chunks = readGlbChunks(data, size);
        json = chunks.json;
        jsonLen = chunks.jsonLen;
        prevalidate(json, jsonLen, true);
        glb = canonicalGlb(chunks);
    } else {
        json = reinterpret_cast<const char*>(data);
        jsonLen = size;
        prevalidate(json, jsonLen, false);
    }
    parseModel(binary, glb, json, jsonLen, baseDir);

    checkExtensions();
    if (!model_.animations.empty())
        warn("animations are not supported (ignored; the scene is shown at rest)");
    if (!model_.skins.empty()) warn("skins are not supported (ignored; meshes shown in bind pose)");

    imageIndex_.assign(model_.images.size(), -2);  // -2: not decoded yet
    convertMaterials();
    buildNodes();

    try {
        finalizeScene(scene_);
    } catch (const Error& e) {
        fail(e.what());
    }
    checkCameraDepthRange();
    return std::move(scene_);
}

void Loader::checkCameraDepthRange() {
    for (size_t i = 0; i < scene_.cameras.size(); ++i) {
        const Camera& cam = scene_.cameras[i];
        if (cam.orthographic) continue;  // linear depth: znear does not cost precision
        const std::string what = "camera " + str(i) + quoted(cam.name);
        try {
            const std::string warning =
                checkCameraDepth(scene_.bounds, glm::vec3(cam.cameraToWorld[3]), cam.znear, what);
            if (!warning.empty()) warn(warning);
        } catch (const Error& e) {
            fail(e.what());
        }
    }
}

void Loader::checkExtensions() {
    for (const std::string& e : model_.extensionsRequired) {
        if (kSupportedExtensions.count(e)) continue;
        if (!ignorableExtension(e))
            fail("requires extension " + oneLine(e, 80) + ", which is not supported");
        warn("required extension " + e + " is not supported (ignored; rendering is approximate)");
    }
    for (const std::string& e : model_.extensionsUsed) {
        if (kSupportedExtensions.count(e)) continue;
        if (std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), e) !=
                model_.extensionsRequired.end() &&
            e != "KHR_texture_transform")
            continue;  // already reported as a required extension
        if (e == "KHR_texture_transform")
            warn("KHR_texture_transform is not supported (texture transforms ignored)");
        else
            warn("extension " + e + " is not supported (ignored)");
    }
}

// --- Accessors ------------------------------------------------------------------------------
int componentSize(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        case TINYGLTF_TYPE_VEC4: return "VEC4";
        case TINYGLTF_TYPE_MAT2: return "MAT2";
        case TINYGLTF_TYPE_MAT3: return "MAT3";
        case TINYGLTF_TYPE_MAT4: return "MAT4";
        default: return "invalid";
    }
}

// One component as float (normalised integers mapped to [0,1] / [-1,1]).
float decodeComponent(const uint8_t* p, int type, bool normalized) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const int8_t v = static_cast<int8_t>(p[0]);
            return normalized ? std::max(v / 127.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : float(p[0]);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0f : float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return float(v);
        }
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default: return 0.0f;
    }
}

uint32_t decodeIndex(const uint8_t* p, int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        default: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

// Checks a bufferView against its buffer; returns it and sets *base to its first byte.
const tinygltf::BufferView& Loader::checkedBufferView(int bv, const std::string& what,
                                                      const uint8_t** base) {
    if (bv < 0 || static_cast<size_t>(bv) >= model_.bufferViews.size())
        fail(what + " refers to bufferView " + std::to_string(bv) + ", which does not exist (" +
             str(model_.bufferViews.size()) + " bufferViews)");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(bv)];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model_.buffers.size())
        fail("bufferView " + std::to_string(bv) + " refers to buffer " +
             std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        fail("bufferView " + std::to_string(bv) + " reads past the end of buffer " +
             std::to_string(view.buffer) + " (needs " + str(uint64_t(view.byteOffset)) + "+" +
             str(uint64_t(view.byteLength)) + " bytes, has " + str(data.size()) + ")");
    *base = data.data() + view.byteOffset;
    return view;
}

std::vector<uint8_t> Loader::bufferViewBytes(int bv, const std::string& what) {
    const uint8_t* base = nullptr;
    const tinygltf::BufferView& view = checkedBufferView(bv, what, &base);
    return std::vector<uint8_t>(base, base + view.byteLength);
}

// Where an accessor's elements lie, checked against its bufferView: nullptr for an accessor
// without one (read as zeros).
Loader::AccessorSource Loader::accessorSource(const tinygltf::Accessor& acc, const std::string& name,
                                              uint64_t count, uint64_t elemSize) {
    AccessorSource source;
    source.stride = elemSize;
    if (acc.bufferView >= 0) {
        const tinygltf::BufferView& view = checkedBufferView(acc.bufferView, name, &source.first);
        if (view.byteStride != 0) {
            if (view.byteStride < elemSize)
                fail(name + ": byteStride " + str(uint64_t(view.byteStride)) +
                     " of bufferView " + std::to_string(acc.bufferView) +
                     " is smaller than an element (" + str(elemSize) + " bytes)");
            source.stride = view.byteStride;
        }
        const uint64_t off = acc.byteOffset;
        if (off > view.byteLength)
            fail(name + ": byteOffset " + str(off) + " lies past the end of bufferView " +
                 std::to_string(acc.bufferView) + " (" + str(uint64_t(view.byteLength)) + " bytes)");
        // off <= byteLength <= buffer size (< 2^32), stride <= 2^32, count <= 2^28: no overflow.
        const uint64_t needed = off + source.stride * (count - 1) + elemSize;
        if (needed > view.byteLength) {
            const uint64_t bufferNeeds = uint64_t(view.byteOffset) + needed;
            fail(name + " reads past the end of bufferView " + std::to_string(acc.bufferView) +
                 " (needs " + str(needed) + " bytes, has " + str(uint64_t(view.byteLength)) +
                 "; buffer " + std::to_string(view.buffer) + " would need " + str(bufferNeeds) +
                 ")");
        }
        source.first += off;
    } else {
        // Allowed by the spec (zeros, usually the base of a sparse accessor). Its size is not
        // backed by any buffer, so bound it by the data the file actually has.
        uint64_t bufferBytes = 0;
        for (const auto& b : model_.buffers) bufferBytes += b.data.size();
        if (count > std::max<uint64_t>(65536, bufferBytes))
            fail(name + " has no bufferView and " + str(count) +
                 " elements, more than the file's buffers could describe");
        if (!acc.sparse.isSparse) warn("an accessor without bufferView is read as zeros");
    }
    return source;
}

// A sparse accessor's index and value arrays, checked against their bufferViews.
Loader::SparseSource Loader::sparseSource(const tinygltf::Accessor& acc, const std::string& name,
                                          uint64_t count, uint64_t elemSize) {
    SparseSource sparse;
    sparse.count = acc.sparse.count;
    if (sparse.count < 1 || uint64_t(sparse.count) > count)
        fail(name + ": sparse count " + std::to_string(sparse.count) + " is invalid (accessor has " +
             str(count) + " elements)");
    sparse.indexType = acc.sparse.indices.componentType;
    const int itype = sparse.indexType;
    sparse.indexSize = (itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                        itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                        itype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                           ? componentSize(itype)
                           : 0;
    if (sparse.indexSize == 0) fail(name + ": sparse indices have invalid componentType " + std::to_string(itype));
    if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
        fail(name + ": sparse byteOffset is negative");
    const auto& iview = checkedBufferView(acc.sparse.indices.bufferView, name + " sparse indices", &sparse.indices);
    const auto& vview = checkedBufferView(acc.sparse.values.bufferView, name + " sparse values", &sparse.values);
    const uint64_t ineed = uint64_t(acc.sparse.indices.byteOffset) + uint64_t(sparse.count) * sparse.indexSize;
    const uint64_t vneed = uint64_t(acc.sparse.values.byteOffset) + uint64_t(sparse.count) * elemSize;
    if (ineed > iview.byteLength)
        fail(name + ": sparse indices read past the end of bufferView " +
             std::to_string(acc.sparse.indices.bufferView) + " (needs " + str(ineed) +
             " bytes, has " + str(uint64_t(iview.byteLength)) + ")");
    if (vneed > vview.byteLength)
        fail(name + ": sparse values read past the end of bufferView " +
             std::to_string(acc.sparse.values.bufferView) + " (needs " + str(vneed) +
             " bytes, has " + str(uint64_t(vview.byteLength)) + ")");
    sparse.indices += acc.sparse.indices.byteOffset;
    sparse.values += acc.sparse.values.byteOffset;
    return sparse;
}

void Loader::readAccessor(int index, const std::string& what, bool asIndices, AccessorData& out) {
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
        fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist (" +
             str(model_.accessors.size()) + " accessors)");
    const tinygltf::Accessor& acc = model_.accessors[size_t(index)];
    const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    const int csize = componentSize(acc.componentType);
    const int ncomp = componentCount(acc.type);
    if (csize == 0) fail(name + " has invalid componentType " + std::to_string(acc.componentType));
    if (ncomp == 0 || ncomp > 4) fail(name + " has unsupported type " + typeName(acc.type));
    if (acc.count == 0) fail(name + " has count 0");
    if (acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                           acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail(name + " is normalized but its components are not 8/16-bit integers");
    const uint64_t count = acc.count;
    const uint64_t elemSize = uint64_t(csize) * uint64_t(ncomp);
    // Count against what the buffers can hold (every element needs at least one byte of some
    // buffer unless the accessor has no bufferView, which is all zeros - still capped).
    const uint64_t limit = asIndices ? kMaxTotalIndices : kMaxTotalVertices;
    if (count > limit) fail(name + " has too many elements (" + str(count) + ")");

    if (asIndices) {
        if (acc.type != TINYGLTF_TYPE_SCALAR ||
            (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
            acc.normalized)
            fail(name + " must be SCALAR unsigned byte/short/int to hold indices");
    }

    const AccessorSource source = accessorSource(acc, name, count, elemSize);
    const size_t n = static_cast<size_t>(count);
    if (asIndices)
        out.indices.assign(n, 0u);
    else
        out.values.assign(n, glm::vec4(0.0f));
    auto store = [&](size_t i, const uint8_t* p) {
        if (asIndices) {
            out.indices[i] = decodeIndex(p, acc.componentType);
        } else {
            glm::vec4 v(0.0f);
            for (int c = 0; c < ncomp; ++c)
                v[c] = decodeComponent(p + c * csize, acc.componentType, acc.normalized);
            out.values[i] = v;
        }
    };
    if (source.first)
        for (size_t i = 0; i < n; ++i) store(i, source.first + i * source.stride);

    if (acc.sparse.isSparse) {
        const SparseSource sparse = sparseSource(acc, name, count, elemSize);
        for (int k = 0; k < sparse.count; ++k) {
            const uint32_t target = decodeIndex(sparse.indices + size_t(k) * sparse.indexSize, sparse.indexType);
            if (target >= count)
                fail(name + ": sparse index " + str(target) + " is out of range (" + str(count) +
                     " elements)");
            store(target, sparse.values + size_t(k) * elemSize);
        }
    }
}

// --- Materials and images ---------------------------------------------------------------------
bool looksLikePng(const std::vector<uint8_t>& b) {
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    return b.size() >= 8 && std::memcmp(b.data(), sig, 8) == 0;
}
bool looksLikeJpeg(const std::vector<uint8_t>& b) {
    return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

int Loader::decodeImage(int imageIndex) {
    int& slot = imageIndex_[size_t(imageIndex)];
    if (slot != -2) return slot;
    slot = -1;
    const tinygltf::Image& src = model_.images[size_t(imageIndex)];
    const std::string what = "image " + std::to_string(imageIndex) +
                             quoted(src.name.empty() ? (src.uri.size() < 200 ? src.uri : "") : src.name);
    std::vector<uint8_t> bytes;
    if (src.bufferView >= 0)
        bytes = bufferViewBytes(src.bufferView, what);
    else
        bytes = src.image;
    if (bytes.empty()) {
        warn(what + " could not be loaded; textures using it are ignored");
        return slot;
    }
    if (!looksLikePng(bytes) && !looksLikeJpeg(bytes)) {
        warn(what + " is not PNG or JPEG; textures using it are ignored");
        return slot;
    }
    if (bytes.size() > size_t(INT_MAX)) {
        warn(what + " is too large; textures using it are ignored");
        return slot;
    }
    const int len = static_cast<int>(bytes.size());
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &comp) || w <= 0 || h <= 0) {
        warn(what + " cannot be decoded (" + std::string(stbi_failure_reason() ? stbi_failure_reason() : "?") +
             "); textures using it are ignored");
        return slot;
    }
    const uint64_t pixels = uint64_t(w) * uint64_t(h);
    if (pixels > kMaxImagePixels) {
        warn(what + " is too large (" + std::to_string(w) + "x" + std::to_string(h) + ", limit " +
             str(kMaxImagePixels) + " pixels per image); textures using it are ignored");
        return slot;
    }
    if (totalPixels_ + pixels > kMaxTotalImagePixels) {  // the image alone would fit: say what ran out
        warn(what + " (" + std::to_string(w) + "x" + std::to_string(h) + ") exceeds the scene's image budget (" +
             str(totalPixels_) + " of " + str(kMaxTotalImagePixels) +
             " pixels already used); textures using it are ignored");
        return slot;
    }
    Image out;
    out.name = src.name.empty() ? src.uri.substr(0, 200) : src.name;
    int dw = 0, dh = 0, dc = 0;
    if (stbi_is_16_bit_from_memory(bytes.data(), len)) {
        stbi_us* px = stbi_load_16_from_memory(bytes.data(), len, &dw, &dh, &dc, 4);
        if (px && dw == w && dh == h) {
            out.rgba8.resize(size_t(pixels) * 4);
            for (size_t i = 0; i < out.rgba8.size(); ++i)
                out.rgba8[i] = static_cast<uint8_t>((uint32_t(px[i]) * 255u + 32767u) / 65535u);
        }
        stbi_image_free(px);
    } else {
        stbi_uc* px = stbi_load_from_memory(bytes.data(), len, &dw, &dh, &dc, 4);
        if (px && dw == w && dh == h) out.rgba8.assign(px, px + size_t(pixels) * 4);
        stbi_image_free(px);
    }
    if (out.rgba8.empty()) {
        warn(what + " cannot be decoded (" + std::string(stbi_failure_reason() ? stbi_failure_reason() : "?") +
             "); textures using it are ignored");
        return slot;
    }
    out.width = w;
    out.height = h;
    totalPixels_ += pixels;
    scene_.images.push_back(std::move(out));
    slot = static_cast<int>(scene_.images.size()) - 1;
    return slot;
}

int Loader::textureImage(int textureIndex, int texCoord, const tinygltf::ExtensionMap& ext,
                         const std::string& where, bool srgb) {
    if (textureIndex < 0) return -1;
    if (static_cast<size_t>(textureIndex) >= model_.textures.size())
        fail(where + " refers to texture " + std::to_string(textureIndex) +
             ", which does not exist (" + str(model_.textures.size()) + " textures)");
    if (texCoord != 0)
        warn("textures using TEXCOORD_1 or higher are not supported (they use TEXCOORD_0)");
    if (ext.count("KHR_texture_transform"))
        warn("KHR_texture_transform is not supported (texture transforms ignored)");
    const tinygltf::Texture& tex = model_.textures[size_t(textureIndex)];
    if (tex.source < 0) {
        warn("texture " + std::to_string(textureIndex) +
             " has no PNG/JPEG source (e.g. KHR_texture_basisu, EXT_texture_webp); ignored");
        return -1;
    }
    if (static_cast<size_t>(tex.source) >= model_.images.size())
        fail("texture " + std::to_string(textureIndex) + " refers to image " +
             std::to_string(tex.source) + ", which does not exist (" + str(model_.images.size()) +
             " images)");
    const int img = decodeImage(tex.source);
    if (img >= 0 && srgb) scene_.images[size_t(img)].srgb = true;
    return img;
}

bool finiteNumber(double v) { return std::isfinite(v); }

// emissiveFactor x KHR_materials_emissive_strength, checked against what the renderer takes.
glm::vec3 Loader::emittedRadiance(const tinygltf::Material& src, const std::string& where) {
    glm::vec3 emissive(0.0f);
    if (!src.emissiveFactor.empty()) {
        if (src.emissiveFactor.size() != 3) fail(where + ": emissiveFactor must have 3 numbers");
        for (int c = 0; c < 3; ++c) {
            const double f = src.emissiveFactor[size_t(c)];
            if (!finiteNumber(f)) fail(where + ": emissiveFactor is not finite");
            // The spec's range is [0, 1] (a brighter emitter uses KHR_materials_emissive_strength);
            // a negative factor emitted negative radiance. Above 1 is taken as many files do, up to
            // the radiance limit below.
            if (f < 0.0) fail(where + ": emissiveFactor " + num(f) + " is outside [0, 1]");
            emissive[c] = static_cast<float>(f);
        }
    }
    float strength = 1.0f;
    auto es = src.extensions.find("KHR_materials_emissive_strength");
    if (es != src.extensions.end() && es->second.IsObject() && es->second.Has("emissiveStrength")) {
        const tinygltf::Value& v = es->second.Get("emissiveStrength");
        if (!v.IsNumber() || !finiteNumber(v.GetNumberAsDouble()) || v.GetNumberAsDouble() < 0.0)
            fail(where + ": emissiveStrength must be a non-negative number");
        strength = static_cast<float>(v.GetNumberAsDouble());
    }
    // In double: the product of two floats' worth of numbers must not overflow before the check.
    const double radiance = double(std::max({emissive.x, emissive.y, emissive.z})) * double(strength);
    if (radiance > double(kMaxRadiance))
        fail(where + ": emissive radiance " + num(radiance) + " (emissiveFactor x emissiveStrength) is more than the " +
             num(double(kMaxRadiance)) + " the renderer takes");
    return emissive * strength;
}

void Loader::convertMaterials() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& src = model_.materials[i];
        const std::string where = "material " + str(i) + quoted(src.name);
        Material m;
        m.name = src.name;
        const auto& pbr = src.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() != 4)
            fail(where + ": baseColorFactor must have 4 numbers");
        for (int c = 0; c < 4; ++c) {
            if (!finiteNumber(pbr.baseColorFactor[size_t(c)])) fail(where + ": baseColorFactor is not finite");
            m.baseColorFactor[c] = static_cast<float>(pbr.baseColorFactor[size_t(c)]);
        }
        if (!finiteNumber(pbr.metallicFactor) || !finiteNumber(pbr.roughnessFactor))
            fail(where + ": metallic/roughness factor is not finite");
        m.metallicFactor = static_cast<float>(pbr.metallicFactor);
        m.roughnessFactor = static_cast<float>(pbr.roughnessFactor);

        m.emissive = emittedRadiance(src, where);

        auto sp = src.extensions.find("KHR_materials_specular");
        if (sp != src.extensions.end() && sp->second.IsObject() && sp->second.Has("specularFactor")) {
            const tinygltf::Value& v = sp->second.Get("specularFactor");
            if (!v.IsNumber() || !finiteNumber(v.GetNumberAsDouble()))
                fail(where + ": specularFactor must be a number");
            m.specularFactor = static_cast<float>(v.GetNumberAsDouble());
        }

        if (!finiteNumber(src.normalTexture.scale) || !finiteNumber(src.occlusionTexture.strength) ||
            !finiteNumber(src.alphaCutoff))
            fail(where + ": normal scale, occlusion strength or alphaCutoff is not finite");
        m.normalScale = static_cast<float>(src.normalTexture.scale);
        m.occlusionStrength = static_cast<float>(src.occlusionTexture.strength);
        m.alphaCutoff = static_cast<float>(src.alphaCutoff);
        if (src.alphaMode == "OPAQUE" || src.alphaMode.empty()) {
            m.alphaMode = AlphaMode::Opaque;
        } else if (src.alphaMode == "MASK") {
            m.alphaMode = AlphaMode::Mask;
        } else if (src.alphaMode == "BLEND") {
            m.alphaMode = AlphaMode::Blend;
            warn("alphaMode BLEND is not supported (such materials are rendered opaque)");
        } else {
            fail(where + ": unknown alphaMode '" + oneLine(src.alphaMode, 40) + "'");
        }
        m.doubleSided = src.doubleSided;

        m.baseColorTexture = textureImage(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                          pbr.baseColorTexture.extensions, where + " baseColorTexture", true);
        m.metallicRoughnessTexture =
            textureImage(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                         pbr.metallicRoughnessTexture.extensions, where + " metallicRoughnessTexture", false);
        m.normalTexture = textureImage(src.normalTexture.index, src.normalTexture.texCoord,
                                       src.normalTexture.extensions, where + " normalTexture", false);
        m.emissiveTexture = textureImage(src.emissiveTexture.index, src.emissiveTexture.texCoord,
                                         src.emissiveTexture.extensions, where + " emissiveTexture", true);
        m.occlusionTexture = textureImage(src.occlusionTexture.index, src.occlusionTexture.texCoord,
                                          src.occlusionTexture.extensions, where + " occlusionTexture", false);
        scene_.materials.push_back(std::move(m));
    }
}

// --- Meshes -----------------------------------------------------------------------------------
const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "invalid";
    }
}

// The accessor of a primitive's attribute, -1 when it has none.
int attributeAccessor(const tinygltf::Primitive& src, const char* name) {
    auto it = src.attributes.find(name);
    return it == src.attributes.end() ? -1 : it->second;
}

// POSITION into p's vertices, one vertex each; their normals and tangents are missing until read.
void Loader::readPositions(const tinygltf::Primitive& src, const std::string& where, Primitive& p) {
    const int posAcc = attributeAccessor(src, "POSITION");
    if (posAcc < 0) fail(where + " has no POSITION attribute");
    AccessorData data;
    readAccessor(posAcc, where + " POSITION", false, data);
    if (model_.accessors[size_t(posAcc)].type != TINYGLTF_TYPE_VEC3)
        fail(where + ": POSITION accessor " + std::to_string(posAcc) + " is not VEC3");
    const size_t nv = data.values.size();
    if (totalVertices_ + nv > kMaxTotalVertices) fail("scene has too many vertices");
    totalVertices_ += nv;
    p.vertices.resize(nv);
    for (size_t i = 0; i < nv; ++i) {
        const glm::vec3 v(data.values[i]);
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            fail(where + ": POSITION accessor " + std::to_string(posAcc) + " element " + str(i) +
                 " is not finite (NaN or Inf)");
        p.vertices[i].position = v;
        p.vertices[i].normal = glm::vec3(0.0f);   // missing until read
        p.vertices[i].tangent = glm::vec4(0.0f);  // missing until read
    }
}

// NORMAL, TANGENT, TEXCOORD_0/1 and COLOR_0 into p's vertices (their POSITIONs already read).
void Loader::readVertexAttributes(const tinygltf::Primitive& src, const std::string& where, Primitive& p) {
    const size_t nv = p.vertices.size();
    AccessorData data;
    auto readAttr = [&](const char* name, std::initializer_list<int> types, bool needNormalizedInts) -> bool {
        const int a = attributeAccessor(src, name);
        if (a < 0) return false;
        readAccessor(a, where + " " + name, false, data);
        const tinygltf::Accessor& acc = model_.accessors[size_t(a)];
        if (std::find(types.begin(), types.end(), acc.type) == types.end())
            fail(where + ": " + name + " accessor " + std::to_string(a) + " has type " + typeName(acc.type));
        if (needNormalizedInts && acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
            (!acc.normalized || (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                 acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)))
            fail(where + ": " + name + " accessor " + std::to_string(a) +
                 " must be float or normalized unsigned byte/short");
        if (data.values.size() != nv)
            fail(where + ": " + name + " accessor " + std::to_string(a) + " has " +
                 str(data.values.size()) + " elements but POSITION has " + str(nv));
        return true;
    };
    if (readAttr("NORMAL", {TINYGLTF_TYPE_VEC3}, false))
        for (size_t i = 0; i < nv; ++i) p.vertices[i].normal = glm::vec3(data.values[i]);
    if (readAttr("TANGENT", {TINYGLTF_TYPE_VEC4}, false))
        for (size_t i = 0; i < nv; ++i) p.vertices[i].tangent = data.values[i];
    if (readAttr("TEXCOORD_0", {TINYGLTF_TYPE_VEC2}, true))
        for (size_t i = 0; i < nv; ++i) {
            glm::vec2 uv(data.values[i]);
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
            p.vertices[i].uv = uv;
        }
    // Kept raw: the lightmap's chart check rejects non-finite values with its reason, where a
    // silent 0 (as TEXCOORD_0 gets) would pass as a collapsed chart.
    if (readAttr("TEXCOORD_1", {TINYGLTF_TYPE_VEC2}, true)) {
        p.uv1.resize(nv);
        for (size_t i = 0; i < nv; ++i) p.uv1[i] = glm::vec2(data.values[i]);
    }
    if (readAttr("COLOR_0", {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, true)) {
        const bool rgb = model_.accessors[size_t(attributeAccessor(src, "COLOR_0"))].type == TINYGLTF_TYPE_VEC3;
        for (size_t i = 0; i < nv; ++i) {
            glm::vec4 c = data.values[i];
            if (rgb) c.w = 1.0f;
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(c[k])) c[k] = 1.0f;
            p.vertices[i].color = c;
        }
    }
}

// Indices (or 0..n-1), then strips and fans into lists.
std::vector<uint32_t> Loader::triangleList(const tinygltf::Primitive& src, int mode, const std::string& where,
                                           size_t nv) {
    std::vector<uint32_t> idx;
    if (src.indices >= 0) {
        AccessorData data;
        readAccessor(src.indices, where + " indices", true, data);
        idx = std::move(data.indices);
    } else {
        idx.resize(nv);
        for (size_t i = 0; i < nv; ++i) idx[i] = static_cast<uint32_t>(i);
    }
    for (size_t i = 0; i < idx.size(); ++i)
        if (idx[i] >= nv)
            fail(where + ": index " + str(idx[i]) + " at position " + str(i) +
                 " is out of range (" + str(nv) + " vertices)");
    std::vector<uint32_t> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (idx.size() % 3 != 0) {
            warn(std::string("a TRIANGLES primitive has an index count that is not a multiple of 3 "
                             "(extra indices ignored)"));
            idx.resize(idx.size() - idx.size() % 3);
        }
        triangles = std::move(idx);
    } else if (idx.size() >= 3) {
        const size_t tris = idx.size() - 2;
        triangles.reserve(tris * 3);
        for (size_t i = 0; i < tris; ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                // glTF: triangle i = {v_i, v_{i+1+i%2}, v_{i+2-i%2}} keeps the winding.
                triangles.insert(triangles.end(),
                                 {idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]});
            } else {
                // glTF: triangle i = {v_{i+1}, v_{i+2}, v_0}.
                triangles.insert(triangles.end(), {idx[i + 1], idx[i + 2], idx[0]});
            }
        }
    }
    return triangles;
}

Primitive Loader::convertPrimitive(int meshIndex, int primIndex, const std::string& where) {
    const tinygltf::Primitive& src = model_.meshes[size_t(meshIndex)].primitives[size_t(primIndex)];
    const int mode = src.mode < 0 ? TINYGLTF_MODE_TRIANGLES : src.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
        fail(where + ": mode " + std::to_string(mode) + " (" + modeName(mode) +
             ") is not supported; only triangles, strips and fans are");
    if (!src.targets.empty()) warn("morph targets are not supported (ignored; base mesh shown)");
    if (src.material < -1 || (src.material >= 0 && static_cast<size_t>(src.material) >= model_.materials.size()))
        fail(where + " refers to material " + std::to_string(src.material) +
             ", which does not exist (" + str(model_.materials.size()) + " materials)");

    Primitive p;
    p.material = src.material;
    readPositions(src, where, p);
    readVertexAttributes(src, where, p);

    p.indices = triangleList(src, mode, where, p.vertices.size());
    if (totalIndices_ + p.indices.size() > kMaxTotalIndices) fail("scene has too many indices");
    totalIndices_ += p.indices.size();
    return p;
}

int Loader::primitiveFor(int mesh, int prim) {
    auto it = primitiveIndex_.find({mesh, prim});
    if (it != primitiveIndex_.end()) return it->second;
    const tinygltf::Mesh& m = model_.meshes[size_t(mesh)];
    const std::string where = "mesh " + std::to_string(mesh) + quoted(m.name) + " primitive " +
                              std::to_string(prim);
    Primitive p = convertPrimitive(mesh, prim, where);
    int index = -1;
    if (p.indices.empty()) {
        warn(where + " has no triangles (skipped)");
    } else {
        scene_.primitives.push_back(std::move(p));
        index = static_cast<int>(scene_.primitives.size()) - 1;
    }
    primitiveIndex_[{mesh, prim}] = index;
    return index;
}

// --- Nodes, lights, cameras -------------------------------------------------------------------
glm::mat4 orthonormalFrame(const glm::mat4& world) {
    glm::vec3 z = glm::vec3(world[2]);
    glm::vec3 y = glm::vec3(world[1]);
    const float zl = glm::length(z);
    if (!(zl > 1e-12f) || !std::isfinite(zl)) return glm::translate(glm::mat4(1.0f), glm::vec3(world[3]));
    z /= zl;
    y -= z * glm::dot(z, y);
    float yl = glm::length(y);
    if (!(yl > 1e-12f) || !std::isfinite(yl)) {
        y = std::fabs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        y -= z * glm::dot(z, y);
        yl = glm::length(y);
    }
    y /= yl;
    const glm::vec3 x = glm::cross(y, z);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x, 0.0f);
    m[1] = glm::vec4(y, 0.0f);
    m[2] = glm::vec4(z, 0.0f);
    m[3] = glm::vec4(glm::vec3(world[3]), 1.0f);
    return m;
}

// The camera a node refers to, placed at the node (its frame made orthonormal).
Camera Loader::nodeCamera(int cameraIndex, const std::string& where, const glm::mat4& world) {
    if (cameraIndex < 0 || static_cast<size_t>(cameraIndex) >= model_.cameras.size())
        fail(where + " refers to camera " + std::to_string(cameraIndex) + ", which does not exist (" +
             str(model_.cameras.size()) + " cameras)");
    const tinygltf::Camera& src = model_.cameras[size_t(cameraIndex)];
    const std::string cw = "camera " + std::to_string(cameraIndex) + quoted(src.name);
    auto bad = badCameras_.find(cameraIndex);
    if (bad != badCameras_.end()) fail(bad->second);
    Camera cam;
    cam.name = src.name;
    cam.cameraToWorld = orthonormalFrame(world);
    if (src.type == "perspective") {
        const auto& p = src.perspective;
        if (!(p.yfov > 0.0 && p.yfov < 3.14159265358979) || !std::isfinite(p.yfov))
            fail(cw + ": yfov " + std::to_string(p.yfov) + " must be in (0, pi)");
        if (!(p.znear > 0.0) || !std::isfinite(p.znear)) fail(cw + ": znear must be > 0");
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && !(p.zfar > p.znear)))
            fail(cw + ": zfar must be greater than znear (or absent for infinite)");
        cam.orthographic = false;
        cam.yfov = static_cast<float>(p.yfov);
        cam.znear = static_cast<float>(p.znear);
        cam.zfar = static_cast<float>(p.zfar);
    } else if (src.type == "orthographic") {
        const auto& o = src.orthographic;
        if (!(o.xmag != 0.0) || !(o.ymag != 0.0) || !std::isfinite(o.xmag) || !std::isfinite(o.ymag))
            fail(cw + ": xmag and ymag must be non-zero");
        if (!(o.znear >= 0.0) || !(o.zfar > o.znear) || !std::isfinite(o.zfar))
            fail(cw + ": orthographic zfar must be greater than znear >= 0");
        cam.orthographic = true;
        cam.xmag = static_cast<float>(std::fabs(o.xmag));
        cam.ymag = static_cast<float>(std::fabs(o.ymag));
        cam.znear = static_cast<float>(o.znear);
        cam.zfar = static_cast<float>(o.zfar);
    } else {
        fail(cw + ": unknown camera type '" + oneLine(src.type, 40) + "'");
    }
    return cam;
}

// The light a node's KHR_lights_punctual extension refers to, placed and aimed by the node.
Light Loader::nodeLight(const tinygltf::Value& ext, const std::string& where, const glm::mat4& world) {
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
        fail(where + ": KHR_lights_punctual needs an integer 'light'");
    const int li = ext.Get("light").GetNumberAsInt();
    if (li < 0 || static_cast<size_t>(li) >= model_.lights.size())
        fail(where + " refers to light " + std::to_string(li) + ", which does not exist (" +
             str(model_.lights.size()) + " lights)");
    const tinygltf::Light& src = model_.lights[size_t(li)];
    const std::string lw = "light " + std::to_string(li) + quoted(src.name);
    auto bad = badLights_.find(li);
    if (bad != badLights_.end()) fail(bad->second);
    Light l;
    l.name = src.name;
    if (src.type == "directional")
        l.type = LightType::Directional;
    else if (src.type == "point")
        l.type = LightType::Point;
    else if (src.type == "spot")
        l.type = LightType::Spot;
    else
        fail(lw + ": unknown light type '" + oneLine(src.type, 40) + "'");
    if (!src.color.empty()) {
        if (src.color.size() != 3) fail(lw + ": color must have 3 numbers");
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(src.color[size_t(c)]) || src.color[size_t(c)] < 0.0)
                fail(lw + ": color must be finite and non-negative");
            l.color[c] = static_cast<float>(src.color[size_t(c)]);
        }
    }
    if (!std::isfinite(src.intensity) || src.intensity < 0.0 || src.intensity > 3.0e38)
        fail(lw + ": intensity must be a finite non-negative number");
    l.intensity = static_cast<float>(src.intensity);
    // The renderers use color x intensity in float: refuse a product that would be Inf.
    for (int c = 0; c < 3; ++c) {
        const double product = double(l.color[c]) * double(l.intensity);
        if (!(product <= double(std::numeric_limits<float>::max()))) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", product);
            fail(lw + ": color x intensity = " + text + " overflows a float (max 3.4e38)");
        }
    }
    if (!std::isfinite(src.range) || src.range < 0.0 || src.range > 3.0e38)
        fail(lw + ": range must be a finite positive number");
    l.range = static_cast<float>(src.range);
    if (l.type == LightType::Spot) {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0 || outer <= 0.0 ||
            inner > outer || outer > 1.5707963267948966 + 1e-6)
            fail(lw + ": cone angles must satisfy 0 <= inner <= outer <= pi/2");
        l.innerConeAngle = static_cast<float>(inner);
        l.outerConeAngle = static_cast<float>(outer);
    }
    l.position = glm::vec3(world[3]);
    glm::vec3 dir = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
    const float len = glm::length(dir);
    l.direction = (len > 1e-12f && std::isfinite(len)) ? dir / len : glm::vec3(0.0f, 0.0f, -1.0f);
    return l;
}

void Loader::addNodeContent(int n, const glm::mat4& world) {
    const tinygltf::Node& node = model_.nodes[size_t(n)];
    const std::string where = "node " + std::to_string(n) + quoted(node.name);
    if (node.skin >= 0) warn("skins are not supported (ignored; meshes shown in bind pose)");
    if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
            fail(where + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist (" +
                 str(model_.meshes.size()) + " meshes)");
        const size_t np = model_.meshes[size_t(node.mesh)].primitives.size();
        for (size_t p = 0; p < np; ++p) {
            const int prim = primitiveFor(node.mesh, static_cast<int>(p));
            if (prim >= 0) scene_.draws.push_back(DrawItem{prim, world});
        }
    } else if (node.mesh < -1) {
        fail(where + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
    }

    if (node.camera >= 0 || node.camera < -1) scene_.cameras.push_back(nodeCamera(node.camera, where, world));

    auto lp = node.extensions.find("KHR_lights_punctual");
    if (lp != node.extensions.end()) scene_.lights.push_back(nodeLight(lp->second, where, world));
}

// Each node's parent (-1 for a root), refusing children that do not exist, nodes with two
// parents and cycles.
std::vector<int> Loader::nodeParents() {
    const size_t n = model_.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (int c : model_.nodes[i].children) {
            if (c < 0 || static_cast<size_t>(c) >= n)
                fail("node " + str(i) + " has child " + std::to_string(c) + ", which does not exist (" +
                     str(n) + " nodes)");
            if (static_cast<size_t>(c) == i) fail("node graph has a cycle (node " + str(i) + " is its own child)");
            if (parent[size_t(c)] != -1)
                fail("node " + std::to_string(c) + " has more than one parent (nodes " +
                     std::to_string(parent[size_t(c)]) + " and " + str(i) + ")");
            parent[size_t(c)] = static_cast<int>(i);
        }
    }
    // With one parent per node, a cycle is a parent chain that comes back to itself.
    std::vector<char> state(n, 0);  // 0 unvisited, 1 on the current chain, 2 done
    std::vector<int> chain;
    for (size_t s = 0; s < n; ++s) {
        chain.clear();
        int v = static_cast<int>(s);
        while (v >= 0 && state[size_t(v)] == 0) {
            state[size_t(v)] = 1;
            chain.push_back(v);
            v = parent[size_t(v)];
        }
        if (v >= 0 && state[size_t(v)] == 1)
            fail("node graph has a cycle (through node " + std::to_string(v) + ")");
        for (int c : chain) state[size_t(c)] = 2;
    }
    return parent;
}

// The root nodes of the scene that is loaded (the default one, else the first), or every
// parentless node of a file without scenes.
std::vector<int> Loader::sceneRoots(const std::vector<int>& parent) {
    const size_t n = model_.nodes.size();
    std::vector<int> roots;
    if (model_.scenes.empty()) {
        if (model_.defaultScene >= 0)
            fail("'scene' is " + std::to_string(model_.defaultScene) + " but the file has no scenes");
        for (size_t i = 0; i < n; ++i)
            if (parent[i] < 0) roots.push_back(static_cast<int>(i));
    } else {
        int si = model_.defaultScene;
        if (si < -1 || si >= static_cast<int>(model_.scenes.size()))
            fail("'scene' is " + std::to_string(si) + " but the file has " +
                 str(model_.scenes.size()) + " scenes");
        if (si < 0) si = 0;
        if (model_.scenes.size() > 1)
            warn("the file has " + str(model_.scenes.size()) + " scenes; only scene " +
                 std::to_string(si) + " is loaded");
        scene_.name = model_.scenes[size_t(si)].name;
        std::set<int> seen;
        for (int r : model_.scenes[size_t(si)].nodes) {
            if (r < 0 || static_cast<size_t>(r) >= n)
                fail("scene " + std::to_string(si) + " lists node " + std::to_string(r) +
                     ", which does not exist (" + str(n) + " nodes)");
            if (parent[size_t(r)] >= 0)
                fail("scene " + std::to_string(si) + " lists node " + std::to_string(r) +
                     ", which is not a root node (its parent is node " +
                     std::to_string(parent[size_t(r)]) + ")");
            if (!seen.insert(r).second) {
                warn("a scene lists the same node twice (loaded once)");
                continue;
            }
            roots.push_back(r);
        }
    }
    return roots;
}

// A node's transform relative to its parent: its matrix, else its translation, rotation and scale.
glm::mat4 Loader::nodeLocalTransform(const tinygltf::Node& node, const std::string& where) {
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(where + ": matrix must have 16 numbers");
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(c * 4 + r)];
        return glm::mat4(m);
    }
    glm::dvec3 t(0.0), s(1.0);
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) fail(where + ": translation must have 3 numbers");
        t = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(where + ": rotation must have 4 numbers");
        q = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w))
            fail(where + ": rotation is not finite");
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(where + ": scale must have 3 numbers");
        s = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    }
    return detail::composeTrs(t, q, s);
}

void Loader::buildNodes() {
    const std::vector<int> parent = nodeParents();
    const std::vector<int> roots = sceneRoots(parent);

    // Depth-first over the forest (explicit stack: chains may be very deep).
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
    while (!stack.empty()) {
        auto [v, parentWorld] = stack.back();
        stack.pop_back();
        const tinygltf::Node& node = model_.nodes[size_t(v)];
        const std::string where = "node " + std::to_string(v) + quoted(node.name);
        const glm::mat4 local = nodeLocalTransform(node, where);
        const glm::mat4 world = parentWorld * local;
        if (!detail::isFinite(local) || !detail::isFinite(world))
            fail(where + ": transform is not finite");
        addNodeContent(v, world);
        const auto& children = node.children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, world);
    }
}

std::string fileBaseDir(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return "";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

std::string lowerExtension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot + 1);
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace

Scene loadGltfFile(const std::string& path) {
    const std::string label = oneLine(path, 300);
    std::vector<unsigned char> bytes;
    std::string why;
    if (!readRegularFile(path, bytes, why, nullptr))
        throw Error(label + ": cannot read file (" + oneLine(why) + ")");
    const std::string ext = lowerExtension(path);
    if (ext == "glb" && (bytes.size() < 4 || readU32(bytes.data()) != kGlbMagic))
        throw Error(label + ": not a binary glTF file (no 'glTF' magic at the start)");
    Loader loader(label);
    Scene s = loader.load(bytes.data(), bytes.size(), fileBaseDir(path));
    if (s.name.empty()) {
        const size_t slash = path.find_last_of('/');
        s.name = slash == std::string::npos ? path : path.substr(slash + 1);
    }
    return s;
}

Scene loadGltfMemory(const uint8_t* data, size_t size, const std::string& baseDir) {
    Loader loader("<memory>");
    return loader.load(data, size, baseDir);
}

}  // namespace gis
