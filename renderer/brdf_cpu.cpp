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
constexpr float kMinNdotL = 1e-4f;
constexpr float kMinHalfVectorLength2 = 1e-8f;
constexpr float kMinLogArgument = 1e-30f;

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }
float pow5(float x) { return x * x * x * x * x; }
float log1mx(float x) {
    if (x < 0.01f) return -x * (1.0f + x * (0.5f + x * (1.0f / 3.0f + x * 0.25f)));
    return std::log(std::max(1.0f - x, kMinLogArgument));
}
float ramp(float lo, float hi, float x) {
    const float t = saturate((x - lo) / (hi - lo));
    return t * t * (3.0f - 2.0f * t);
}
float invNoL(const BrdfAngles& a) { return 1.0f / std::max(a.NoL, kMinNdotL); }

// Diffuse f (without N.L), per brdf.glsl's evaluateBrdf.
glm::vec3 lambert(const CpuSurfaceBrdf& s, const BrdfAngles&) { return s.diffuseColor * kInvPi; }
glm::vec3 lambertWrap(const CpuSurfaceBrdf& s, const BrdfAngles& a) {
    const float w = s.roughness;
    return s.diffuseColor * (std::max(a.NoL + w, 0.0f) / ((1.0f + w) * (1.0f + w)) * kInvPi * invNoL(a));
}
glm::vec3 toonDiffuse(const CpuSurfaceBrdf& s, const BrdfAngles& a) {
    return s.diffuseColor * (ramp(-s.roughness, s.roughness, a.NoL) * kInvPi * invNoL(a));
}
glm::vec3 burley(const CpuSurfaceBrdf& s, const BrdfAngles& a) {
    const float fd90Minus1 = 2.0f * s.roughness * a.LoH * a.LoH - 0.5f;
    const float light = 1.0f + fd90Minus1 * pow5(1.0f - std::max(a.NoL, 0.0f));
    const float view = 1.0f + fd90Minus1 * pow5(1.0f - a.NoV);
    return s.diffuseColor * (light * view * kInvPi);
}

float distributionGgx(const BrdfAngles& a, float alpha) {
    const float a2 = alpha * alpha;
    const float d = a.NoH * a.NoH * a2 + a.sinNH2;
    return a2 / (kPi * d * d);
}
float distributionBlinnPhong(const BrdfAngles& a, float alpha) {
    const float n = 2.0f / (alpha * alpha) - 2.0f;
    return (n + 2.0f) * (0.5f * kInvPi) * std::exp(0.5f * n * log1mx(a.sinNH2));
}
float visibilitySmithGgxHammon(float NoV, float NoL, float alpha) {
    return 0.5f / (2.0f * NoL * NoV + alpha * ((NoL + NoV) - 2.0f * NoL * NoV));
}
glm::vec3 microfacet(const CpuSurfaceBrdf& s, const BrdfAngles& a, bool ggxLobe) {
    if (!a.hasHalf || a.NoH <= 0.0f) return glm::vec3(0.0f);
    const float alpha = s.roughness * s.roughness;
    const float D = ggxLobe ? distributionGgx(a, alpha) : distributionBlinnPhong(a, alpha);
    const glm::vec3 F = s.f0 + (glm::vec3(s.f90) - s.f0) * pow5(1.0f - a.LoH);
    return D * visibilitySmithGgxHammon(a.NoV, std::max(a.NoL, 0.0f), alpha) * F;
}
glm::vec3 ggx(const CpuSurfaceBrdf& s, const BrdfAngles& a) { return microfacet(s, a, true); }
glm::vec3 blinnPhong(const CpuSurfaceBrdf& s, const BrdfAngles& a) { return microfacet(s, a, false); }
glm::vec3 toonSpecular(const CpuSurfaceBrdf& s, const BrdfAngles& a) {
    if (a.NoL <= 0.0f) return glm::vec3(0.0f);
    const float mid = (1.0f - s.roughness) * (1.0f - s.roughness);
    const float intensity = ramp(mid - 0.5f * s.roughness, mid + 0.5f * s.roughness, a.RoV) * mid;
    return intensity * glm::clamp(s.diffuseColor + s.f0, 0.0f, 1.0f) * s.f90 * invNoL(a);
}

// One entry per model (see brdf_cpu.h), in brdf.glsl's id order.
const std::vector<DiffuseModelInfo> kDiffuseModels = {
    {"lambert", DiffuseModel::Lambert, lambert},
    {"wrap", DiffuseModel::LambertWrap, lambertWrap},
    {"toon", DiffuseModel::Toon, toonDiffuse},
    {"burley", DiffuseModel::Burley, burley},
};
const std::vector<SpecularModelInfo> kSpecularModels = {
    {"ggx", SpecularModel::Ggx, ggx},
    {"blinn", SpecularModel::BlinnPhong, blinnPhong},
    {"toon", SpecularModel::Toon, toonSpecular},
    {"none", SpecularModel::None, nullptr},
};

}  // namespace

CpuSurfaceBrdf makeCpuSurfaceBrdf(glm::vec3 baseColor, float metallic, float roughness, float specularFactor) {
    CpuSurfaceBrdf s;
    baseColor = glm::clamp(baseColor, 0.0f, 1.0f);
    metallic = saturate(metallic);
    specularFactor = saturate(specularFactor);
    s.diffuseColor = baseColor * (1.0f - metallic);
    s.f0 = glm::mix(glm::vec3(0.04f * specularFactor), baseColor, metallic);
    s.f90 = specularFactor + (1.0f - specularFactor) * metallic;
    s.roughness = std::clamp(roughness, kMinRoughness, 1.0f);
    return s;
}

BrdfAngles brdfAngles(glm::vec3 N, glm::vec3 V, glm::vec3 L) {
    BrdfAngles a;
    a.NoL = std::clamp(glm::dot(N, L), -1.0f, 1.0f);
    const float NoVraw = std::clamp(glm::dot(N, V), -1.0f, 1.0f);
    a.NoV = std::max(NoVraw, kMinNdotV);
    a.RoV = 2.0f * a.NoL * NoVraw - glm::dot(L, V);
    const glm::vec3 h = V + L;
    const float hLen2 = glm::dot(h, h);
    a.hasHalf = hLen2 >= kMinHalfVectorLength2;
    a.LoH = a.hasHalf ? saturate(0.5f * std::sqrt(hLen2)) : 0.0f;
    if (a.hasHalf) {
        const glm::vec3 H = h / std::sqrt(hLen2);
        a.NoH = saturate(glm::dot(N, H));
        const glm::vec3 c = glm::cross(N, H);
        a.sinNH2 = saturate(glm::dot(c, c));
    }
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
