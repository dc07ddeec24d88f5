#include "eval/trajectory_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "common/error.h"
#include "common/tum_io.h"
#include "eval/colormap.h"
#include "eval/plot_axes.h"
#include "eval/statistics.h"
#include "eval/svg_document.h"

namespace depot::eval {
namespace {

// Page layout, pixels.
constexpr double kWidth = 1180.0;
constexpr double kLeft = 80.0;
constexpr double kViewsTop = 118.0;
constexpr double kViewSize = 420.0;
constexpr double kViewGap = 90.0;
constexpr double kColourBarLeft = kLeft + 2.0 * kViewSize + kViewGap + 50.0;
constexpr double kColourBarWidth = 18.0;
constexpr double kSeriesTop = kViewsTop + kViewSize + 80.0;
constexpr double kSeriesWidth = kColourBarLeft + kColourBarWidth - kLeft;
constexpr double kSeriesHeight = 190.0;
constexpr double kSeriesGap = 80.0;
constexpr double kBottomMargin = 60.0;

const char* const kReferenceColour = "#8c8c8c";
const char* const kNoValueColour = "#c8c8c8";
const char* const kSeriesColour = "#3b3b3b";

struct ColourScale {
  double lo = 0.0;
  double hi = 0.0;
  bool valid = false;
  std::string colour(double v) const {
    if (!valid || !std::isfinite(v)) return kNoValueColour;
    return viridis(hi > lo ? (v - lo) / (hi - lo) : 0.5);
  }
};

ColourScale colour_scale_of(const std::vector<double>& values) {
  ColourScale s;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (!s.valid) s.lo = s.hi = v;
    s.lo = std::min(s.lo, v);
    s.hi = std::max(s.hi, v);
    s.valid = true;
  }
  return s;
}

void check_plot(const TrajectoryPlot& plot) {
  if (plot.reference.empty() && plot.estimate.empty()) fail("plot", "no positions to draw");
  if (!plot.estimate_colour_values.empty() &&
      plot.estimate_colour_values.size() != plot.estimate.size()) {
    fail("plot", "one colour value per estimate position is needed");
  }
  for (const ErrorSeries& s : plot.series) {
    if (s.stamps.size() != s.values.size()) {
      fail("plot", "series '" + s.name + "' has different numbers of stamps and values");
    }
  }
}

using Project = std::function<Point2(const Eigen::Vector3d&)>;

AxisRange range_of(const TrajectoryPlot& plot, int axis) {
  AxisRange r{INFINITY, -INFINITY};
  for (const auto* list : {&plot.reference, &plot.estimate}) {
    for (const Eigen::Vector3d& p : *list) {
      r.lo = std::min(r.lo, p[axis]);
      r.hi = std::max(r.hi, p[axis]);
    }
  }
  return r;
}

void draw_view(SvgDocument& svg, const TrajectoryPlot& plot, const ColourScale& colours,
               double left, int vertical_axis, const std::string& title) {
  const PlotArea area{left, kViewsTop, kViewSize, kViewSize};
  AxisRange x, y;
  equal_aspect_ranges(area, range_of(plot, 0), range_of(plot, vertical_axis), 0.04, &x, &y);
  const PlotFrame frame(area, x, y);
  const double step = nice_step(std::max(x.span(), y.span()), 6);
  const Project project = [&](const Eigen::Vector3d& p) {
    return frame.to_pixel(p.x(), p[vertical_axis]);
  };

  frame.draw_background(svg, step, step);
  std::vector<Point2> reference;
  for (const Eigen::Vector3d& p : plot.reference) reference.push_back(project(p));
  svg.polyline(reference, {kReferenceColour, 1.5, "5,3"});

  const bool coloured = !plot.estimate_colour_values.empty();
  for (size_t k = 0; k + 1 < plot.estimate.size(); ++k) {
    const double value =
        coloured ? 0.5 * (plot.estimate_colour_values[k] + plot.estimate_colour_values[k + 1])
                 : NAN;
    svg.line(project(plot.estimate[k]), project(plot.estimate[k + 1]),
             {colours.colour(value), 2.2, ""});
  }
  if (!plot.reference.empty()) svg.circle(project(plot.reference.front()), 3.5, "#000000");

  const std::string v = vertical_axis == 1 ? "y" : "z";
  frame.draw_axes(svg, step, step, {"x (m)", v + " (m)", title});
}

void draw_colour_bar(SvgDocument& svg, const ColourScale& colours, const std::string& label) {
  const double top = kViewsTop;
  const double height = kViewSize;
  const Stroke outline{"#444444", 1.0, ""};
  if (!colours.valid) {
    svg.rect(kColourBarLeft, top, kColourBarWidth, height, kNoValueColour, &outline);
    return;
  }
  svg.vertical_gradient("error-colours", viridis_samples());
  svg.rect(kColourBarLeft, top, kColourBarWidth, height, "url(#error-colours)", &outline);

  TextStyle tick_text;
  tick_text.size = 11.0;
  const double right = kColourBarLeft + kColourBarWidth;
  const AxisRange range{colours.lo, colours.hi};
  auto bar_y = [&](double v) {
    return range.span() > 0.0 ? top + height - (v - range.lo) / range.span() * height
                              : top + 0.5 * height;
  };
  if (range.span() > 0.0) {
    const double step = nice_step(range.span(), 6);
    for (double v : ticks_within(range, step)) {
      svg.line({right, bar_y(v)}, {right + 5.0, bar_y(v)}, outline);
      svg.text({right + 8.0, bar_y(v) + 4.0}, tick_label(v, step), tick_text);
    }
  } else {
    svg.text({right + 8.0, bar_y(range.lo) + 4.0}, tick_label(range.lo, 1e-4), tick_text);
  }
  TextStyle label_text;
  label_text.size = 12.5;
  label_text.anchor = TextAnchor::kMiddle;
  label_text.rotate_deg = -90.0;
  svg.text({right + 62.0, top + 0.5 * height}, label, label_text);
}

void draw_legend(SvgDocument& svg, double y, bool has_gaps) {
  TextStyle text;
  text.size = 12.0;
  double x = kLeft;
  svg.line({x, y - 4.0}, {x + 30.0, y - 4.0}, {kReferenceColour, 1.5, "5,3"});
  svg.text({x + 36.0, y}, "ground truth", text);
  x += 140.0;
  const std::vector<std::string> samples = viridis_samples();
  for (size_t k = 0; k + 1 < samples.size(); k += 2) {
    svg.line({x + 3.0 * k, y - 4.0}, {x + 3.0 * (k + 2), y - 4.0}, {samples[k], 2.2, ""});
  }
  svg.text({x + 36.0, y}, "estimate (aligned), coloured by error", text);
  x += 290.0;
  if (has_gaps) {
    svg.line({x, y - 4.0}, {x + 30.0, y - 4.0}, {kNoValueColour, 2.2, ""});
    svg.text({x + 36.0, y}, "no value", text);
    x += 110.0;
  }
  svg.circle({x + 4.0, y - 4.0}, 3.5, "#000000");
  svg.text({x + 14.0, y}, "start", text);
}

struct Marker {
  const char* name;
  double value;
  const char* colour;
  const char* dash;
};

void draw_series(SvgDocument& svg, const ErrorSeries& series, double time_origin, double top) {
  const PlotArea area{kLeft, top, kSeriesWidth, kSeriesHeight};
  std::vector<double> finite;
  double t_max = 0.0;
  for (size_t k = 0; k < series.values.size(); ++k) {
    t_max = std::max(t_max, series.stamps[k] - time_origin);
    if (std::isfinite(series.values[k])) finite.push_back(series.values[k]);
  }
  const double v_max = finite.empty() ? 1.0 : *std::max_element(finite.begin(), finite.end());
  const AxisRange x = nice_range_from_zero(0.0, t_max, 10);
  const AxisRange y = nice_range_from_zero(0.0, v_max, 5);
  const PlotFrame frame(area, x, y);
  const double x_step = nice_step(x.span(), 10);
  const double y_step = nice_step(y.span(), 5);
  const std::string unit = " (" + series.unit + ")";

  frame.draw_background(svg, x_step, y_step);
  std::vector<Point2> line;
  for (size_t k = 0; k < series.values.size(); ++k) {
    if (!std::isfinite(series.values[k])) continue;
    line.push_back(frame.to_pixel(series.stamps[k] - time_origin, series.values[k]));
  }
  svg.polyline(line, {kSeriesColour, 1.2, ""});

  std::vector<Marker> markers;
  if (!finite.empty()) {
    const ErrorStatistics s = compute_statistics(finite);
    markers = {{"rmse", s.rmse, "#d62728", "6,3"},
               {"mean", s.mean, "#2ca02c", "2,2"},
               {"median", s.median, "#1f77b4", "8,3,2,3"}};
  }
  TextStyle legend_text;
  legend_text.size = 11.5;
  double legend_x = kLeft + kSeriesWidth - 3.0 * 115.0;
  for (const Marker& m : markers) {
    const double py = frame.to_pixel(0.0, m.value).y;
    svg.line({kLeft, py}, {kLeft + kSeriesWidth, py}, {m.colour, 1.4, m.dash});
    svg.line({legend_x, top - 12.0}, {legend_x + 24.0, top - 12.0}, {m.colour, 1.8, m.dash});
    svg.text({legend_x + 28.0, top - 8.0}, fmt::format("{} {:.4g}", m.name, m.value), legend_text);
    legend_x += 115.0;
  }
  frame.draw_axes(svg, x_step, y_step, {"time (s)", series.name + unit, ""});
  TextStyle title;
  title.size = 13.5;
  title.bold = true;
  svg.text({kLeft, top - 8.0}, series.name + " over time" + unit, title);
}

}  // namespace

std::string render_trajectory_plot_svg(const TrajectoryPlot& plot) {
  check_plot(plot);
  const auto n = static_cast<double>(plot.series.size());
  const double height =
      plot.series.empty() ? kViewsTop + kViewSize + kBottomMargin
                          : kSeriesTop + n * kSeriesHeight + (n - 1.0) * kSeriesGap + kBottomMargin;
  SvgDocument svg(kWidth, height);

  TextStyle title;
  title.size = 17.0;
  title.bold = true;
  svg.text({kLeft, 32.0}, plot.title, title);
  TextStyle subtitle;
  subtitle.size = 12.5;
  subtitle.colour = "#444444";
  svg.text({kLeft, 54.0}, plot.subtitle, subtitle);
  const ColourScale colours = colour_scale_of(plot.estimate_colour_values);
  const bool has_gaps =
      std::any_of(plot.estimate_colour_values.begin(), plot.estimate_colour_values.end(),
                  [](double v) { return !std::isfinite(v); });
  draw_legend(svg, 80.0, has_gaps || !colours.valid);
  draw_view(svg, plot, colours, kLeft, 1, "top view (x-y)");
  draw_view(svg, plot, colours, kLeft + kViewSize + kViewGap, 2, "side view (x-z)");
  draw_colour_bar(svg, colours, plot.colour_label);

  double time_origin = plot.time_origin;
  if (!std::isfinite(time_origin)) {
    time_origin = 0.0;
    for (const ErrorSeries& s : plot.series) {
      if (!s.stamps.empty()) {
        time_origin = s.stamps.front();
        break;
      }
    }
  }
  double top = kSeriesTop;
  for (const ErrorSeries& s : plot.series) {
    draw_series(svg, s, time_origin, top);
    top += kSeriesHeight + kSeriesGap;
  }
  return svg.str();
}

void write_trajectory_plot_svg(const std::string& path, const TrajectoryPlot& plot) {
  write_text_file_atomic(path, render_trajectory_plot_svg(plot));
}

}  // namespace depot::eval
