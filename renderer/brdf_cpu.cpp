#include "brdf_cpu.h"

#include <algorithm>
#include <cmath>

namespace gis {

namespace {

// The named constants of brdf.glsl and common.glsl.
constexpr float kPi = 3.14159265358979f;
constexpr float kInvPi = 0.31830988618379f;
constexpr float kMinRoughness = 0.045f;
constexpr float kMinNdotV = 1e-4f;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

glm::vec3 lambert(const CpuSurfaceBrdf& s, const BrdfAngles&) { return s.diffuseColor * kInvPi; }

float distributionGgx(float NoH, float alpha) {
    const float a2 = alpha * alpha;
    const float f = (NoH * a2 - NoH) * NoH + 1.0f;
    return a2 / (kPi * f * f);
}

float visibilitySmithGgxHammon(float NoV, float NoL, float alpha) {
    const float lerp = 2.0f * NoL * NoV + alpha * ((NoL + NoV) - 2.0f * NoL * NoV);
    return 0.5f / std::max(lerp, 1e-8f);
}

glm::vec3 fresnelSchlick(glm::vec3 f0, float VoH) {
    const float m = 1.0f - saturate(VoH);
    const float m2 = m * m;
    return f0 + (glm::vec3(1.0f) - f0) * (m2 * m2 * m);
}

glm::vec3 ggx(const CpuSurfaceBrdf& s, const BrdfAngles& a) {
    const float alpha = s.roughness * s.roughness;
    return distributionGgx(a.NoH, alpha) * visibilitySmithGgxHammon(a.NoV, a.NoL, alpha) * fresnelSchlick(s.f0, a.VoH);
}

// One entry per model (see brdf_cpu.h).
const std::vector<DiffuseModelInfo> kDiffuseModels = {
    {"lambert", DiffuseModel::Lambert, lambert},
};
const std::vector<SpecularModelInfo> kSpecularModels = {
    {"ggx", SpecularModel::Ggx, ggx},
    {"none", SpecularModel::None, nullptr},
};

}  // namespace

CpuSurfaceBrdf makeCpuSurfaceBrdf(glm::vec3 baseColor, float metallic, float roughness, float specularFactor) {
    CpuSurfaceBrdf s;
    s.diffuseColor = baseColor * (1.0f - metallic);
    s.f0 = glm::mix(glm::vec3(0.04f * specularFactor), baseColor, metallic);
    s.roughness = std::clamp(roughness, kMinRoughness, 1.0f);
    return s;
}

BrdfAngles brdfAngles(glm::vec3 N, glm::vec3 V, glm::vec3 L) {
    BrdfAngles a;
    a.NoL = glm::dot(N, L);
    a.NoV = std::max(glm::dot(N, V), kMinNdotV);
    const glm::vec3 h = V + L;
    const float hLen2 = glm::dot(h, h);
    const glm::vec3 H = hLen2 > 1e-12f ? h / std::sqrt(hLen2) : N;
    a.NoH = saturate(glm::dot(N, H));
    a.VoH = saturate(glm::dot(V, H));
    return a;
}

const std::vector<DiffuseModelInfo>& diffuseModels() { return kDiffuseModels; }
const std::vector<SpecularModelInfo>& specularModels() { return kSpecularModels; }

const char* diffuseModelName(DiffuseModel m) {
    for (const DiffuseModelInfo& i : kDiffuseModels)
        if (i.model == m) return i.name;
    throw Error("diffuse model " + std::to_string(int(m)) + " has no entry in renderer/brdf_cpu.cpp");
}

const char* specularModelName(SpecularModel m) {
    for (const SpecularModelInfo& i : kSpecularModels)
        if (i.model == m) return i.name;
    throw Error("specular model " + std::to_string(int(m)) + " has no entry in renderer/brdf_cpu.cpp");
}

namespace {
const DiffuseModelInfo& diffuseInfo(DiffuseModel m) {
    for (const DiffuseModelInfo& i : kDiffuseModels)
        if (i.model == m) return i;
    throw Error("diffuse model " + std::to_string(int(m)) + " has no entry in renderer/brdf_cpu.cpp");
}
const SpecularModelInfo& specularInfo(SpecularModel m) {
    for (const SpecularModelInfo& i : kSpecularModels)
        if (i.model == m) return i;
    throw Error("specular model " + std::to_string(int(m)) + " has no entry in renderer/brdf_cpu.cpp");
}
}  // namespace

glm::vec3 evaluateCpuBrdf(const CpuSurfaceBrdf& s, glm::vec3 N, glm::vec3 V, glm::vec3 L, DiffuseModel diffuse,
                          SpecularModel specular) {
    const BrdfAngles a = brdfAngles(N, V, L);
    if (a.NoL <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 f = diffuseInfo(diffuse).evaluate(s, a);
    const SpecularModelInfo& spec = specularInfo(specular);
    if (spec.evaluate) f += spec.evaluate(s, a);
    return f;
}

std::vector<LobeSample> brdfLobe(const CpuSurfaceBrdf& s, float viewAngle, DiffuseModel diffuse,
                                 SpecularModel specular, int samples) {
    const DiffuseModelInfo& d = diffuseInfo(diffuse);
    const SpecularModelInfo& sp = specularInfo(specular);
    const glm::vec3 N(0.0f, 0.0f, 1.0f);
    const glm::vec3 V(-std::sin(viewAngle), 0.0f, std::cos(viewAngle));
    std::vector<LobeSample> out;
    samples = std::max(samples, 2);
    for (int i = 0; i < samples; ++i) {
        LobeSample ls;
        ls.angle = (-0.5f + float(i) / float(samples - 1)) * kPi;
        const glm::vec3 L(std::sin(ls.angle), 0.0f, std::cos(ls.angle));
        const BrdfAngles a = brdfAngles(N, V, L);
        if (a.NoL > 0.0f) {
            ls.diffuse = d.evaluate(s, a) * a.NoL;
            if (sp.evaluate) ls.specular = sp.evaluate(s, a) * a.NoL;
        }
        out.push_back(ls);
    }
    return out;
}

}  // namespace gis
