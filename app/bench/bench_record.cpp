#include "bench/bench_record.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/content_hash.h"
#include "image.h"
#include "scene/atomic_file.h"
#include "error.h"

namespace gis {

namespace {

namespace fs = std::filesystem;

// The checksum covers the record's bytes up to its closing field, exactly as written, so the check
// needs no JSON library to agree on number formatting: BODY is `{...}`, the file is
// `{...,"sha256":"HEX"}` + newline, HEX = SHA-256 of BODY.
const std::string kClosing = ",\"sha256\":\"";

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string failurePath(const std::string& recordPath) {
    return fs::path(recordPath).replace_extension(".failed").string();
}

}  // namespace

void writeRecord(const std::string& path, nlohmann::ordered_json body, const std::vector<std::string>& files) {
    const fs::path dir = fs::path(path).parent_path();
    for (const std::string& f : files) body["files"][f] = sha256File((dir / f).string());
    const std::string text = body.dump();
    const std::string closed = text.substr(0, text.size() - 1) + kClosing + sha256Hex(text) + "\"}\n";
    writeFileAtomically(path, closed);
}

RecordCheck readRecord(const std::string& path, const std::string& id) {
    RecordCheck r;
    std::error_code ec;
    r.exists = fs::exists(path, ec);
    if (!r.exists) {
        r.problem = "missing";
        return r;
    }
    const std::string text = slurp(path);
    const size_t at = text.rfind(kClosing);
    const nlohmann::ordered_json whole = nlohmann::ordered_json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (whole.is_discarded() || at == std::string::npos || !whole.is_object() || !whole.contains("sha256")) {
        r.problem = "truncated or damaged (" + std::to_string(text.size()) + " bytes, not a closed record)";
        return r;
    }
    const std::string body = text.substr(0, at) + "}";
    if (!whole["sha256"].is_string() || whole["sha256"].get<std::string>() != sha256Hex(body)) {
        r.problem = "checksum mismatch (the file was altered after it was written)";
        return r;
    }
    r.body = nlohmann::ordered_json::parse(body);
    if (r.body.value("id", std::string()) != id) {
        r.problem = "holds id " + r.body.value("id", std::string("(none)")) + ", not " + id;
        return r;
    }
    const fs::path dir = fs::path(path).parent_path();
    if (r.body.contains("files"))
        for (const auto& [name, sum] : r.body["files"].items()) {
            const fs::path file = dir / name;
            if (!fs::exists(file, ec)) {
                r.problem = "its file " + name + " is missing";
                return r;
            }
            if (sha256File(file.string()) != sum.get<std::string>()) {
                r.problem = "its file " + name + " does not match its checksum";
                return r;
            }
        }
    r.ok = true;
    return r;
}

void writeFailure(const std::string& recordPath, const std::string& message) {
    try {
        writeFileAtomically(failurePath(recordPath), message + "\n");
    } catch (const Error&) {
        // The job's own error is what the user must see; a note that could not be left changes nothing.
    }
}

std::string readFailure(const std::string& recordPath) {
    std::ifstream in(failurePath(recordPath));
    std::string line;
    std::getline(in, line);
    return line;
}

void clearFailure(const std::string& recordPath) {
    std::error_code ec;
    fs::remove(failurePath(recordPath), ec);
}

}  // namespace gis
