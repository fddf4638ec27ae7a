#include "report/svg_chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace phongcl {

namespace {

// Plot area inside the document; the legend sits in the right margin.
constexpr double kLeft = 80, kTop = 50, kBottom = 60, kRight = 190;
constexpr double kFontSize = 11, kCharWidth = 6.4;  // label width estimate for overlap checks
constexpr std::array<const char*, 6> kPalette = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

std::string escape_xml(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

struct Tick {
  double value;
  std::string label;  // SVG text content (may hold a <tspan>); empty: a minor tick
};

// Maps data values to pixels along one axis and lists its ticks.
class Scale {
 public:
  Scale(const ChartAxis& axis, double data_min, double data_max, double pixel_from, double pixel_to)
      : log_(axis.log_scale), pixel_from_(pixel_from), pixel_to_(pixel_to) {
    if (log_) {
      // A tenth of a decade of room, so points near a decade do not sit on the frame.
      lo_ = std::floor(std::log10(data_min) - 0.1);
      hi_ = std::max(std::ceil(std::log10(data_max) + 0.1), lo_ + 1);
      const int decades = static_cast<int>(hi_ - lo_);
      const int every = decades > 8 ? (decades + 7) / 8 : 1;  // at most about eight labelled decades
      for (int k = static_cast<int>(lo_); k <= static_cast<int>(hi_); ++k) {
        if ((k - static_cast<int>(lo_)) % every == 0) ticks_.push_back({std::pow(10.0, k), decade_label(k)});
        if (every == 1 && k < hi_)
          for (int m = 2; m <= 9; ++m) ticks_.push_back({m * std::pow(10.0, k), ""});
      }
    } else {
      double span = data_max - data_min;
      if (span <= 0) span = data_min != 0 ? std::abs(data_min) * 0.2 : 1.0;
      const double step = nice_step(span / 5);
      lo_ = std::floor((data_min - 0.02 * span) / step) * step;
      hi_ = std::ceil((data_max + 0.02 * span) / step) * step;
      for (double v = lo_; v <= hi_ + step * 1e-6; v += step) {
        const double value = std::abs(v) < step * 1e-9 ? 0.0 : v;
        char text[32];
        std::snprintf(text, sizeof text, "%g", value);
        ticks_.push_back({value, text});
      }
    }
  }

  double pixel(double value) const {
    const double t = ((log_ ? std::log10(value) : value) - lo_) / (hi_ - lo_);
    return pixel_from_ + t * (pixel_to_ - pixel_from_);
  }
  const std::vector<Tick>& ticks() const { return ticks_; }

 private:
  static double nice_step(double rough) {
    const double magnitude = std::pow(10.0, std::floor(std::log10(rough)));
    for (double factor : {1.0, 2.0, 5.0})
      if (rough <= factor * magnitude) return factor * magnitude;
    return 10 * magnitude;
  }
  static std::string decade_label(int exponent) {
    if (exponent >= -2 && exponent <= 3) {
      char text[16];
      std::snprintf(text, sizeof text, "%g", std::pow(10.0, exponent));
      return text;
    }
    return "10<tspan dy=\"-5\" font-size=\"8\">" + std::to_string(exponent) + "</tspan>";
  }

  bool log_;
  double lo_ = 0, hi_ = 1, pixel_from_, pixel_to_;
  std::vector<Tick> ticks_;
};

struct Box {
  double x0, y0, x1, y1;
  // With a small gap, so neighbouring labels do not read as one.
  bool overlaps(const Box& other) const {
    constexpr double gap = 4;
    return x0 < other.x1 + gap && other.x0 < x1 + gap && y0 < other.y1 + gap && other.y0 < y1 + gap;
  }
};

// Places labels one by one at the first nearby spot that stays in the plot and clear of the
// obstacles (markers, lines) and the labels placed before it; falls back to the right of the point.
class LabelPlacer {
 public:
  LabelPlacer(Box plot, std::vector<Box> obstacles) : plot_(plot), taken_(std::move(obstacles)) {}

  std::string place(double px, double py, const std::string& label) {
    const double width = kCharWidth * static_cast<double>(label.size()), height = kFontSize;
    // Text anchored at (px + dx, py + dy): the renderer's real text width then only changes how
    // far the label reaches away from its point, never which point it seems to belong to.
    enum Anchor { start, middle, end };
    struct Spot { double dx, dy; Anchor anchor; };
    const std::array<Spot, 12> spots = {{{11, 4, start}, {-11, 4, end}, {0, -9, middle}, {0, 17, middle},
                                         {8, -8, start}, {8, 16, start}, {-8, -8, end}, {-8, 16, end},
                                         {8, 18, start}, {8, -12, start}, {0, -21, middle}, {0, 29, middle}}};
    auto box_of = [&](const Spot& spot) {
      const double x = px + spot.dx - (spot.anchor == middle ? width / 2 : spot.anchor == end ? width : 0);
      return Box{x, py + spot.dy - height, x + width, py + spot.dy + 2};
    };
    Spot chosen = spots.front();
    for (const Spot& spot : spots) {
      const Box box = box_of(spot);
      const bool inside = box.x0 >= plot_.x0 && box.x1 <= plot_.x1 && box.y0 >= plot_.y0 && box.y1 <= plot_.y1;
      if (inside && std::none_of(taken_.begin(), taken_.end(), [&](const Box& t) { return t.overlaps(box); })) {
        chosen = spot;
        break;
      }
    }
    taken_.push_back(box_of(chosen));
    static constexpr const char* anchor_names[] = {"start", "middle", "end"};
    return "<text class=\"label\" x=\"" + number(px + chosen.dx) + "\" y=\"" + number(py + chosen.dy) +
           "\" text-anchor=\"" + anchor_names[chosen.anchor] + "\">" + escape_xml(label) + "</text>\n";
  }

 private:
  Box plot_;
  std::vector<Box> taken_;
};

std::string marker(MarkerShape shape, const char* css_class, double x, double y, const std::string& color,
                   const std::string& tooltip) {
  const std::string title = tooltip.empty() ? "" : "<title>" + escape_xml(tooltip) + "</title>";
  const std::string paint = " fill=\"" + color + "\" stroke=\"white\" stroke-width=\"1\"";
  switch (shape) {
    case MarkerShape::circle:
      return "<circle class=\"" + std::string(css_class) + "\" cx=\"" + number(x) + "\" cy=\"" + number(y) + "\" r=\"5\"" + paint + ">" + title + "</circle>\n";
    case MarkerShape::square:
      return "<rect class=\"" + std::string(css_class) + "\" x=\"" + number(x - 4.5) + "\" y=\"" + number(y - 4.5) +
             "\" width=\"9\" height=\"9\"" + paint + ">" + title + "</rect>\n";
    case MarkerShape::diamond:
      return "<polygon class=\"" + std::string(css_class) + "\" points=\"" + number(x) + "," + number(y - 6) + " " + number(x + 6) + "," + number(y) +
             " " + number(x) + "," + number(y + 6) + " " + number(x - 6) + "," + number(y) + "\"" + paint + ">" + title +
             "</polygon>\n";
    case MarkerShape::none:
      return "";
  }
  return "";
}

void check_points(const Chart& chart) {
  bool any = false;
  for (const auto& series : chart.series) {
    for (const auto& p : series.points) {
      any = true;
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw std::invalid_argument("render_svg: series '" + series.name + "' has a non-finite point");
      if ((chart.x.log_scale && p.x <= 0) || (chart.y.log_scale && p.y <= 0))
        throw std::invalid_argument("render_svg: series '" + series.name + "' has a point <= 0 on a log axis");
    }
  }
  if (!any) throw std::invalid_argument("render_svg: the chart has no points");
}

}  // namespace

std::string render_svg(const Chart& chart) {
  check_points(chart);
  double x_min = INFINITY, x_max = -INFINITY, y_min = INFINITY, y_max = -INFINITY;
  for (const auto& series : chart.series) {
    for (const auto& p : series.points) {
      x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x);
      y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
    }
  }
  const Box plot{kLeft, kTop, chart.width - kRight, chart.height - kBottom};
  const Scale xs(chart.x, x_min, x_max, plot.x0, plot.x1);
  const Scale ys(chart.y, y_min, y_max, plot.y1, plot.y0);  // y grows upwards
  auto color_of = [&](std::size_t i) {
    return chart.series[i].color.empty() ? std::string(kPalette[i % kPalette.size()]) : chart.series[i].color;
  };

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(chart.width) + "\" height=\"" +
                    std::to_string(chart.height) + "\" viewBox=\"0 0 " + std::to_string(chart.width) + " " +
                    std::to_string(chart.height) + "\" font-family=\"sans-serif\" font-size=\"" + number(kFontSize) + "\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text class=\"title\" x=\"" + number((plot.x0 + plot.x1) / 2) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">" +
         escape_xml(chart.title) + "</text>\n";

  // Grid and ticks: minor ticks get a short mark only, major ones a grid line and a label.
  svg += "<g class=\"axes\" stroke=\"#888\" fill=\"none\">\n";
  for (const Tick& t : xs.ticks()) {
    const double x = xs.pixel(t.value);
    if (x < plot.x0 - 0.5 || x > plot.x1 + 0.5) continue;
    if (!t.label.empty()) svg += "<line x1=\"" + number(x) + "\" y1=\"" + number(plot.y0) + "\" x2=\"" + number(x) + "\" y2=\"" + number(plot.y1) + "\" stroke=\"#eee\"/>\n";
    svg += "<line x1=\"" + number(x) + "\" y1=\"" + number(plot.y1) + "\" x2=\"" + number(x) + "\" y2=\"" + number(plot.y1 + (t.label.empty() ? 3 : 6)) + "\"/>\n";
  }
  for (const Tick& t : ys.ticks()) {
    const double y = ys.pixel(t.value);
    if (y < plot.y0 - 0.5 || y > plot.y1 + 0.5) continue;
    if (!t.label.empty()) svg += "<line x1=\"" + number(plot.x0) + "\" y1=\"" + number(y) + "\" x2=\"" + number(plot.x1) + "\" y2=\"" + number(y) + "\" stroke=\"#eee\"/>\n";
    svg += "<line x1=\"" + number(plot.x0 - (t.label.empty() ? 3 : 6)) + "\" y1=\"" + number(y) + "\" x2=\"" + number(plot.x0) + "\" y2=\"" + number(y) + "\"/>\n";
  }
  svg += "<rect x=\"" + number(plot.x0) + "\" y=\"" + number(plot.y0) + "\" width=\"" + number(plot.x1 - plot.x0) +
         "\" height=\"" + number(plot.y1 - plot.y0) + "\"/>\n</g>\n";
  svg += "<g class=\"tick-labels\" fill=\"#333\">\n";
  for (const Tick& t : xs.ticks()) {
    const double x = xs.pixel(t.value);
    if (t.label.empty() || x < plot.x0 - 0.5 || x > plot.x1 + 0.5) continue;
    svg += "<text x=\"" + number(x) + "\" y=\"" + number(plot.y1 + 20) + "\" text-anchor=\"middle\">" + t.label + "</text>\n";
  }
  for (const Tick& t : ys.ticks()) {
    const double y = ys.pixel(t.value);
    if (t.label.empty() || y < plot.y0 - 0.5 || y > plot.y1 + 0.5) continue;
    svg += "<text x=\"" + number(plot.x0 - 9) + "\" y=\"" + number(y + 4) + "\" text-anchor=\"end\">" + t.label + "</text>\n";
  }
  svg += "</g>\n";
  svg += "<text class=\"axis-label\" x=\"" + number((plot.x0 + plot.x1) / 2) + "\" y=\"" + number(chart.height - 18.0) +
         "\" text-anchor=\"middle\" font-size=\"13\">" + escape_xml(chart.x.label) + "</text>\n";
  svg += "<text class=\"axis-label\" transform=\"translate(20," + number((plot.y0 + plot.y1) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\" font-size=\"13\">" + escape_xml(chart.y.label) + "</text>\n";

  // Lines under markers, markers under labels.
  // What labels must keep clear of: markers, and lines sampled every few pixels.
  std::vector<Box> obstacles;
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const ChartSeries& series = chart.series[i];
    if (series.line && series.points.size() > 1) {
      svg += "<polyline class=\"series-line\" fill=\"none\" stroke=\"" + color_of(i) + "\" stroke-width=\"1.5\" points=\"";
      for (const auto& p : series.points) svg += number(xs.pixel(p.x)) + "," + number(ys.pixel(p.y)) + " ";
      svg += "\"/>\n";
      for (std::size_t k = 1; k < series.points.size(); ++k) {
        const double x0 = xs.pixel(series.points[k - 1].x), y0 = ys.pixel(series.points[k - 1].y);
        const double x1 = xs.pixel(series.points[k].x), y1 = ys.pixel(series.points[k].y);
        const int steps = 1 + static_cast<int>(std::hypot(x1 - x0, y1 - y0) / 4);
        for (int t = 0; t <= steps; ++t) {
          const double x = x0 + (x1 - x0) * t / steps, y = y0 + (y1 - y0) * t / steps;
          obstacles.push_back({x - 1, y - 1, x + 1, y + 1});
        }
      }
    }
    if (series.marker != MarkerShape::none)
      for (const auto& p : series.points) obstacles.push_back({xs.pixel(p.x) - 6, ys.pixel(p.y) - 6, xs.pixel(p.x) + 6, ys.pixel(p.y) + 6});
  }
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const ChartSeries& series = chart.series[i];
    svg += "<g class=\"series\" data-name=\"" + escape_xml(series.name) + "\">\n";
    for (const auto& p : series.points) {
      char tooltip[64];
      std::snprintf(tooltip, sizeof tooltip, " (%g, %g)", p.x, p.y);
      svg += marker(series.marker, "point", xs.pixel(p.x), ys.pixel(p.y), color_of(i), p.label + tooltip);
    }
    svg += "</g>\n";
  }
  LabelPlacer placer(plot, obstacles);
  svg += "<g class=\"labels\" fill=\"#222\">\n";
  for (const auto& series : chart.series)
    for (const auto& p : series.points)
      if (!p.label.empty()) svg += placer.place(xs.pixel(p.x), ys.pixel(p.y), p.label);
  svg += "</g>\n";

  // Legend in the right margin: a marker or a line sample per named series.
  svg += "<g class=\"legend\">\n";
  double legend_y = plot.y0 + 10;
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const ChartSeries& series = chart.series[i];
    if (series.name.empty()) continue;
    const double x = plot.x1 + 18;
    if (series.line) svg += "<line x1=\"" + number(x - 8) + "\" y1=\"" + number(legend_y) + "\" x2=\"" + number(x + 8) + "\" y2=\"" + number(legend_y) + "\" stroke=\"" + color_of(i) + "\" stroke-width=\"1.5\"/>\n";
    svg += marker(series.marker, "legend-marker", x, legend_y, color_of(i), "");
    svg += "<text x=\"" + number(x + 14) + "\" y=\"" + number(legend_y + 4) + "\">" + escape_xml(series.name) + "</text>\n";
    legend_y += 20;
  }
  svg += "</g>\n</svg>\n";
  return svg;
}

}  // namespace phongcl
