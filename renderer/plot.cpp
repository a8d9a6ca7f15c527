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

namespace {

bool overlaps(const LabelBox& a, const LabelBox& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

bool coversDisc(const LabelBox& b, double cx, double cy, double r) {
    const double nx = std::clamp(cx, double(b.x0), double(b.x1)), ny = std::clamp(cy, double(b.y0), double(b.y1));
    return (nx - cx) * (nx - cx) + (ny - cy) * (ny - cy) < r * r;
}

// Whether the segment passes through the box (sampled every pixel: the chart's lines are short).
bool crosses(const LabelBox& b, const Segment& s) {
    const int steps = std::max(1, int(std::hypot(s.x1 - s.x0, s.y1 - s.y0)));
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps, x = s.x0 + (s.x1 - s.x0) * t, y = s.y0 + (s.y1 - s.y0) * t;
        if (x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1) return true;
    }
    return false;
}

bool inside(const LabelBox& b, const LabelBox& bounds) {
    return b.x0 >= bounds.x0 && b.y0 >= bounds.y0 && b.x1 <= bounds.x1 && b.y1 <= bounds.y1;
}

// Positions around a point, nearest first: right, left, above, below, then the diagonals, at
// growing distances.
std::vector<LabelBox> labelCandidates(const LabelRequest& q) {
    std::vector<LabelBox> out;
    const int w = q.width, h = q.height;
    for (double d : {8.0, 16.0, 28.0, 44.0, 64.0, 90.0, 120.0, 160.0, 220.0}) {
        const double e = 0.7 * d;
        const double xy[8][2] = {{q.x + d, q.y - h / 2.0},     {q.x - d - w, q.y - h / 2.0},
                                 {q.x - w / 2.0, q.y - d - h}, {q.x - w / 2.0, q.y + d},
                                 {q.x + e, q.y - e - h},       {q.x + e, q.y + e},
                                 {q.x - e - w, q.y - e - h},   {q.x - e - w, q.y + e}};
        for (const auto& p : xy) {
            const int x0 = int(std::lround(p[0])), y0 = int(std::lround(p[1]));
            out.push_back({x0, y0, x0 + w, y0 + h});
        }
    }
    return out;
}

}  // namespace

std::vector<LabelBox> placeLabels(const std::vector<LabelRequest>& labels,
                                  const std::vector<std::pair<double, double>>& discs, double discRadius,
                                  LabelBox bounds, const std::vector<Segment>& lines) {
    constexpr int kHard = 1000;  // a covered point or label outweighs any number of crossed lines
    std::vector<LabelBox> placed;
    for (const LabelRequest& q : labels) {
        LabelBox best{};
        int bestConflicts = -1;
        for (const LabelBox& b : labelCandidates(q)) {
            if (!inside(b, bounds)) continue;
            int conflicts = 0;
            for (const auto& [x, y] : discs) conflicts += kHard * coversDisc(b, x, y, discRadius);
            for (const LabelBox& p : placed) conflicts += kHard * overlaps(b, p);
            for (const Segment& s : lines) conflicts += crosses(b, s);
            if (bestConflicts < 0 || conflicts < bestConflicts) best = b, bestConflicts = conflicts;
            if (conflicts == 0) break;
        }
        if (bestConflicts < 0) {  // no position fits the bounds: pinned inside them by its corner
            const int x0 = std::clamp(int(q.x), bounds.x0, std::max(bounds.x0, bounds.x1 - q.width));
            const int y0 = std::clamp(int(q.y), bounds.y0, std::max(bounds.y0, bounds.y1 - q.height));
            best = {x0, y0, x0 + q.width, y0 + q.height};
        }
        placed.push_back(best);
    }
    return placed;
}

namespace {

constexpr int kLabelHeight = 16;    // stb_easy_font at scale 2, with a pixel to spare
constexpr double kDiscRadius = 7.0;
constexpr double kDiscClearance = kDiscRadius + 2.0;

// Log axes over whole decades around the data (at least one each way): the grid, tick labels kept
// inside the image, the axis titles.
struct LogAxes {
    int left = 110, right = 0, top = 80, bottom = 0;
    double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
    double px(double x) const { return left + (std::log10(x) - xmin) / (xmax - xmin) * (right - left); }
    double py(double y) const { return bottom - (std::log10(y) - ymin) / (ymax - ymin) * (bottom - top); }
};

LogAxes drawLogAxes(Canvas& c, const std::vector<std::pair<double, double>>& xy, const std::string& title,
                    const std::string& xLabel, const std::string& yLabel) {
    const int width = c.image.width, height = c.image.height;
    LogAxes a;
    a.right = width - 30;
    a.bottom = height - 80;
    const int titleScale = Canvas::textWidth(title, 3) <= width - a.left - 10 ? 3 : 2;  // a long title fits
    c.text(a.left, 12, title, kBlack, titleScale);
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (const auto& [x, y] : xy) {
        xmin = std::min(xmin, std::log10(x)), xmax = std::max(xmax, std::log10(x));
        ymin = std::min(ymin, std::log10(y)), ymax = std::max(ymax, std::log10(y));
    }
    a.xmin = std::floor(xmin), a.xmax = std::max(std::ceil(xmax), a.xmin + 1);
    a.ymin = std::floor(ymin), a.ymax = std::max(std::ceil(ymax), a.ymin + 1);
    for (double d = a.xmin; d <= a.xmax + 1e-9; d += 1.0) {
        const double x = a.px(std::pow(10.0, d));
        c.line(x, a.top, x, a.bottom, 1, kGrey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, d));
        const int w = Canvas::textWidth(buf);
        c.text(std::clamp(int(x) - w / 2, 0, width - w - 2), a.bottom + 10, buf, kDark);
    }
    for (double d = a.ymin; d <= a.ymax + 1e-9; d += 1.0) {
        const double y = a.py(std::pow(10.0, d));
        c.line(a.left, y, a.right, y, 1, kGrey);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, d));
        c.text(std::max(0, a.left - 10 - Canvas::textWidth(buf)), std::clamp(int(y) - 7, 0, height - kLabelHeight), buf,
               kDark);
    }
    c.line(a.left, a.bottom, a.right, a.bottom, 2, kBlack);
    c.line(a.left, a.top, a.left, a.bottom, 2, kBlack);
    c.text(std::max(0, (a.left + a.right - Canvas::textWidth(xLabel)) / 2), a.bottom + 40, xLabel, kBlack);
    c.text(10, a.top - 26, yLabel, kBlack);
    return a;
}

// Labels beside their points (placeLabels), each in its colour; one placed away from its point is
// joined to it by a thin line.
struct ChartLabel {
    std::string text;
    Rgba colour;
    double x = 0.0, y = 0.0;  // the point it names, in pixels
};

void drawLabels(Canvas& c, const std::vector<ChartLabel>& labels, const std::vector<std::pair<double, double>>& discs,
                const std::vector<Segment>& lines, const LogAxes& a) {
    std::vector<LabelRequest> requests;
    for (const ChartLabel& l : labels) requests.push_back({l.x, l.y, Canvas::textWidth(l.text), kLabelHeight});
    const LabelBox bounds{a.left + 2, a.top - 4, c.image.width, a.bottom - 2};
    const std::vector<LabelBox> boxes = placeLabels(requests, discs, kDiscClearance, bounds, lines);
    for (size_t i = 0; i < boxes.size(); ++i) {
        const LabelBox& b = boxes[i];
        const ChartLabel& l = labels[i];
        const double nx = std::clamp(l.x, double(b.x0), double(b.x1)), ny = std::clamp(l.y, double(b.y0), double(b.y1));
        if (std::hypot(nx - l.x, ny - l.y) > kDiscClearance + 12.0) c.line(l.x, l.y, nx, ny, 1, l.colour);
    }
    for (const auto& [x, y] : discs) c.disc(x, y, kDiscRadius, kBlack);  // leader lines under the points
    for (size_t i = 0; i < boxes.size(); ++i) c.text(boxes[i].x0, boxes[i].y0 + 1, labels[i].text, labels[i].colour);
}

Rgba seriesColour(int series) { return kSeriesColors[size_t(std::max(series, 0)) % 8]; }

}  // namespace

ImageU8 drawTradeoffChart(const std::vector<ChartPoint>& points, const std::string& title, const std::string& xLabel,
                          const std::string& yLabel, int width, int height) {
    Canvas c(width, height, kWhite);
    std::vector<ChartPoint> pts;
    std::vector<std::pair<double, double>> xy;
    for (const ChartPoint& p : points)
        if (p.x > 0.0 && p.y > 0.0 && std::isfinite(p.x) && std::isfinite(p.y)) pts.push_back(p), xy.emplace_back(p.x, p.y);
    if (pts.empty()) {
        c.text(110, 12, title, kBlack, 3);
        c.text(110, height / 2, "no points with positive, finite time and error", kBlack);
        return c.image;
    }
    const LogAxes a = drawLogAxes(c, xy, title, xLabel, yLabel);
    const std::vector<size_t> front = paretoFront(pts);
    std::vector<Segment> stairs;  // the best error reachable within a budget
    for (size_t i = 1; i < front.size(); ++i) {
        const ChartPoint &p = pts[front[i - 1]], &q = pts[front[i]];
        stairs.push_back({a.px(p.x), a.py(p.y), a.px(q.x), a.py(p.y)});
        stairs.push_back({a.px(q.x), a.py(p.y), a.px(q.x), a.py(q.y)});
    }
    for (const Segment& s : stairs) c.line(s.x0, s.y0, s.x1, s.y1, 3, {120, 120, 120});
    std::vector<ChartLabel> labels;
    std::vector<std::pair<double, double>> at;
    for (const ChartPoint& p : pts) {
        labels.push_back({p.label, seriesColour(p.series), a.px(p.x), a.py(p.y)});
        at.emplace_back(labels.back().x, labels.back().y);
    }
    drawLabels(c, labels, at, stairs, a);
    for (const ChartLabel& l : labels) c.disc(l.x, l.y, kDiscRadius - 1.5, l.colour);
    c.text(a.right - Canvas::textWidth("grey staircase: Pareto front"), a.top - 26, "grey staircase: Pareto front", kDark);
    return c.image;
}

ImageU8 drawCurvesChart(const std::vector<ChartCurve>& curves, const std::string& title, const std::string& xLabel,
                        const std::string& yLabel, int width, int height) {
    Canvas c(width, height, kWhite);
    std::vector<ChartCurve> kept;
    std::vector<std::pair<double, double>> xy;
    for (const ChartCurve& curve : curves) {
        ChartCurve k{curve.label, {}, curve.series};
        for (const auto& [x, y] : curve.points)
            if (x > 0.0 && y > 0.0 && std::isfinite(x) && std::isfinite(y)) k.points.emplace_back(x, y), xy.emplace_back(x, y);
        if (!k.points.empty()) kept.push_back(k);
    }
    if (kept.empty()) {
        c.text(110, 12, title, kBlack, 3);
        c.text(110, height / 2, "no points with positive, finite time and error", kBlack);
        return c.image;
    }
    const LogAxes a = drawLogAxes(c, xy, title, xLabel, yLabel);
    std::vector<std::pair<double, double>> dots;
    std::vector<Segment> lines;
    for (const ChartCurve& k : kept) {
        for (size_t i = 1; i < k.points.size(); ++i) {
            lines.push_back({a.px(k.points[i - 1].first), a.py(k.points[i - 1].second), a.px(k.points[i].first),
                             a.py(k.points[i].second)});
            c.line(lines.back().x0, lines.back().y0, lines.back().x1, lines.back().y1, 2, seriesColour(k.series));
        }
        for (const auto& [x, y] : k.points) dots.emplace_back(a.px(x), a.py(y));
    }
    std::vector<ChartLabel> ends;  // each curve named at its last point
    for (const ChartCurve& k : kept)
        ends.push_back({k.label, seriesColour(k.series), a.px(k.points.back().first), a.py(k.points.back().second)});
    drawLabels(c, ends, dots, lines, a);
    size_t d = 0;
    for (const ChartCurve& k : kept)
        for (size_t i = 0; i < k.points.size(); ++i, ++d) c.disc(dots[d].first, dots[d].second, kDiscRadius - 1.5, seriesColour(k.series));
    return c.image;
}

ImageU8 stackImages(const std::vector<ImageU8>& images) {
    int width = 0, height = 0;
    for (const ImageU8& im : images) width = std::max(width, im.width), height += im.height;
    Canvas c(std::max(width, 1), std::max(height, 1), kWhite);
    int y = 0;
    for (const ImageU8& im : images) {
        c.blit(im, 0, y);
        y += im.height;
    }
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
