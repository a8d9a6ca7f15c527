// make_seed_corpus <shared/assets> <work dir>: fills <work dir>/seeds with the shared .gltf/.glb
// files (each at most 128 KiB after embedding; .gltf external files become data: URIs) and
// empties <work dir>/corpus and <work dir>/artifacts.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

static std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
    }
    if (i + 1 == in.size()) {
        unsigned v = (unsigned char)in[i] << 16;
        out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == in.size()) {
        unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
    }
    return out;
}

static bool readFile(const fs::path& p, std::string& out) {
    std::ifstream f(p, std::ios::binary);
    if (!f) return false;
    out.assign(std::istreambuf_iterator<char>(f), {});
    return true;
}

static std::string urlDecode(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size()) {
            out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: make_seed_corpus <shared/assets> <work dir>\n";
        return 2;
    }
    const fs::path src = argv[1], work = argv[2];
    const size_t kMax = 128 * 1024;
    fs::remove_all(work / "seeds");
    fs::remove_all(work / "corpus");
    fs::remove_all(work / "artifacts");
    fs::create_directories(work / "seeds");
    fs::create_directories(work / "corpus");
    fs::create_directories(work / "artifacts");
    size_t written = 0, skipped = 0;
    for (const auto& e : fs::recursive_directory_iterator(src)) {
        if (!e.is_regular_file()) continue;
        const std::string ext = e.path().extension().string();
        if (ext != ".gltf" && ext != ".glb") continue;
        std::string data;
        if (!readFile(e.path(), data)) continue;
        if (ext == ".gltf") {
            try {
                nlohmann::json j = nlohmann::json::parse(data);
                for (const char* key : {"buffers", "images"}) {
                    if (!j.contains(key) || !j[key].is_array()) continue;
                    for (auto& item : j[key]) {
                        if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
                        const std::string uri = item["uri"];
                        if (uri.rfind("data:", 0) == 0) continue;
                        std::string bytes;
                        if (!readFile(e.path().parent_path() / urlDecode(uri), bytes)) continue;
                        if (bytes.size() > kMax) { data.clear(); break; }
                        item["uri"] = std::string("data:application/octet-stream;base64,") + base64(bytes);
                    }
                }
                if (!data.empty()) data = j.dump();
            } catch (const std::exception&) {
                // invalid JSON: keep the file as it is, it is a fine seed too
            }
        }
        if (data.empty() || data.size() > kMax) {
            ++skipped;
            continue;
        }
        std::string name = fs::relative(e.path(), src).string();
        for (char& c : name)
            if (c == '/' || c == ' ') c = '_';
        std::ofstream(work / "seeds" / name, std::ios::binary) << data;
        ++written;
    }
    std::cout << "seed corpus: " << written << " files in " << (work / "seeds").string() << " ("
              << skipped << " skipped as larger than " << kMax << " bytes)\n";
    return written > 0 ? 0 : 1;
}
