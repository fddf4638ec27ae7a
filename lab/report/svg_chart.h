#pragma once
// A small handwritten SVG chart: several series of (x, y) points, each drawn as markers, a line
// through its points, or both; linear or log axes with ticks, grid and labels; point labels placed
// so they do not overlap each other or the markers; a legend and a title.
#include <string>
#include <vector>

namespace phongcl {

struct ChartAxis {
  std::string label;
  bool log_scale = false;
};

enum class MarkerShape { circle, square, diamond, none };

struct ChartPoint {
  double x = 0.0, y = 0.0;
  std::string label;  // drawn next to the point; empty: none
};

struct ChartSeries {
  std::string name;  // legend entry; empty: left out of the legend
  std::vector<ChartPoint> points;
  MarkerShape marker = MarkerShape::circle;
  bool line = false;   // connect the points in the order given
  std::string color;   // any SVG colour; empty: from a fixed palette by series index
};

struct Chart {
  std::string title;
  ChartAxis x, y;
  std::vector<ChartSeries> series;
  int width = 860, height = 540;  // pixels, legend included
};

// The chart as a standalone SVG document. Throws std::invalid_argument on a non-finite
// coordinate, a non-positive one on a log axis, or a chart without points.
std::string render_svg(const Chart& chart);

}  // namespace phongcl
