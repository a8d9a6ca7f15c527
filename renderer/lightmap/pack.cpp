#include "lightmap/pack.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <string>

#include "error.h"

namespace gis::lightmap::detail {
namespace {

// The top edge of what is packed so far, as segments from left to right. A rectangle goes where
// its top ends lowest (then leftmost), resting on the highest segment under it.
class Skyline {
public:
    Skyline(int width, int height) : width_(width), height_(height), segs_{{0, 0, width}} {}

    bool insert(glm::ivec2 size, glm::ivec2& at) {
        int bestTop = INT_MAX;
        for (size_t i = 0; i < segs_.size(); ++i) {
            const int x = segs_[i].x;
            if (x + size.x > width_) break;
            int y = 0;
            for (size_t j = i; j < segs_.size() && segs_[j].x < x + size.x; ++j) y = std::max(y, segs_[j].y);
            if (y + size.y > height_ || y + size.y >= bestTop) continue;
            bestTop = y + size.y;
            at = {x, y};
        }
        if (bestTop == INT_MAX) return false;
        raise(at.x, bestTop, size.x);
        return true;
    }

private:
    struct Seg {
        int x, y, w;
    };

    void raise(int x, int top, int w) {
        std::vector<Seg> next;
        bool inserted = false;
        for (const Seg& s : segs_) {
            const int s1 = s.x + s.w;
            if (s1 <= x) {
                next.push_back(s);
                continue;
            }
            if (!inserted) {
                if (s.x < x) next.push_back({s.x, s.y, x - s.x});
                next.push_back({x, top, w});
                inserted = true;
            }
            const int from = std::max(s.x, x + w);
            if (s1 > from) next.push_back({from, s.y, s1 - from});
        }
        segs_.clear();
        for (const Seg& s : next)
            if (!segs_.empty() && segs_.back().y == s.y)
                segs_.back().w += s.w;
            else
                segs_.push_back(s);
    }

    int width_, height_;
    std::vector<Seg> segs_;
};

// Packs what fits of `todo` (indices, in order) into atlas `atlas` of side `side`; returns the rest.
std::vector<size_t> fill(const std::vector<size_t>& todo, const std::vector<glm::ivec2>& sizes, int gutter,
                         int side, int atlas, Packing& out) {
    // The usable square starts `gutter` in from the border and each rectangle carries `gutter` on
    // its right and top, so neighbours and the far border stay `gutter` away too.
    Skyline sky(side - gutter, side - gutter);
    std::vector<size_t> rest;
    for (size_t i : todo) {
        glm::ivec2 at;
        if (sky.insert(sizes[i] + gutter, at))
            out.places[i] = {atlas, at + gutter};
        else
            rest.push_back(i);
    }
    return rest;
}

}  // namespace

Packing pack(const std::vector<glm::ivec2>& sizes, int gutter, int maxSize, int maxAtlases) {
    std::vector<size_t> order(sizes.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (sizes[a].y != sizes[b].y) return sizes[a].y > sizes[b].y;
        if (sizes[a].x != sizes[b].x) return sizes[a].x > sizes[b].x;
        return a < b;
    });
    double area = 0.0;
    int largest = 1;
    for (const glm::ivec2& s : sizes) {
        if (s.x + 2 * gutter > maxSize || s.y + 2 * gutter > maxSize)
            throw Error("a chart of " + std::to_string(s.x) + "x" + std::to_string(s.y) + " texels and its gutter of " +
                        std::to_string(gutter) + " do not fit in an atlas of maxAtlasSize " + std::to_string(maxSize));
        area += double(s.x + gutter) * double(s.y + gutter);
        largest = std::max({largest, s.x, s.y});
    }
    Packing out;
    out.places.resize(sizes.size());
    // Sides grow in steps of 1/16 (multiples of 4) from the area's square: a power of two would
    // leave up to three quarters of the atlas empty.
    auto roundUp4 = [](double v) { return int(std::ceil(v / 4.0)) * 4; };
    int side = std::min(maxSize, std::max({16, roundUp4(largest + 2.0 * gutter), roundUp4(std::sqrt(area) + gutter)}));
    for (;; side = std::min(maxSize, roundUp4(side * 1.0625))) {
        if (fill(order, sizes, gutter, side, 0, out).empty()) {
            out.atlasSizes = {side};
            return out;
        }
        if (side == maxSize) break;
    }
    std::vector<size_t> todo = order;
    for (int atlas = 0; atlas < maxAtlases && !todo.empty(); ++atlas) {
        todo = fill(todo, sizes, gutter, maxSize, atlas, out);
        out.atlasSizes.push_back(maxSize);
    }
    if (!todo.empty())
        throw Error("the charts need more than maxAtlases " + std::to_string(maxAtlases) + " atlases of maxAtlasSize " +
                    std::to_string(maxSize) + " (" + std::to_string(todo.size()) + " of " +
                    std::to_string(sizes.size()) + " charts left over)");
    return out;
}

}  // namespace gis::lightmap::detail
