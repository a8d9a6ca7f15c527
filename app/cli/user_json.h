// Reading JSON that a user wrote (settings files, bench manifests): json::parse, but a number the
// grammar accepts and a double cannot hold is refused, naming it, instead of read as something else.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace gis {

// The largest settings file or viewer script read (readUserFile's limit): text a person writes is
// far smaller, and /dev/zero or a sparse file of gigabytes is refused before it is read.
constexpr uint64_t kMaxUserTextBytes = uint64_t(16) << 20;

// Throws nlohmann::json::parse_error on bad syntax (nlohmann refuses overflow, 1e400, itself) and
// gis::Error for a literal with non-zero digits that underflows to zero (1e-400) and for a whole
// number past INT64_MAX (read as a signed integer it wrapped).
nlohmann::json parseUserJson(const std::string& text);

}  // namespace gis
