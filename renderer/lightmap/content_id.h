// FNV-1a, 64 bits, over bytes: a content id for the lightmap's caches (the atlas's hash, the bake's
// cache key), not a defence against forgery.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace gis::lightmap {

struct ContentId {
    uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t n) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    }
    // A string and its end, so "ab" + "c" and "a" + "bc" differ.
    void add(const std::string& s) { add(s.data(), s.size()), add("", 1); }
    template <typename T>
    void value(const T& v) { add(&v, sizeof v); }
    template <typename T>
    void vec(const std::vector<T>& v) {
        const uint64_t n = v.size();
        add(&n, sizeof n);
        if (n) add(v.data(), n * sizeof(T));
    }
    std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
        return text;
    }
};

}  // namespace gis::lightmap
