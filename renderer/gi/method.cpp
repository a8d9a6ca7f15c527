#include "gi/method.h"

#include <algorithm>

#include "passes/lighting_pass.h"
#include "scene/scene_lighting.h"

namespace gis {

std::vector<GiMethod>& methodRegistry();  // gi/methods.cpp

const std::vector<GiMethod>& giMethods() { return methodRegistry(); }

void registerGiMethod(GiMethod method) {
    if (findGiMethod(method.name)) throw Error("GI method '" + method.name + "' is already registered");
    methodRegistry().push_back(std::move(method));
}

std::vector<ShaderTables> methodShaderTables() {
    std::vector<ShaderTables> tables;
    for (const GiMethod& m : giMethods()) tables.push_back(m.shaderTables);
    return tables;
}

const GiMethod* findGiMethod(const std::string& name) {
    for (const GiMethod& m : giMethods())
        if (m.name == name) return &m;
    return nullptr;
}

const GiMethod& methodInRole(MethodRole role) {
    for (const GiMethod& m : giMethods())
        if (m.role == role) return m;
    throw Error(std::string("no GI method is registered as the ") +
                (role == MethodRole::Reference ? "reference" : role == MethodRole::AoReference ? "AO reference" : "method"));
}

std::string roleParamKey(MethodRole role, const std::string& key) {
    const GiMethod& m = methodInRole(role);
    if (!m.param(key)) throw Error("GI method '" + m.name + "' has no parameter '" + key + "'");
    return m.name + "." + key;
}

namespace {
std::vector<std::string> methodNameList() {
    std::vector<std::string> names;
    for (const GiMethod& m : giMethods()) names.push_back(m.name);
    return names;
}
}  // namespace

std::string giMethodNames() {
    std::string s;
    for (const GiMethod& m : giMethods()) s += (s.empty() ? "" : ", ") + m.name;
    return s;
}

const GiMethod& giMethod(const std::string& name) {
    if (const GiMethod* m = findGiMethod(name)) return *m;
    throw Error("unknown GI method '" + name + "' (" + didYouMean(name, methodNameList()) + "available: " +
                giMethodNames() + ")");
}

const std::vector<std::string>& presetNames() {
    static const std::vector<std::string> names{"low", "medium", "high"};
    return names;
}

const ParamDesc* GiMethod::param(const std::string& key) const {
    for (const ParamDesc& d : params)
        if (d.key == key) return &d;
    return nullptr;
}

const GiPreset& GiMethod::preset(const std::string& presetName) const {
    for (const GiPreset& p : presets)
        if (p.name == presetName) return p;
    std::string names;
    for (const GiPreset& p : presets) names += (names.empty() ? "" : ", ") + p.name;
    throw Error("unknown preset '" + presetName + "' for " + name + " (expected " + names + ")");
}

void applyPreset(RenderSettings& s, const std::string& method, const std::string& presetName) {
    const GiPreset& p = giMethod(method).preset(presetName);
    s.gi = method;
    for (const auto& [key, value] : p.values) s.params[key] = value;
    if (p.shadowMapSize) s.shadowMapSize = p.shadowMapSize;
    if (p.shadowCubeSize) s.shadowCubeSize = p.shadowCubeSize;
}

const ParamDesc& findParam(const std::string& fullKey, std::string* methodOut) {
    for (const GiMethod& m : giMethods())
        for (const ParamDesc& d : m.params)
            if (fullKey == m.name + "." + d.key || (!d.alias.empty() && fullKey == d.alias)) {
                if (methodOut) *methodOut = m.name;
                return d;
            }
    for (const ParamGroup& g : paramGroups())
        for (const ParamDesc& d : g.params)
            if (fullKey == g.name + "." + d.key) {
                if (methodOut) *methodOut = g.name;
                return d;
            }
    const size_t dot = fullKey.find('.');
    const std::string prefix = dot == std::string::npos ? "" : fullKey.substr(0, dot);
    for (const ParamGroup& g : paramGroups())
        if (g.name == prefix) {
            std::string keys;
            for (const ParamDesc& d : g.params) keys += (keys.empty() ? "" : ", ") + d.key;
            throw Error("unknown parameter '" + fullKey + "' (" + g.name + " has: " + keys + ")");
        }
    const GiMethod* m = prefix.empty() ? nullptr : findGiMethod(prefix);
    if (!m)
        throw Error("unknown parameter '" + fullKey + "' (expected METHOD.KEY; " +
                    didYouMean(prefix, methodNameList()) + "methods: " + giMethodNames() + ")");
    std::string keys;
    std::vector<std::string> names;
    for (const ParamDesc& d : m->params) keys += (keys.empty() ? "" : ", ") + d.key, names.push_back(d.key);
    throw Error("unknown parameter '" + fullKey + "' (" + didYouMean(fullKey.substr(dot + 1), names) + m->name +
                " has: " + (keys.empty() ? "none" : keys) + ")");
}

bool isGroupParam(const std::string& fullKey) {
    for (const ParamGroup& g : paramGroups())
        if (fullKey.rfind(g.name + ".", 0) == 0) return true;
    return false;
}

void checkParams(const ParamValues& values) {
    std::vector<const GiMethod*> named;
    for (const auto& [key, value] : values) {
        std::string method;
        const ParamDesc& d = findParam(key, &method);
        checkParamValue(method, d, value);
        const GiMethod* m = findGiMethod(method);
        if (m && m->checkSettings && std::find(named.begin(), named.end(), m) == named.end()) named.push_back(m);
    }
    for (const GiMethod* m : named) m->checkSettings(values);
}

void checkViewOfMethod(const std::string& gi, const std::string& view) {
    const GiMethod& method = giMethod(gi);
    const std::vector<std::string> terms = LightingPass::termViewNames();
    auto writes = [&view](const GiMethod& m) {
        return m.pipeline == MethodPipeline::Deferred ||
               std::find(m.termViews.begin(), m.termViews.end(), view) != m.termViews.end();
    };
    if (view != "ao" && std::find(terms.begin(), terms.end(), view) != terms.end() && !writes(method)) {
        std::string with;
        for (const GiMethod& m : giMethods())
            if (writes(m)) with += (with.empty() ? "" : ", ") + m.name;
        throw Error("view '" + view + "' is a term of the deferred lighting pass, which --gi " + gi +
                    " does not run, and " + gi + " does not write it itself (it exists for " + with + ")");
    }
    const size_t dot = view.find('.');
    const GiMethod* owner = dot == std::string::npos ? nullptr : findGiMethod(view.substr(0, dot));
    if (owner && owner != &method)
        throw Error("view '" + view + "' is a view of --gi " + owner->name + ", not produced by --gi " + gi);
}

void setParam(RenderSettings& s, const std::string& fullKey, const std::string& text) {
    // An alias flag (--spp, --ao-radius) sets every row that declares it.
    bool any = false;
    for (const GiMethod& m : giMethods())
        for (const ParamDesc& d : m.params)
            if (fullKey == m.name + "." + d.key || (!d.alias.empty() && fullKey == d.alias)) {
                s.params[m.name + "." + d.key] = parseParamValue(m.name, d, text);
                any = true;
            }
    for (const ParamGroup& g : paramGroups())
        for (const ParamDesc& d : g.params)
            if (fullKey == g.name + "." + d.key) {
                s.params[fullKey] = parseParamValue(g.name, d, text);
                any = true;
            }
    if (!any) findParam(fullKey);  // throws the message naming the method's keys
}

ParamValue getParam(const RenderSettings& s, const std::string& fullKey) {
    auto it = s.params.find(fullKey);
    return it != s.params.end() ? it->second : findParam(fullKey).defaultValue;
}

}  // namespace gis
