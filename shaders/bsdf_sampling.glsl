// Drawing a direction from a surface's BSDF, and its density: the path tracer's bounces and MIS,
// and ReSTIR DI's BSDF candidates. A mixture of the cosine-weighted diffuse lobe and GGX's visible
// normals (Heitz 2018, "Sampling the GGX distribution of visible normals"), reflected.
// Needs brdf.glsl, random.glsl and sampling.glsl.
#ifndef BSDF_SAMPLING_GLSL
#define BSDF_SAMPLING_GLSL

// Smith G1 for GGX.
float smithG1(float NoV, float alpha) {
    float a2 = alpha * alpha;
    return 2.0 * NoV / max(NoV + sqrt(a2 + (1.0 - a2) * NoV * NoV), 1e-8);
}

// Visible-normal sampling of GGX (Heitz 2018), in the local frame where the normal is +Z.
vec3 sampleGgxVisibleNormal(vec3 v, float alpha, vec2 u) {
    vec3 vh = normalize(vec3(alpha * v.x, alpha * v.y, v.z));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x), phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 1e-6)));
}

// Probability of choosing the specular lobe when sampling a direction.
float specularChoice(SurfaceBrdf brdf, bool hasSpecular, float NoV) {
    if (!hasSpecular) return 0.0;
    float diff = luminance(brdf.diffuseColor);
    if (diff <= 0.0) return 1.0;  // a metal: the specular lobe is all there is
    float spec = luminance(fresnelSchlick(brdf.f0, brdf.f90, NoV));
    // Never below 10% either way, so neither lobe's samples become rare enough to spike.
    return clamp(spec / (spec + diff), 0.1, 0.9);
}

// Solid-angle density of sampling L (cosine-weighted diffuse + GGX visible normals, mixed).
float bsdfPdf(SurfaceBrdf brdf, vec3 N, vec3 V, vec3 L, float pSpecular) {
    float NoL = dot(N, L);
    if (NoL <= 0.0) return 0.0;
    float pdf = (1.0 - pSpecular) * NoL * INV_PI;
    if (pSpecular > 0.0) {
        // The BRDF's own GGX term and geometry (brdf.glsl), so the density matches what is evaluated.
        BrdfGeometry g = brdfGeometry(N, V, L);
        float alpha = brdf.roughness * brdf.roughness;
        pdf += pSpecular * smithG1(g.NoV, alpha) * distributionGgx(g, alpha) / (4.0 * g.NoV);
    }
    return pdf;
}

// A direction above both the shading normal N and the geometric normal Ng, or false.
bool sampleBsdf(SurfaceBrdf brdf, vec3 N, vec3 Ng, vec3 V, float pSpecular, inout Rng rng, out vec3 L,
                out bool specularLobe) {
    vec2 u = nextFloat2(rng);
    specularLobe = nextFloat(rng) < pSpecular;
    if (specularLobe) {
        vec3 t, b;
        orthonormalBasis(N, t, b);
        vec3 vLocal = vec3(dot(V, t), dot(V, b), max(dot(V, N), MIN_N_DOT_V));
        float alpha = brdf.roughness * brdf.roughness;
        vec3 h = sampleGgxVisibleNormal(normalize(vLocal), alpha, u);
        vec3 H = t * h.x + b * h.y + N * h.z;
        L = reflect(-V, H);
    } else {
        L = cosineDirection(N, u);
    }
    return dot(L, N) > 0.0 && dot(L, Ng) > 0.0;
}

#endif
