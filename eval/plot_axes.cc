#include "eval/plot_axes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace depot::eval {
namespace {

constexpr double kTickLength = 5.0;
const char* const kFrameColour = "#444444";
const char* const kGridColour = "#e4e4e4";

AxisRange widened_if_empty(AxisRange r) {
  if (r.span() > 0.0) return r;
  const double half = std::max(std::abs(r.lo) * 0.05, 0.5e-3);
  return {r.lo - half, r.hi + half};
}

}  // namespace

double nice_step(double span, int target_ticks) {
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(target_ticks, 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  double nice = 10.0;
  if (fraction <= 1.0) {
    nice = 1.0;
  } else if (fraction <= 2.0) {
    nice = 2.0;
  } else if (fraction <= 5.0) {
    nice = 5.0;
  }
  return nice * power;
}

std::vector<double> ticks_within(const AxisRange& range, double step) {
  std::vector<double> ticks;
  if (!(step > 0.0)) return ticks;
  const double eps = step * 1e-9;
  for (double k = std::ceil((range.lo - eps) / step); k * step <= range.hi + eps; k += 1.0) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < eps ? 0.0 : v);
    if (ticks.size() > 1000) break;  // guards against a degenerate step
  }
  return ticks;
}

std::string tick_label(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::string s = fmt::format("{:.{}f}", value, decimals);
  if (s.find_first_not_of("-0.") == std::string::npos && s[0] == '-') s.erase(0, 1);  // no "-0"
  return s;
}

AxisRange nice_range_from_zero(double lo, double hi, int target_ticks) {
  AxisRange r = widened_if_empty({std::min(lo, 0.0), hi});
  const double step = nice_step(r.span(), target_ticks);
  return {std::floor(r.lo / step) * step, std::ceil(r.hi / step) * step};
}

void equal_aspect_ranges(const PlotArea& area, AxisRange data_x, AxisRange data_y, double margin,
                         AxisRange* x, AxisRange* y) {
  data_x = widened_if_empty(data_x);
  data_y = widened_if_empty(data_y);
  const double per_pixel =
      std::max(data_x.span() / area.width, data_y.span() / area.height) * (1.0 + 2.0 * margin);
  const double cx = 0.5 * (data_x.lo + data_x.hi);
  const double cy = 0.5 * (data_y.lo + data_y.hi);
  *x = {cx - 0.5 * per_pixel * area.width, cx + 0.5 * per_pixel * area.width};
  *y = {cy - 0.5 * per_pixel * area.height, cy + 0.5 * per_pixel * area.height};
}

PlotFrame::PlotFrame(const PlotArea& area, const AxisRange& x, const AxisRange& y)
    : area_(area), x_(widened_if_empty(x)), y_(widened_if_empty(y)) {}

Point2 PlotFrame::to_pixel(double x, double y) const {
  return {area_.left + (x - x_.lo) / x_.span() * area_.width,
          area_.top + area_.height - (y - y_.lo) / y_.span() * area_.height};
}

void PlotFrame::draw_background(SvgDocument& svg, double x_step, double y_step) const {
  const Stroke grid{kGridColour, 1.0, ""};
  const double bottom = area_.top + area_.height;
  const double right = area_.left + area_.width;
  for (double v : ticks_within(x_, x_step)) {
    const double px = to_pixel(v, y_.lo).x;
    svg.line({px, area_.top}, {px, bottom}, grid);
  }
  for (double v : ticks_within(y_, y_step)) {
    const double py = to_pixel(x_.lo, v).y;
    svg.line({area_.left, py}, {right, py}, grid);
  }
}

void PlotFrame::draw_axes(SvgDocument& svg, double x_step, double y_step,
                          const AxisLabels& labels) const {
  const Stroke frame{kFrameColour, 1.0, ""};
  const double bottom = area_.top + area_.height;
  svg.rect(area_.left, area_.top, area_.width, area_.height, "none", &frame);

  TextStyle tick_text;
  tick_text.size = 11.0;
  tick_text.anchor = TextAnchor::kMiddle;
  for (double v : ticks_within(x_, x_step)) {
    const double px = to_pixel(v, y_.lo).x;
    svg.line({px, bottom}, {px, bottom + kTickLength}, frame);
    svg.text({px, bottom + kTickLength + 12.0}, tick_label(v, x_step), tick_text);
  }
  tick_text.anchor = TextAnchor::kEnd;
  for (double v : ticks_within(y_, y_step)) {
    const double py = to_pixel(x_.lo, v).y;
    svg.line({area_.left - kTickLength, py}, {area_.left, py}, frame);
    svg.text({area_.left - kTickLength - 3.0, py + 4.0}, tick_label(v, y_step), tick_text);
  }

  TextStyle axis_text;
  axis_text.size = 12.5;
  axis_text.anchor = TextAnchor::kMiddle;
  svg.text({area_.left + 0.5 * area_.width, bottom + 38.0}, labels.x, axis_text);
  axis_text.rotate_deg = -90.0;
  svg.text({area_.left - 52.0, area_.top + 0.5 * area_.height}, labels.y, axis_text);

  TextStyle title_text;
  title_text.size = 13.5;
  title_text.bold = true;
  title_text.anchor = TextAnchor::kMiddle;
  svg.text({area_.left + 0.5 * area_.width, area_.top - 8.0}, labels.title, title_text);
}

}  // namespace depot::eval
