// The BRDF models of shaders/brdf.glsl evaluated on the CPU, for the view's lobe plot. One table
// entry per model: adding a model to brdf.glsl (and DiffuseModel / SpecularModel) means adding its
// entry to kDiffuseModels / kSpecularModels in brdf_cpu.cpp, nothing else (the panel's selectors
// and the plot read the tables). Single precision and the same guards as the GLSL, so the plot
// shows what the renderer computes; tests/view checks it against the lighting pass.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "render_settings.h"
#include "gl/shader.h"

namespace gis {

// makeSurfaceBrdf() of brdf.glsl.
struct CpuSurfaceBrdf {
    glm::vec3 diffuseColor{0.0f};
    glm::vec3 f0{0.04f};
    float f90 = 1.0f;
    float roughness = 0.5f;
};
CpuSurfaceBrdf makeCpuSurfaceBrdf(glm::vec3 baseColor, float metallic, float roughness, float specularFactor);

// What one model needs about (N, V, L): brdf.glsl's BrdfGeometry, with the same guards.
struct BrdfAngles {
    float NoL = 0.0f;      // signed
    float NoV = 0.0f;      // >= MIN_N_DOT_V
    float NoH = 0.0f;
    float sinNH2 = 1.0f;   // 1 - N.H^2 as |N x H|^2
    float LoH = 0.0f;      // = V.H
    float RoV = 0.0f;      // reflect(-L, N) . V
    bool hasHalf = false;  // false when L = -V
};
BrdfAngles brdfAngles(glm::vec3 N, glm::vec3 V, glm::vec3 L);

struct DiffuseModelInfo {
    const char* name;                 // as on the command line (--diffuse) and in settings files
    DiffuseModel model;
    glm::vec3 (*evaluate)(const CpuSurfaceBrdf&, const BrdfAngles&);  // f, without the N.L factor
};
struct SpecularModelInfo {
    const char* name;                 // --specular
    SpecularModel model;
    glm::vec3 (*evaluate)(const CpuSurfaceBrdf&, const BrdfAngles&);  // f; nullptr: no lobe
};
const std::vector<DiffuseModelInfo>& diffuseModels();
const std::vector<SpecularModelInfo>& specularModels();
const char* diffuseModelName(DiffuseModel m);    // throws gis::Error for a model without an entry
const char* specularModelName(SpecularModel m);

// evaluateBrdf() of brdf.glsl: f(l, v) for unit N, V, L; 0 when N.L <= 0.
glm::vec3 evaluateCpuBrdf(const CpuSurfaceBrdf& s, glm::vec3 N, glm::vec3 V, glm::vec3 L, DiffuseModel diffuse,
                          SpecularModel specular);

// The lobe in the plane of incidence: N = +Z, V at `viewAngle` radians from N (towards -X), L
// swept from -90 to +90 degrees (positive towards +X, the mirror side). f * N.L per component.
struct LobeSample {
    float angle = 0.0f;               // radians, of L from N
    glm::vec3 diffuse{0.0f}, specular{0.0f};
};
std::vector<LobeSample> brdfLobe(const CpuSurfaceBrdf& s, float viewAngle, DiffuseModel diffuse,
                                 SpecularModel specular, int samples = 181);

}  // namespace gis
