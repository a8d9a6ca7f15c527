#include "lightmap/seams.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace gis::lightmap {

namespace {
using EndKey = std::array<uint32_t, 6>;  // a vertex's position and normal, bit for bit

EndKey endKey(const SeamVertex& v) {
    EndKey k;
    const float f[6] = {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z};
    std::memcpy(k.data(), f, sizeof f);
    return k;
}

struct Side {
    uint32_t from, to;  // vertices, in the edge key's order
};

bool samePlace(const SeamVertex& a, const SeamVertex& b) {
    return a.layer == b.layer && glm::all(glm::lessThan(glm::abs(a.texel - b.texel), glm::vec2(1e-4f)));
}

// A side's taps at a point: the texels with light of their own in its bilinear footprint, with
// their weights renormalised (the lookup's, apply.frag).
struct Taps {
    size_t at[4];
    float weight[4];
    int count = 0;
};

Taps tapsAt(const TexelImage& image, glm::vec2 texel, int layer) {
    Taps t;
    const glm::vec2 st = texel - 0.5f;
    const glm::ivec2 corner = glm::ivec2(glm::floor(st));
    const glm::vec2 f = st - glm::floor(st);
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const glm::ivec2 offset(k & 1, k >> 1);
        const glm::ivec2 p = glm::clamp(corner + offset, glm::ivec2(0), glm::ivec2(image.side - 1));
        const size_t at = ((size_t(layer) * size_t(image.side) + size_t(p.y)) * size_t(image.side) + size_t(p.x)) * 4;
        const float w = (offset.x ? f.x : 1.0f - f.x) * (offset.y ? f.y : 1.0f - f.y);
        if (image.rgba[at + 3] != 1.0f || !(w > 0.0f)) continue;
        t.at[t.count] = at;
        t.weight[t.count++] = w;
        sum += w;
    }
    for (int i = 0; i < t.count; ++i) t.weight[i] /= sum;
    return t;
}

glm::vec3 read(const TexelImage& image, const Taps& t) {
    glm::vec3 v(0.0f);
    for (int i = 0; i < t.count; ++i)
        v += t.weight[i] * glm::vec3(image.rgba[t.at[i]], image.rgba[t.at[i] + 1], image.rgba[t.at[i] + 2]);
    return v;
}

void move(TexelImage& image, const Taps& t, glm::vec3 by) {
    for (int i = 0; i < t.count; ++i)
        for (int c = 0; c < 3; ++c) image.rgba[t.at[i] + size_t(c)] += t.weight[i] * by[c];
}
}  // namespace

std::vector<SeamPoint> findSeams(const std::vector<SeamVertex>& vertices, const std::vector<uint32_t>& indices,
                                 float perTexel) {
    std::map<std::array<uint32_t, 12>, std::vector<Side>> edges;
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = indices[t + size_t(e)], b = indices[t + size_t((e + 1) % 3)];
            EndKey ka = endKey(vertices[a]), kb = endKey(vertices[b]);
            if (kb < ka) std::swap(ka, kb), std::swap(a, b);
            if (ka == kb) continue;  // a degenerate edge
            std::array<uint32_t, 12> key;
            std::copy(ka.begin(), ka.end(), key.begin());
            std::copy(kb.begin(), kb.end(), key.begin() + 6);
            edges[key].push_back({a, b});
        }
    std::vector<SeamPoint> points;
    for (const auto& [key, sides] : edges)
        for (size_t s = 1; s < sides.size(); ++s) {
            const SeamVertex &a0 = vertices[sides[0].from], &a1 = vertices[sides[0].to];
            const SeamVertex &b0 = vertices[sides[s].from], &b1 = vertices[sides[s].to];
            if (samePlace(a0, b0) && samePlace(a1, b1)) continue;  // one chart: the lookup is continuous
            if (a0.unstitched || a1.unstitched || b0.unstitched || b1.unstitched) continue;
            const float texels = std::max(glm::length(a1.texel - a0.texel), glm::length(b1.texel - b0.texel));
            const int n = std::max(2, int(std::ceil(texels * perTexel)));
            for (int i = 0; i < n; ++i) {
                const float u = (float(i) + 0.5f) / float(n);
                points.push_back({glm::mix(a0.texel, a1.texel, u), glm::mix(b0.texel, b1.texel, u), a0.layer, b0.layer});
            }
        }
    return points;
}

bool lookUp(const TexelImage& image, glm::vec2 texel, int layer, glm::vec3& out) {
    const Taps t = tapsAt(image, texel, layer);
    out = read(image, t);
    return t.count > 0;
}

namespace {
using Rows = std::vector<std::pair<Taps, Taps>>;  // each point's equation read(a) - read(b) = 0

std::vector<glm::vec3> residuals(const TexelImage& image, const Rows& rows) {  // A x
    std::vector<glm::vec3> r(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) r[i] = read(image, rows[i].first) - read(image, rows[i].second);
    return r;
}

// A^T y, added to `image`'s texels scaled by `scale`.
void addTransposed(TexelImage& image, const Rows& rows, const std::vector<glm::vec3>& y, float scale) {
    for (size_t i = 0; i < rows.size(); ++i) {
        move(image, rows[i].first, scale * y[i]);
        move(image, rows[i].second, -scale * y[i]);
    }
}

// The largest difference between two sides, over the mean value along the seams.
float relativeGap(const TexelImage& image, const Rows& rows) {
    float worst = 0.0f, sum = 0.0f;
    for (const auto& [a, b] : rows) {
        const glm::vec3 va = read(image, a), vb = read(image, b);
        worst = std::max(worst, glm::length(va - vb));
        sum += 0.5f * glm::length(va + vb);
    }
    return sum > 0.0f ? worst / (sum / float(rows.size())) : 0.0f;
}

float dot3(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, int c) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += double(a[i][c]) * double(b[i][c]);
    return float(sum);
}
}  // namespace

// The least change x - x0 with A x = 0 is -A^T l, where (A A^T) l = A x0: conjugate gradients on
// that system (one per channel, all at once), A A^T applied as A of A^T through a scratch image
// holding only the rows' texels.
StitchGaps stitchSeams(const std::vector<SeamPoint>& points, TexelImage& image, int iterations, bool light) {
    Rows rows;
    for (const SeamPoint& p : points) {
        Taps a = tapsAt(image, p.a, p.layerA), b = tapsAt(image, p.b, p.layerB);
        if (a.count && b.count) rows.push_back({a, b});
    }
    const float before = relativeGap(image, rows);
    std::vector<glm::vec3> r = residuals(image, rows), direction = r, lambda(rows.size(), glm::vec3(0.0f));
    TexelImage scratch{std::vector<float>(image.rgba.size(), 0.0f), image.side, image.layers};
    glm::vec3 rr(dot3(r, r, 0), dot3(r, r, 1), dot3(r, r, 2));
    for (int it = 0; it < iterations && rr.x + rr.y + rr.z > 0.0f; ++it) {
        for (const auto& [a, b] : rows)  // clear the rows' texels, then A^T p into them
            for (const Taps* t : {&a, &b})
                for (int k = 0; k < t->count; ++k) std::fill_n(&scratch.rgba[t->at[k]], 3, 0.0f);
        addTransposed(scratch, rows, direction, 1.0f);
        const std::vector<glm::vec3> q = residuals(scratch, rows);
        glm::vec3 next(0.0f);
        for (int c = 0; c < 3; ++c) {
            const float pq = dot3(direction, q, c);
            const float alpha = pq > 0.0f ? rr[c] / pq : 0.0f;
            for (size_t i = 0; i < rows.size(); ++i) lambda[i][c] += alpha * direction[i][c], r[i][c] -= alpha * q[i][c];
            next[c] = dot3(r, r, c);
            const float beta = rr[c] > 0.0f ? next[c] / rr[c] : 0.0f;
            for (size_t i = 0; i < rows.size(); ++i) direction[i][c] = r[i][c] + beta * direction[i][c];
        }
        rr = next;
    }
    addTransposed(image, rows, lambda, -1.0f);
    if (light)  // a move never makes light negative
        for (const auto& [a, b] : rows)
            for (const Taps* t : {&a, &b})
                for (int k = 0; k < t->count; ++k)
                    for (size_t c = 0; c < 3; ++c) image.rgba[t->at[k] + c] = std::max(image.rgba[t->at[k] + c], 0.0f);
    return {before, relativeGap(image, rows)};
}

}  // namespace gis::lightmap
