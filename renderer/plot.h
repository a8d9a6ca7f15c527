// A tiny CPU canvas for the benchmark's figures (no plotting program needed): filled rectangles,
// thick lines, discs and bitmap text (stb_easy_font), the error-versus-milliseconds chart with its
// Pareto front, and labelled image grids.
#pragma once

#include <string>
#include <vector>

#include "image.h"

namespace gis {

struct Rgba {
    uint8_t r = 0, g = 0, b = 0, a = 255;
};

struct Canvas {
    Canvas(int width, int height, Rgba background);
    ImageU8 image;
    void fillRect(int x0, int y0, int x1, int y1, Rgba c);
    void disc(double cx, double cy, double radius, Rgba c);
    void line(double x0, double y0, double x1, double y1, double thickness, Rgba c);
    // Text with its top-left corner at (x, y); scale multiplies stb_easy_font's ~7 px glyphs.
    void text(int x, int y, const std::string& s, Rgba c, int scale = 2);
    static int textWidth(const std::string& s, int scale = 2);
    void blit(const ImageU8& src, int x, int y);
};

struct ChartPoint {
    std::string label;
    double x = 0.0, y = 0.0;   // both > 0: the axes are logarithmic
    int series = 0;            // colour index (e.g. the GI method)
};

// Points on the lower-left boundary: no other point is both faster and more accurate.
std::vector<size_t> paretoFront(const std::vector<ChartPoint>& points);

ImageU8 drawTradeoffChart(const std::vector<ChartPoint>& points, const std::string& title, const std::string& xLabel,
                          const std::string& yLabel, int width = 960, int height = 640);

// A line per series on log axes (e.g. error against GPU ms spent since a camera cut), dots at its
// points, its label at its last point.
struct ChartCurve {
    std::string label;
    std::vector<std::pair<double, double>> points;  // x, y > 0
    int series = 0;
};
ImageU8 drawCurvesChart(const std::vector<ChartCurve>& curves, const std::string& title, const std::string& xLabel,
                        const std::string& yLabel, int width = 960, int height = 640);

// Pixel boxes, half-open: [x0, x1) x [y0, y1).
struct LabelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
struct LabelRequest {
    double x = 0.0, y = 0.0;  // the point it names, in pixels
    int width = 0, height = 0;
};
struct Segment {
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};
// Where each label goes: the first of the positions around its point, nearest first, whose box
// lies inside `bounds` and covers no disc (every point drawn, its own included), no label placed
// before it and, where it can, no line. Where none is free, the position that covers the fewest
// discs and labels.
std::vector<LabelBox> placeLabels(const std::vector<LabelRequest>& labels,
                                  const std::vector<std::pair<double, double>>& discs, double discRadius,
                                  LabelBox bounds, const std::vector<Segment>& lines = {});

// Images one above the other on white, left-aligned.
ImageU8 stackImages(const std::vector<ImageU8>& images);

// Images side by side, `columns` per row, each with a caption line under it.
ImageU8 composeGrid(const std::vector<std::pair<std::string, ImageU8>>& tiles, int columns);

}  // namespace gis
