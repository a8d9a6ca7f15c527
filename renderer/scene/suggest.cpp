#include <algorithm>
#include <vector>

#include "scene/scene_lighting.h"

namespace gis {

namespace {

// Optimal string alignment distance (Levenshtein plus adjacent transposition, so "vtc" is one
// edit from "vct"): a typo's usual shapes each cost one.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i)
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[a.size()][b.size()];
}

}  // namespace

std::string didYouMean(const std::string& given, const std::vector<std::string>& candidates) {
    if (given.size() > 200) return "";
    // Within a third of the word (at least one edit), or the word is a prefix of exactly one candidate.
    std::string best;
    size_t bestDistance = std::max<size_t>(1, given.size() / 3) + 1;
    for (const std::string& c : candidates) {
        const size_t dist = editDistance(given, c);
        if (dist < bestDistance) best = c, bestDistance = dist;
    }
    if (best.empty() && !given.empty()) {
        size_t prefixed = 0;
        for (const std::string& c : candidates)
            if (c.rfind(given, 0) == 0) best = c, ++prefixed;
        if (prefixed != 1) best.clear();
    }
    return best.empty() ? "" : "did you mean '" + best + "'? ";
}

}  // namespace gis
