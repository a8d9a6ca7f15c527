// libFuzzer entry point for Radiance .hdr environment maps (renderer/environment.cpp): any input
// must either decode or throw gis::Error with a one-line, non-empty message; a map that decodes
// must hold the promises the renderer relies on (docs/hardening.md): width x height texels, each
// finite, non-negative and at most kMaxRadiance, and an SH projection and sampling CDF without inf
// or NaN. Anything else (crash, sanitizer report, other exception, broken promise, timeout, huge
// allocation) is a finding.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "environment.h"
#include "scene/limits.h"
#include "scene/scene.h"

namespace {

void broken(const char* promise) {
    std::fprintf(stderr, "broken promise: %s\n", promise);
    std::abort();
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    gis::EnvironmentMap map;
    try {
        map = gis::decodeEnvironmentMap(std::string(reinterpret_cast<const char*>(data), size), "fuzz.hdr");
    } catch (const gis::Error& e) {
        const char* m = e.what();
        if (!m || !*m || std::strchr(m, '\n')) broken("one-line gis::Error");
        return 0;
    }
    if (map.width < 1 || map.height < 1 || map.texels.size() != size_t(map.width) * size_t(map.height))
        broken("width x height texels");
    for (const glm::vec3& t : map.texels)
        if (!finite(t) || t.x < 0.0f || t.y < 0.0f || t.z < 0.0f || std::max({t.x, t.y, t.z}) > gis::kMaxRadiance)
            broken("texels finite, non-negative and at most kMaxRadiance");
    // The projection and the sampler are what the renderer makes of the map; small maps keep the
    // fuzzer fast (their cost is the texel count's, Environment.ShProjectionOfANarrowMapIsQuickAndRight).
    if (map.texels.size() <= 4096) {
        for (const glm::vec3& c : gis::projectSh9(map))
            if (!finite(c)) broken("finite SH projection");
        const gis::EnvironmentSampler sampler(map);
        if (!std::isfinite(sampler.marginalCdf().back())) broken("finite sampling CDF");
    }
    return 0;
}
