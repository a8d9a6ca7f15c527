#include "cli/user_json.h"

#include <cstdint>
#include <limits>

#include "param_table.h"
#include "scene/scene.h"

namespace gis {
namespace {

// nlohmann's own DOM builder, checking each float against the text it was read from (sax_parse
// calls the handler's members by its static type, so this one replaces the base's).
struct StrictDomParser : nlohmann::detail::json_sax_dom_parser<nlohmann::json> {
    using Base = nlohmann::detail::json_sax_dom_parser<nlohmann::json>;
    using Base::Base;
    bool number_float(double value, const std::string& literal) {
        if (value == 0.0 && hasNonZeroMantissa(literal))
            throw Error("the number " + literal + " is too small for a double (it would be read as 0)");
        return Base::number_float(value, literal);
    }
    // Whole numbers past INT64_MAX are unsigned to nlohmann, and reading one as a signed integer
    // wrapped (18446744073709551615 was -1, "must be >= 0"); no key of a user's file takes one.
    bool number_unsigned(std::uint64_t value) {
        if (value > std::uint64_t(std::numeric_limits<std::int64_t>::max()))
            throw Error("the number " + std::to_string(value) + " is too large (a whole number is at most " +
                        std::to_string(std::numeric_limits<std::int64_t>::max()) + ")");
        return Base::number_unsigned(value);
    }
};

}  // namespace

nlohmann::json parseUserJson(const std::string& text) {
    nlohmann::json result;
    StrictDomParser sax(result);
    nlohmann::json::sax_parse(text, &sax);
    return result;
}

}  // namespace gis
