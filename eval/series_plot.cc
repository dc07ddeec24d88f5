#include "eval/series_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/error.h"
#include "eval/plot_axes.h"
#include "eval/svg_document.h"

namespace depot::eval {
namespace {

constexpr double kWidth = 670, kHeight = 400;
constexpr double kLeft = 78, kRight = 180, kTop = 34, kBottom = 58;

bool parse_number(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(*value);
}

std::string log_tick_label(int exponent) {
  if (exponent >= 0) return fmt::format("{:.0f}", std::pow(10.0, exponent));
  return fmt::format("{:.{}f}", std::pow(10.0, exponent), -exponent);
}

void draw_marker(SvgDocument& svg, Point2 at, const PlotSeries& series) {
  if (series.marker == PlotMarker::kSquare)
    svg.rect(at.x - 3.5, at.y - 3.5, 7, 7, series.colour);
  else
    svg.circle(at, 3.5, series.colour);
}

}  // namespace

std::string series_colour(size_t index) {
  static const char* colours[] = {"#d62728", "#1f77b4", "#ff7f0e", "#2ca02c",
                                  "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  return colours[index % 8];
}

std::string render_series_plot_svg(const SeriesPlot& plot) {
  const size_t n = plot.x_levels.size();
  if (n == 0) fail("series plot '" + plot.title + "'", "no x levels");
  for (const auto& s : plot.series)
    if (s.mean.size() != n || s.std.size() != n)
      fail("series plot '" + plot.title + "'", "series '" + s.name + "' has the wrong length");

  // x: numeric positions when all levels are numbers, else 0..n-1.
  std::vector<double> xs(n);
  bool numeric = true;
  for (size_t i = 0; i < n; ++i) numeric = numeric && parse_number(plot.x_levels[i], &xs[i]);
  if (!numeric)
    for (size_t i = 0; i < n; ++i) xs[i] = static_cast<double>(i);
  double x_lo = *std::min_element(xs.begin(), xs.end());
  double x_hi = *std::max_element(xs.begin(), xs.end());
  if (x_hi - x_lo < 1e-12) x_lo -= 0.5, x_hi += 0.5;
  const double x_pad = 0.06 * (x_hi - x_lo);
  x_lo -= x_pad, x_hi += x_pad;

  // y: data extent including error bars.
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : plot.series)
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.mean[i])) continue;
      const double e = std::isfinite(s.std[i]) ? s.std[i] : 0.0;
      const double a = plot.log_y ? s.mean[i] : s.mean[i] - e;
      if (!plot.log_y || a > 0) lo = std::min(lo, a);
      hi = std::max(hi, s.mean[i] + e);
    }
  for (const PlotThreshold& t : plot.thresholds) {
    if (!plot.log_y || t.y > 0) lo = std::min(lo, t.y);
    hi = std::max(hi, t.y);
  }
  AxisRange y;
  if (plot.log_y) {
    if (!std::isfinite(lo) || lo <= 0)
      fail("series plot '" + plot.title + "'", "no positive value for a log axis");
    y = {std::floor(std::log10(lo)), std::ceil(std::log10(hi))};
    if (y.hi - y.lo < 1) y.hi = y.lo + 1;
  } else if (plot.y_lo < plot.y_hi) {
    y = {plot.y_lo, plot.y_hi};
  } else {
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    y = nice_range_from_zero(std::min(lo, 0.0), hi, 5);
  }
  auto to_y = [&](double v) {
    const double t = plot.log_y ? std::log10(std::max(v, 1e-300)) : v;
    return kTop + (kHeight - kTop - kBottom) * (1.0 - (t - y.lo) / y.span());
  };
  auto to_x = [&](double v) {
    return kLeft + (kWidth - kLeft - kRight) * (v - x_lo) / (x_hi - x_lo);
  };
  const double bottom = kHeight - kBottom, right = kWidth - kRight;

  SvgDocument svg(kWidth, kHeight);
  const Stroke grid{"#e3e3e3", 1.0, ""}, frame{"#555555", 1.0, ""};
  TextStyle tick;
  tick.size = 11;
  tick.anchor = TextAnchor::kEnd;
  if (plot.log_y) {
    for (int e = static_cast<int>(y.lo); e <= static_cast<int>(y.hi); ++e) {
      const double py = to_y(std::pow(10.0, e));
      svg.line({kLeft, py}, {right, py}, grid);
      svg.text({kLeft - 6, py + 4}, log_tick_label(e), tick);
      for (int m = 2; m < 10 && e < static_cast<int>(y.hi); ++m) {
        const double pm = to_y(m * std::pow(10.0, e));
        svg.line({kLeft, pm}, {kLeft + 4, pm}, frame);
      }
    }
  } else {
    const double step = nice_step(y.span(), 5);
    for (double v : ticks_within(y, step)) {
      svg.line({kLeft, to_y(v)}, {right, to_y(v)}, grid);
      svg.text({kLeft - 6, to_y(v) + 4}, tick_label(v, step), tick);
    }
  }
  tick.anchor = TextAnchor::kMiddle;
  for (size_t i = 0; i < n; ++i) {
    const double px = to_x(xs[i]);
    svg.line({px, bottom}, {px, bottom + 5}, frame);
    svg.text({px, bottom + 18}, plot.x_levels[i], tick);
  }
  svg.rect(kLeft, kTop, right - kLeft, bottom - kTop, "none", &frame);
  for (const PlotThreshold& t : plot.thresholds) {
    const double py = to_y(t.y);
    if (py < kTop - 1e-9 || py > bottom + 1e-9) continue;  // a fixed range may leave it out
    svg.line({kLeft, py}, {right, py}, Stroke{"#888888", 1.2, "5 4"});
    TextStyle note;
    note.size = 11;
    note.anchor = TextAnchor::kEnd;
    note.colour = "#666666";
    svg.text({right - 4, py - 4}, t.label, note);
  }

  for (size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const Stroke line{s.colour, 2.0, s.dash}, bar{s.colour, 1.2, ""};
    std::vector<Point2> run;  // consecutive defined points
    auto flush = [&] {
      svg.polyline(run, line);
      run.clear();
    };
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.mean[i]) || (plot.log_y && s.mean[i] <= 0)) {
        flush();
        continue;
      }
      const Point2 p{to_x(xs[i]), to_y(s.mean[i])};
      run.push_back(p);
      if (std::isfinite(s.std[i]) && s.std[i] > 0) {
        const double a = s.mean[i] - s.std[i], b = s.mean[i] + s.std[i];
        const double ya = plot.log_y && a <= 0 ? bottom : std::min(bottom, to_y(a));
        const double yb = std::max(kTop, to_y(b));
        svg.line({p.x, ya}, {p.x, yb}, bar);
        svg.line({p.x - 4, ya}, {p.x + 4, ya}, bar);
        svg.line({p.x - 4, yb}, {p.x + 4, yb}, bar);
      }
      draw_marker(svg, p, s);
    }
    flush();
    // Legend entry.
    const double ly = kTop + 10 + 20 * k;
    svg.line({right + 14, ly}, {right + 40, ly}, line);
    draw_marker(svg, {right + 27, ly}, s);
    TextStyle legend;
    legend.size = 12;
    svg.text({right + 46, ly + 4}, s.name, legend);
  }

  for (size_t k = 0; k < plot.rings.size(); ++k) {
    const PlotRing& r = plot.rings[k];
    if (r.series >= plot.series.size() || r.level >= n) continue;
    const PlotSeries& s = plot.series[r.series];
    const double v = s.mean[r.level];
    if (!std::isfinite(v) || (plot.log_y && v <= 0)) continue;
    const Point2 p{to_x(xs[r.level]), to_y(v)};
    const Stroke ring{s.colour, 2.0, ""};
    svg.circle(p, 8.0, "none", &ring);
    TextStyle note;
    note.size = 11;
    note.anchor = TextAnchor::kMiddle;
    note.colour = s.colour;
    // Alternately above and below, so rings at one level stay readable.
    svg.text({p.x, k % 2 ? p.y + 22 : p.y - 12}, r.label, note);
  }

  TextStyle label;
  label.size = 12.5;
  label.anchor = TextAnchor::kMiddle;
  svg.text({0.5 * (kLeft + right), kHeight - 16}, plot.x_label, label);
  label.rotate_deg = -90;
  svg.text({22, 0.5 * (kTop + bottom)}, plot.y_label + (plot.log_y ? " (log scale)" : ""), label);
  TextStyle title;
  title.size = 13.5;
  title.bold = true;
  title.anchor = TextAnchor::kMiddle;
  svg.text({0.5 * (kLeft + right), kTop - 12}, plot.title, title);
  return svg.str();
}

}  // namespace depot::eval
