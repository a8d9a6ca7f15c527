#include "brdf_reference.h"

#include <algorithm>
#include <cmath>

namespace gis::test::brdf {

namespace {
constexpr double kPi = 3.14159265358979323846;

double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

double smoothStep(double lo, double hi, double x) {
    const double t = clamp01((x - lo) / (hi - lo));
    return t * t * (3.0 - 2.0 * t);
}

double schlickWeight(double cosine) { return std::pow(1.0 - cosine, 5.0); }

struct Angles {
    double NoL = 0, NoV = 0, NoVraw = 0, NoH = 0, LoH = 0, RoV = 0;
    bool hasHalf = false;
};

Angles angles(glm::dvec3 n, glm::dvec3 v, glm::dvec3 l) {
    Angles a;
    a.NoL = std::clamp(glm::dot(n, l), -1.0, 1.0);
    a.NoVraw = std::clamp(glm::dot(n, v), -1.0, 1.0);
    a.NoV = std::max(a.NoVraw, kMinNdotV);
    const glm::dvec3 r = 2.0 * glm::dot(n, l) * n - l;  // mirror direction of l
    a.RoV = glm::dot(r, v);
    const glm::dvec3 h = v + l;
    a.hasHalf = glm::dot(h, h) >= kMinHalfVectorLength2;
    if (a.hasHalf) {
        const glm::dvec3 H = glm::normalize(h);
        a.NoH = clamp01(glm::dot(n, H));
        a.LoH = clamp01(glm::dot(l, H));
    }
    return a;
}

// Cosine-weighted diffuse response per unit diffuse colour.
double diffuseResponse(const Angles& a, double r, int model) {
    const double cosL = std::max(a.NoL, 0.0);
    switch (model) {
        case kWrap: return std::max(a.NoL + r, 0.0) / ((1.0 + r) * (1.0 + r) * kPi);
        case kToonDiffuse: return smoothStep(-r, r, a.NoL) / kPi;
        case kBurley: {
            const double fd90 = 0.5 + 2.0 * r * a.LoH * a.LoH;
            return (1.0 + (fd90 - 1.0) * schlickWeight(cosL)) * (1.0 + (fd90 - 1.0) * schlickWeight(a.NoV)) * cosL / kPi;
        }
        default: return cosL / kPi;
    }
}

// Microfacet f (no cosine) for N.L > 0.
glm::dvec3 microfacet(const Surface& s, const Angles& a, double r, int model) {
    if (!a.hasHalf || a.NoH <= 0.0) return glm::dvec3(0.0);
    const double alpha = r * r;
    const double D = model == kGgx ? ggxD(a.NoH, alpha) : blinnPhongD(a.NoH, alpha);
    const double NoL = std::max(a.NoL, 0.0);
    const double vis = 0.5 / ((1.0 - alpha) * 2.0 * NoL * a.NoV + alpha * (NoL + a.NoV));
    const glm::dvec3 F = s.f0 + (glm::dvec3(s.f90) - s.f0) * schlickWeight(a.LoH);
    return D * vis * F;
}

glm::dvec3 toonSpecularResponse(const Surface& s, const Angles& a, double r) {
    if (a.NoL <= 0.0) return glm::dvec3(0.0);
    const double mid = (1.0 - r) * (1.0 - r);
    const double intensity = smoothStep(mid - 0.5 * r, mid + 0.5 * r, a.RoV) * mid;
    return intensity * glm::clamp(s.diffuseColor + s.f0, 0.0, 1.0) * s.f90;
}
}  // namespace

const char* diffuseName(int model) {
    static const char* names[] = {"lambert", "wrap", "toon", "burley"};
    return model >= 0 && model < kDiffuseCount ? names[model] : "?";
}

const char* specularName(int model) {
    static const char* names[] = {"ggx", "blinn", "toon", "none"};
    return model >= 0 && model < kSpecularCount ? names[model] : "?";
}

Surface makeSurface(glm::dvec3 baseColor, double metallic, double roughness, double specularFactor) {
    baseColor = glm::clamp(baseColor, 0.0, 1.0);
    metallic = clamp01(metallic);
    specularFactor = clamp01(specularFactor);
    Surface s;
    s.diffuseColor = baseColor * (1.0 - metallic);
    s.f0 = glm::mix(glm::dvec3(0.04 * specularFactor), baseColor, metallic);
    s.f90 = specularFactor + (1.0 - specularFactor) * metallic;
    s.roughness = std::clamp(roughness, kMinRoughness, 1.0);
    return s;
}

double ggxD(double NoH, double alpha) {
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double blinnPhongExponent(double alpha) { return 2.0 / (alpha * alpha) - 2.0; }

double blinnPhongD(double NoH, double alpha) {
    const double n = blinnPhongExponent(alpha);
    return (n + 2.0) / (2.0 * kPi) * std::pow(NoH, n);
}

glm::dvec3 evaluateCosine(const Surface& s, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, int diffuse, int specular) {
    const Angles a = angles(n, v, l);
    const double r = std::clamp(s.roughness, kMinRoughness, 1.0);
    glm::dvec3 out = s.diffuseColor * diffuseResponse(a, r, diffuse);
    if (a.NoL > 0.0) {
        if (specular == kGgx || specular == kBlinnPhong) out += microfacet(s, a, r, specular) * a.NoL;
        else if (specular == kToonSpecular) out += toonSpecularResponse(s, a, r);
    }
    return out;
}

glm::dvec3 evaluate(const Surface& s, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, int diffuse, int specular) {
    const Angles a = angles(n, v, l);
    if (a.NoL <= 0.0) return glm::dvec3(0.0);
    const double r = std::clamp(s.roughness, kMinRoughness, 1.0);
    const double cosL = std::max(a.NoL, kMinNdotL);  // only the non-BRDF models divide by it
    double d = 1.0 / kPi;
    if (diffuse == kWrap || diffuse == kToonDiffuse) d = diffuseResponse(a, r, diffuse) / cosL;
    else if (diffuse == kBurley) d = diffuseResponse(a, r, diffuse) / a.NoL;
    glm::dvec3 out = s.diffuseColor * d;
    if (specular == kGgx || specular == kBlinnPhong) out += microfacet(s, a, r, specular);
    else if (specular == kToonSpecular) out += toonSpecularResponse(s, a, r) / cosL;
    return out;
}

}  // namespace gis::test::brdf
