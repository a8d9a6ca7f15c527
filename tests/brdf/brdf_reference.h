// CPU double-precision reference of every BRDF in shaders/brdf.glsl, written from the formulas
// (the sources cited there), not transliterated: it normalises H and uses 1 - N.H^2 and pow()
// where the GLSL uses |N x H|^2, |L + V| and exp/log. The guards are the same named constants,
// because they define the model at the extremes.
#pragma once

#include <glm/glm.hpp>

namespace gis::test::brdf {

// The ids of gis::DiffuseModel / SpecularModel and brdf.glsl's DIFFUSE_* / SPECULAR_*.
enum Diffuse { kLambert = 0, kWrap = 1, kToonDiffuse = 2, kBurley = 3, kDiffuseCount = 4 };
enum Specular { kGgx = 0, kBlinnPhong = 1, kToonSpecular = 2, kNoSpecular = 3, kSpecularCount = 4 };
const char* diffuseName(int model);
const char* specularName(int model);

constexpr double kMinRoughness = 0.045;
constexpr double kMinNdotV = 1e-4;
constexpr double kMinNdotL = 1e-4;
constexpr double kMinHalfVectorLength2 = 1e-8;

struct Surface {
    glm::dvec3 diffuseColor{0.0};
    glm::dvec3 f0{0.0};
    double f90 = 1.0;
    double roughness = kMinRoughness;
};

Surface makeSurface(glm::dvec3 baseColor, double metallic, double roughness, double specularFactor);

// f(l, v) (0 for N.L <= 0) and the cosine-weighted response f * max(N.L, 0) (for wrap and toon,
// the model's own response, non-zero a little past N.L = 0).
glm::dvec3 evaluate(const Surface& s, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, int diffuse, int specular);
glm::dvec3 evaluateCosine(const Surface& s, glm::dvec3 n, glm::dvec3 v, glm::dvec3 l, int diffuse, int specular);

// The normal distributions (for importance sampling in the furnace test), alpha = roughness^2.
double ggxD(double NoH, double alpha);
double blinnPhongD(double NoH, double alpha);
double blinnPhongExponent(double alpha);

}  // namespace gis::test::brdf
