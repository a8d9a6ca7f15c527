#include "plot.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace gis {

namespace {
const Rgba kSeriesColors[] = {{31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {148, 103, 189},
                              {255, 127, 14}, {140, 86, 75}, {227, 119, 194}, {23, 190, 207}};
const Rgba kBlack{0, 0, 0}, kGrey{200, 200, 200}, kDark{90, 90, 90}, kWhite{255, 255, 255};
}  // namespace

Canvas::Canvas(int width, int height, Rgba bg) {
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * height * 4);
    for (size_t i = 0; i < image.rgba.size(); i += 4) {
        image.rgba[i] = bg.r;
        image.rgba[i + 1] = bg.g;
        image.rgba[i + 2] = bg.b;
        image.rgba[i + 3] = bg.a;
    }
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, Rgba c) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, image.width), y1 = std::min(y1, image.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
            p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
        }
}

void Canvas::disc(double cx, double cy, double r, Rgba c) {
    for (int y = int(std::floor(cy - r)); y <= int(std::ceil(cy + r)); ++y)
        for (int x = int(std::floor(cx - r)); x <= int(std::ceil(cx + r)); ++x)
            if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= r * r) fillRect(x, y, x + 1, y + 1, c);
}

void Canvas::line(double x0, double y0, double x1, double y1, double thickness, Rgba c) {
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, int(len * 2.0));
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        disc(x0 + (x1 - x0) * t, y0 + (y1 - y0) * t, 0.5 * thickness, c);
    }
}

void Canvas::text(int x, int y, const std::string& s, Rgba c, int scale) {
    static char buffer[99999];
    std::string copy = s;
    const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer, sizeof buffer);
    for (int q = 0; q < quads; ++q) {
        const float* v = reinterpret_cast<const float*>(buffer + q * 4 * 16);  // 4 vertices of 16 bytes
        const float* v2 = reinterpret_cast<const float*>(buffer + (q * 4 + 2) * 16);
        fillRect(x + int(v[0] * scale), y + int(v[1] * scale), x + int(v2[0] * scale), y + int(v2[1] * scale), c);
    }
}

int Canvas::textWidth(const std::string& s, int scale) {
    std::string copy = s;
    return stb_easy_font_width(copy.data()) * scale;
}

void Canvas::blit(const ImageU8& src, int x, int y) {
    for (int j = 0; j < src.height; ++j)
        for (int i = 0; i < src.width; ++i) {
            const int tx = x + i, ty = y + j;
            if (tx < 0 || ty < 0 || tx >= image.width || ty >= image.height) continue;
            std::copy_n(&src.rgba[(size_t(j) * src.width + i) * 4], 4, &image.rgba[(size_t(ty) * image.width + tx) * 4]);
        }
}

std::vector<size_t> paretoFront(const std::vector<ChartPoint>& points) {
    std::vector<size_t> order(points.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return points[a].x < points[b].x || (points[a].x == points[b].x && points[a].y < points[b].y);
    });
    std::vector<size_t> front;
    double best = INFINITY;
    for (size_t i : order)
        if (points[i].y < best) {
            front.push_back(i);
            best = points[i].y;
        }
    return front;
}

ImageU8 drawTradeoffChart(const std::vector<ChartPoint>& points, const std::string& title, const std::string& xLabel,
                          const std::string& yLabel, int width, int height) {
    Canvas c(width, height, kWhite);
    const int left = 110, right = width - 30, top = 80, bottom = height - 80;
    c.text(left, 12, title, kBlack, 3);
    std::vector<ChartPoint> pts;
    for (const ChartPoint& p : points)
        if (p.x > 0.0 && p.y > 0.0 && std::isfinite(p.x) && std::isfinite(p.y)) pts.push_back(p);
    if (pts.empty()) {
        c.text(left, height / 2, "no points with positive, finite time and error", kBlack);
        return c.image;
    }
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (const ChartPoint& p : pts) {
        xmin = std::min(xmin, std::log10(p.x)), xmax = std::max(xmax, std::log10(p.x));
        ymin = std::min(ymin, std::log10(p.y)), ymax = std::max(ymax, std::log10(p.y));
    }
    // Whole decades around the data, at least one decade wide.
    xmin = std::floor(xmin), xmax = std::max(std::ceil(xmax), xmin + 1);
    ymin = std::floor(ymin), ymax = std::max(std::ceil(ymax), ymin + 1);
    auto px = [&](double x) { return left + (std::log10(x) - xmin) / (xmax - xmin) * (right - left); };
    auto py = [&](double y) { return bottom - (std::log10(y) - ymin) / (ymax - ymin) * (bottom - top); };
    for (double d = xmin; d <= xmax + 1e-9; d += 1.0) {
        const double x = px(std::pow(10.0, d));
        c.line(x, top, x, bottom, 1, kGrey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, d));
        c.text(int(x) - Canvas::textWidth(buf) / 2, bottom + 10, buf, kDark);
    }
    for (double d = ymin; d <= ymax + 1e-9; d += 1.0) {
        const double y = py(std::pow(10.0, d));
        c.line(left, y, right, y, 1, kGrey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, d));
        c.text(left - 10 - Canvas::textWidth(buf), int(y) - 7, buf, kDark);
    }
    c.line(left, bottom, right, bottom, 2, kBlack);
    c.line(left, top, left, bottom, 2, kBlack);
    c.text((left + right - Canvas::textWidth(xLabel)) / 2, bottom + 40, xLabel, kBlack);
    c.text(10, top - 26, yLabel, kBlack);

    const std::vector<size_t> front = paretoFront(pts);
    for (size_t i = 1; i < front.size(); ++i) {  // staircase: the best error reachable within a budget
        const ChartPoint &a = pts[front[i - 1]], &b = pts[front[i]];
        c.line(px(a.x), py(a.y), px(b.x), py(a.y), 3, {120, 120, 120});
        c.line(px(b.x), py(a.y), px(b.x), py(b.y), 3, {120, 120, 120});
    }
    std::vector<std::array<int, 4>> placed;  // label boxes already drawn: later labels move down
    for (const ChartPoint& p : pts) {
        const Rgba col = kSeriesColors[size_t(std::max(p.series, 0)) % 8];
        c.disc(px(p.x), py(p.y), 7, kBlack);
        c.disc(px(p.x), py(p.y), 5.5, col);
        const int w = Canvas::textWidth(p.label), h = 16;
        int x = int(px(p.x)) + 10, y = int(py(p.y)) - 16;
        if (x + w > width) x = int(px(p.x)) - 10 - w;
        for (bool moved = true; moved;) {
            moved = false;
            for (const auto& b : placed)
                if (x < b[2] && x + w > b[0] && y < b[3] && y + h > b[1]) {
                    y = b[3] + 1;
                    moved = true;
                }
        }
        c.text(x, y, p.label, col);
        placed.push_back({x, y, x + w, y + h});
    }
    c.text(right - Canvas::textWidth("grey staircase: Pareto front"), top - 26, "grey staircase: Pareto front", kDark);
    return c.image;
}

ImageU8 composeGrid(const std::vector<std::pair<std::string, ImageU8>>& tiles, int columns) {
    if (tiles.empty()) return Canvas(1, 1, kWhite).image;
    columns = std::max(1, std::min(columns, int(tiles.size())));
    int tw = 0, th = 0;
    for (const auto& [label, img] : tiles) tw = std::max(tw, img.width), th = std::max(th, img.height);
    // Small renders are enlarged (nearest neighbour, whole factors) so captions fit under them.
    const int zoom = std::max(1, (200 + tw - 1) / std::max(tw, 1));
    tw *= zoom, th *= zoom;
    const int caption = 30, pad = 8;
    const int rows = (int(tiles.size()) + columns - 1) / columns;
    Canvas c(columns * (tw + pad) + pad, rows * (th + caption + pad) + pad, kWhite);
    for (size_t i = 0; i < tiles.size(); ++i) {
        const int x = pad + int(i % columns) * (tw + pad), y = pad + int(i / columns) * (th + caption + pad);
        const ImageU8& src = tiles[i].second;
        ImageU8 big;
        big.width = src.width * zoom;
        big.height = src.height * zoom;
        big.rgba.resize(size_t(big.width) * big.height * 4);
        for (int j = 0; j < big.height; ++j)
            for (int k = 0; k < big.width; ++k)
                std::copy_n(&src.rgba[(size_t(j / zoom) * src.width + k / zoom) * 4], 4,
                            &big.rgba[(size_t(j) * big.width + k) * 4]);
        c.blit(big, x, y);
        // Caption: first line up to "  " (two spaces), the rest on the second line.
        const std::string& label = tiles[i].first;
        const size_t split = label.find("  ");
        c.text(x + 2, y + th + 4, label.substr(0, split), kBlack, 1);
        if (split != std::string::npos) c.text(x + 2, y + th + 16, label.substr(split + 2), kDark, 1);
    }
    return c.image;
}

}  // namespace gis
