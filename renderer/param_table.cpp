#include "param_table.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace gis {

namespace {

// The shortest text (up to 9 significant digits, float's round-trip precision) that reads back as
// the same float: "0.03", not "0.0299999993" for 0.03f.
std::string number(double v) {
    for (int digits = 6; digits <= 9; ++digits) {
        std::ostringstream os;
        os.precision(digits);
        os << v;
        const double back = std::strtod(os.str().c_str(), nullptr);
        if (float(back) == float(v)) return os.str();
    }
    return std::to_string(v);
}

[[noreturn]] void fail(const std::string& method, const ParamDesc& d, const std::string& text, const std::string& why) {
    throw Error(method + "." + d.key + ": '" + text + "' " + why);
}

enum class NumberText { Number, NotPlain, TooLarge, TooSmall };

// Parameters hold floats: a number a float cannot hold is refused rather than read as Inf or as 0
// (1e-50 would become 0, which for ssao.radius means "15% of the scene").
NumberText parseNumber(const std::string& text, double& out) {
    if (!isPlainNumber(text)) return NumberText::NotPlain;
    out = std::strtod(text.c_str(), nullptr);
    if (!std::isfinite(float(out))) return NumberText::TooLarge;
    if (float(out) == 0.0f && hasNonZeroMantissa(text)) return NumberText::TooSmall;
    return NumberText::Number;
}

// The message for a number parseNumber refused; `notPlain` says what the text should have been.
std::string numberProblem(NumberText problem, const std::string& notPlain) {
    switch (problem) {
        case NumberText::TooLarge: return "is too large for a float";
        case NumberText::TooSmall: return "is too small for a float (it would be read as 0)";
        default: return notPlain;
    }
}

}  // namespace

bool isPlainNumber(const std::string& w) {
    size_t i = 0;
    auto digits = [&] {
        const size_t start = i;
        while (i < w.size() && std::isdigit(static_cast<unsigned char>(w[i]))) ++i;
        return i > start;
    };
    if (i < w.size() && w[i] == '-') ++i;
    if (!digits()) return false;
    if (i < w.size() && w[i] == '.' && (++i, !digits())) return false;
    if (i < w.size() && (w[i] == 'e' || w[i] == 'E')) {
        ++i;
        if (i < w.size() && (w[i] == '+' || w[i] == '-')) ++i;
        if (!digits()) return false;
    }
    return i == w.size();
}

bool hasNonZeroMantissa(const std::string& literal) {
    for (char c : literal) {
        if (c == 'e' || c == 'E') return false;
        if (c >= '1' && c <= '9') return true;
    }
    return false;
}

const char* paramTypeName(ParamType t) {
    switch (t) {
        case ParamType::Int: return "int";
        case ParamType::Float: return "float";
        case ParamType::Bool: return "bool";
        case ParamType::Choice: return "choice";
        case ParamType::Colour: return "colour";
    }
    return "?";
}

std::string describeParamRange(const ParamDesc& d) {
    switch (d.type) {
        case ParamType::Bool: return "true|false";
        case ParamType::Choice: {
            std::string s;
            for (const std::string& c : d.choices) s += (s.empty() ? "" : "|") + c;
            return s;
        }
        case ParamType::Colour: return "R,G,B in [0, " + number(d.max) + "]";
        default: return "[" + number(d.min) + ", " + number(d.max) + "]";
    }
}

std::string formatParamValue(const ParamDesc& d, const ParamValue& v) {
    switch (d.type) {
        case ParamType::Bool: return v.number != 0 ? "true" : "false";
        case ParamType::Choice: return v.text;
        case ParamType::Colour: return number(v.colour.r) + "," + number(v.colour.g) + "," + number(v.colour.b);
        default: return number(v.number);
    }
}

void checkParamValue(const std::string& method, const ParamDesc& d, const ParamValue& v) {
    const std::string text = formatParamValue(d, v);
    switch (d.type) {
        case ParamType::Int:
            if (v.number != std::floor(v.number)) fail(method, d, text, "is not an integer");
            [[fallthrough]];
        case ParamType::Float:
            if (!std::isfinite(v.number) || v.number < d.min || v.number > d.max)
                fail(method, d, text, "is out of range " + describeParamRange(d));
            return;
        case ParamType::Bool:
            if (v.number != 0 && v.number != 1) fail(method, d, text, "is not one of " + describeParamRange(d));
            return;
        case ParamType::Choice:
            for (const std::string& c : d.choices)
                if (c == v.text) return;
            fail(method, d, text, "is not one of " + describeParamRange(d));
        case ParamType::Colour:
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(v.colour[c]) || v.colour[c] < 0 || v.colour[c] > d.max)
                    fail(method, d, text, "is out of range: " + describeParamRange(d));
            return;
    }
}

ParamValue parseParamValue(const std::string& method, const ParamDesc& d, const std::string& text) {
    ParamValue v;
    switch (d.type) {
        case ParamType::Int:
        case ParamType::Float:
            if (const NumberText n = parseNumber(text, v.number); n != NumberText::Number)
                fail(method, d, text, numberProblem(n, d.type == ParamType::Int ? "is not an integer" : "is not a number"));
            break;
        case ParamType::Bool:
            if (text == "true" || text == "1" || text == "on") v.number = 1;
            else if (text == "false" || text == "0" || text == "off") v.number = 0;
            else fail(method, d, text, "is not one of " + describeParamRange(d));
            break;
        case ParamType::Choice: v.text = text; break;
        case ParamType::Colour: {
            std::vector<double> parts;
            std::stringstream ss(text);
            std::string item;
            while (std::getline(ss, item, ',')) {
                double x = 0;
                if (const NumberText n = parseNumber(item, x); n != NumberText::Number)
                    fail(method, d, text, numberProblem(n, "is not a colour (R,G,B or one value)"));
                parts.push_back(x);
            }
            if (parts.size() == 1) v.colour = glm::vec3(float(parts[0]));
            else if (parts.size() == 3) v.colour = glm::vec3(float(parts[0]), float(parts[1]), float(parts[2]));
            else fail(method, d, text, "is not a colour (R,G,B or one value)");
            break;
        }
    }
    checkParamValue(method, d, v);
    return v;
}

}  // namespace gis
