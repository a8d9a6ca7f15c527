// The result files of bench jobs: ID.json beside the image it describes, written last and
// atomically, closed by a checksum of everything before it. A record that is missing, cut short,
// altered, or whose image no longer matches its checksum is never taken for a result.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace gis {

// Adds "files": {name: sha256} for `files` (names in the record's directory) and the closing
// "sha256" field, then writes atomically. Throws gis::Error naming the file.
void writeRecord(const std::string& path, nlohmann::ordered_json body, const std::vector<std::string>& files);

struct RecordCheck {
    bool ok = false;
    bool exists = false;
    std::string problem;            // when not ok: "missing", "truncated ...", "checksum mismatch" ...
    nlohmann::ordered_json body;    // when ok: without the closing checksum
};
// Verifies the record at `path` (its checksum, its id, every file it names).
RecordCheck readRecord(const std::string& path, const std::string& id);

// A job that threw leaves ID.failed with its message, so a merge can say why; a later success
// removes it.
void writeFailure(const std::string& recordPath, const std::string& message);
std::string readFailure(const std::string& recordPath);  // "" when none
void clearFailure(const std::string& recordPath);

}  // namespace gis
