// Reading JSON that a user wrote (settings files, bench manifests): json::parse, but a number the
// grammar accepts and a double cannot hold is refused, naming it, instead of read as something else.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace gis {

// Throws nlohmann::json::parse_error on bad syntax (nlohmann refuses overflow, 1e400, itself) and
// gis::Error for a literal with non-zero digits that underflows to zero (1e-400).
nlohmann::json parseUserJson(const std::string& text);

}  // namespace gis
