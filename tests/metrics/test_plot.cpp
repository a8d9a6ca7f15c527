// The bench's charts (renderer/plot.*): labels never cover a point that is not theirs, and every
// tick label lies inside the image (issue #42: "hddagi/low" sat far from its point, the right-most
// tick was clipped).
#include <gtest/gtest.h>

#include <cmath>

#include "plot.h"

namespace gis::test {
namespace {

bool covers(const LabelBox& b, double x, double y, double r) {
    const double nx = std::fmin(std::fmax(x, b.x0), b.x1), ny = std::fmin(std::fmax(y, b.y0), b.y1);
    return std::hypot(nx - x, ny - y) < r;
}

TEST(Plot, LabelsNeverCoverAPointNotTheirs) {
    // A crowded cluster (a method's presets at nearly the same cost and error) beside open space.
    std::vector<std::pair<double, double>> points;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) points.emplace_back(400.0 + 14.0 * i, 300.0 + 12.0 * j);
    points.emplace_back(150.0, 120.0);
    points.emplace_back(880.0, 560.0);  // near the corner: its label must turn inwards
    std::vector<LabelRequest> requests;
    for (const auto& [x, y] : points) requests.push_back({x, y, 110, 16});
    const LabelBox bounds{110, 76, 960, 558};
    const double radius = 9.0;
    const std::vector<LabelBox> boxes = placeLabels(requests, points, radius, bounds);
    ASSERT_EQ(boxes.size(), points.size());
    for (size_t i = 0; i < boxes.size(); ++i) {
        const LabelBox& b = boxes[i];
        EXPECT_TRUE(b.x0 >= bounds.x0 && b.y0 >= bounds.y0 && b.x1 <= bounds.x1 && b.y1 <= bounds.y1) << i;
        for (size_t k = 0; k < points.size(); ++k)
            EXPECT_FALSE(covers(b, points[k].first, points[k].second, radius)) << "label " << i << " covers point " << k;
        for (size_t k = 0; k < i; ++k)
            EXPECT_FALSE(b.x0 < boxes[k].x1 && boxes[k].x0 < b.x1 && b.y0 < boxes[k].y1 && boxes[k].y0 < b.y1)
                << "labels " << k << " and " << i << " overlap";
    }
    // The lone point's label sits right beside it, not pushed away.
    const LabelBox& lone = boxes[16];
    EXPECT_LT(std::fabs(lone.x0 - 150.0) + std::fabs((lone.y0 + lone.y1) / 2.0 - 120.0), 24.0);
}

TEST(Plot, EveryTickLabelIsInsideTheImage) {
    // Times up to 5e4 ms: the axis ends at 1e5, whose tick label is centred on the plot's right edge.
    const std::vector<ChartPoint> points{{"a", 0.5, 0.3, 0}, {"b", 5e4, 0.02, 1}};
    const ImageU8 chart = drawTradeoffChart(points, "t", "x", "y", 480, 320);
    for (int column : {0, chart.width - 1})
        for (int y = 0; y < chart.height; ++y) {
            const uint8_t* p = &chart.rgba[(size_t(y) * chart.width + column) * 4];
            ASSERT_TRUE(p[0] == 255 && p[1] == 255 && p[2] == 255) << "column " << column << " row " << y << " is drawn on";
        }
    const ImageU8 curves = drawCurvesChart({{"c", {{1.0, 0.5}, {3e4, 0.05}}, 0}}, "t", "x", "y", 480, 320);
    for (int y = 0; y < curves.height; ++y) {
        const uint8_t* p = &curves.rgba[(size_t(y) * curves.width + curves.width - 1) * 4];
        ASSERT_TRUE(p[0] == 255 && p[1] == 255 && p[2] == 255) << "row " << y;
    }
}

}  // namespace
}  // namespace gis::test
