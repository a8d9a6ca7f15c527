// One declaration per GI-method parameter (Godot's property model): key, label, help, type, range,
// default and whether it is live (read in execute(), changes nothing baked) or rebuild (baked into
// GPU resources). The CLI (`--set METHOD.KEY=VALUE`), the settings JSON, the viewer's panel and
// script, presets, validation and the viewer's rebuild decision are all driven by these rows.
//
// A method keeps its parameters in a plain struct; `ParamTable<S>` binds each row to a member, so
// the struct's default initialisers are the defaults and a pass reads typed fields. Values travel
// through RenderSettings as text-free `ParamValue`s keyed "method.key", holding only what differs
// from the defaults (a preset or the user set it).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "error.h"

namespace gis {

enum class ParamType { Int, Float, Bool, Choice, Colour };
enum class ParamUpdate { Live, Rebuild };

// Int, Float and Bool use `number`; Choice `text`; Colour `colour`.
struct ParamValue {
    ParamValue() = default;
    ParamValue(double n) : number(n) {}  // Int, Float, Bool (1 = true)
    static ParamValue choice(const char* name) {  // a Choice row's value, by its name
        ParamValue v;
        v.text = name;
        return v;
    }
    double number = 0.0;
    std::string text;
    glm::vec3 colour{0.0f};
    bool operator==(const ParamValue& o) const { return number == o.number && text == o.text && colour == o.colour; }
    bool operator!=(const ParamValue& o) const { return !(*this == o); }
};

struct ParamDesc {
    std::string key;                  // "samples": the full name is METHOD.KEY
    std::string label;                // panel label
    std::string help;
    ParamType type = ParamType::Float;
    double min = 0.0, max = 0.0;      // Int/Float range (inclusive); Colour: per channel
    std::vector<std::string> choices; // Choice
    ParamValue defaultValue;
    ParamUpdate update = ParamUpdate::Rebuild;
    std::string alias;                // an older CLI flag that sets the same row ("--ao-samples"), or ""
};

// A number as a settings file writes it (JSON's grammar: -?D+(.D+)?([eE][+-]?D+)?). strtod also takes
// 0x10, +5, .5, inf and nan: every number a user types (parameters, script and panel commands) is
// held to this grammar instead, so each input reads the same text the same way.
bool isPlainNumber(const std::string& word);
// A literal with a non-zero digit before its exponent is not zero, whatever strtod made of it: the
// test for a number that underflowed.
bool hasNonZeroMantissa(const std::string& literal);

// Parses `text` for `desc` ("32", "0.5", "true", "geometry", "1,0.5,0" or "0.5"); throws the one
// validation message: "METHOD.KEY: VALUE is out of range [MIN, MAX]" and the like. Numbers are
// plain (isPlainNumber) and finite, and one that underflows a double (1e-400, read as 0) is refused.
ParamValue parseParamValue(const std::string& method, const ParamDesc& desc, const std::string& text);
// Throws the same message for a value out of range (values built in code, JSON, the panel).
void checkParamValue(const std::string& method, const ParamDesc& desc, const ParamValue& value);
std::string formatParamValue(const ParamDesc& desc, const ParamValue& value);
std::string describeParamRange(const ParamDesc& desc);  // "[1, 256]", "hardware|geometry|off", "true|false"
const char* paramTypeName(ParamType type);

// A parameter table of a frame module every method shares (the emitter lights,
// renderer/emitters/): keys GROUP.KEY, set with --set, stored in RenderSettings::params, listed by
// `gisandbox methods` and validated exactly as a method's rows, but no --gi name.
struct ParamGroup {
    std::string name;                       // the key prefix: "emitters"
    std::string summary;                    // one line for `gisandbox methods`
    std::vector<ParamDesc> params;
};

// "method.key" -> value, for every parameter that is not at its default.
using ParamValues = std::map<std::string, ParamValue>;

// Rows bound to the members of a method's settings struct S.
template <class S>
struct ParamTable {
    std::vector<ParamDesc> rows;
    std::vector<std::function<void(S&, const ParamValue&)>> assign;

    ParamTable& integer(int S::*member, std::string key, std::string label, std::string help, int lo, int hi,
                        ParamUpdate update, std::string alias = "") {
        ParamDesc d = row(std::move(key), std::move(label), std::move(help), ParamType::Int, update, alias);
        d.min = lo, d.max = hi, d.defaultValue.number = S{}.*member;
        return add(d, [member](S& s, const ParamValue& v) { s.*member = int(v.number); });
    }
    ParamTable& real(float S::*member, std::string key, std::string label, std::string help, double lo, double hi,
                     ParamUpdate update, std::string alias = "") {
        ParamDesc d = row(std::move(key), std::move(label), std::move(help), ParamType::Float, update, alias);
        d.min = lo, d.max = hi, d.defaultValue.number = S{}.*member;
        return add(d, [member](S& s, const ParamValue& v) { s.*member = float(v.number); });
    }
    ParamTable& boolean(bool S::*member, std::string key, std::string label, std::string help, ParamUpdate update,
                        std::string alias = "") {
        ParamDesc d = row(std::move(key), std::move(label), std::move(help), ParamType::Bool, update, alias);
        d.max = 1, d.defaultValue.number = (S{}.*member) ? 1 : 0;
        return add(d, [member](S& s, const ParamValue& v) { s.*member = v.number != 0; });
    }
    // A choice stored as the index of its name in `choices`.
    ParamTable& choice(int S::*member, std::string key, std::string label, std::string help,
                       std::vector<std::string> choices, ParamUpdate update) {
        ParamDesc d = row(std::move(key), std::move(label), std::move(help), ParamType::Choice, update, "");
        d.choices = choices;
        d.defaultValue.text = choices.at(size_t(S{}.*member));
        return add(d, [member, choices](S& s, const ParamValue& v) {
            for (size_t i = 0; i < choices.size(); ++i)
                if (choices[i] == v.text) s.*member = int(i);
        });
    }
    ParamTable& colour(glm::vec3 S::*member, std::string key, std::string label, std::string help, double hi,
                       ParamUpdate update) {
        ParamDesc d = row(std::move(key), std::move(label), std::move(help), ParamType::Colour, update, "");
        d.max = hi, d.defaultValue.colour = S{}.*member;
        return add(d, [member](S& s, const ParamValue& v) { s.*member = v.colour; });
    }

    // The typed settings of `method`: defaults, overridden by `values["method.key"]`.
    S read(const std::string& method, const ParamValues& values) const {
        S s{};
        for (size_t i = 0; i < rows.size(); ++i) {
            auto it = values.find(method + "." + rows[i].key);
            if (it != values.end()) assign[i](s, it->second);
        }
        return s;
    }

private:
    static ParamDesc row(std::string key, std::string label, std::string help, ParamType type, ParamUpdate update,
                         const std::string& alias) {
        ParamDesc d;
        d.key = std::move(key), d.label = std::move(label), d.help = std::move(help);
        d.type = type, d.update = update, d.alias = alias;
        return d;
    }
    ParamTable& add(const ParamDesc& d, std::function<void(S&, const ParamValue&)> f) {
        rows.push_back(d);
        assign.push_back(std::move(f));
        return *this;
    }
};

}  // namespace gis
