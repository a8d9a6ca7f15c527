// libFuzzer entry point: any input must either load or throw gis::Error with a one-line,
// non-empty message. Anything else (crash, sanitizer report, other exception, leak, timeout,
// huge allocation) is a finding.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        // No base directory: external URIs resolve against the working directory only (the
        // test runs in an empty folder), so inputs cannot reach the developer's files by
        // relative paths.
        gis::Scene s = gis::loadGltfMemory(data, size, "");
        (void)s.triangleCount();
    } catch (const gis::Error& e) {
        const char* m = e.what();
        if (!m || !*m || std::strchr(m, '\n')) {
            std::fprintf(stderr, "bad gis::Error message: '%s'\n", m ? m : "(null)");
            std::abort();
        }
    }
    return 0;
}
