#pragma once
// Plot panels for the SVG figures: a data-to-pixel mapping, "nice" tick
// steps (1, 2 or 5 times a power of ten), and drawing of the frame, grid,
// ticks, tick labels, axis labels and panel title.
#include <string>
#include <vector>

#include "eval/svg_document.h"

namespace depot::eval {

struct AxisRange {
  double lo = 0.0;
  double hi = 1.0;
  double span() const { return hi - lo; }
};

struct PlotArea {  // pixels
  double left = 0.0;
  double top = 0.0;
  double width = 1.0;
  double height = 1.0;
};

// A step of 1, 2 or 5 x 10^k giving about `target_ticks` ticks over `span`.
double nice_step(double span, int target_ticks);

// Multiples of `step` inside [lo, hi].
std::vector<double> ticks_within(const AxisRange& range, double step);

// `value` with as many decimals as `step` needs ("0.25", "-1", "0").
std::string tick_label(double value, double step);

// Smallest range containing [lo, hi] that starts at 0 when lo >= 0 and ends on
// multiples of a nice step; a zero-width range is widened.
AxisRange nice_range_from_zero(double lo, double hi, int target_ticks);

// Ranges with the same metres per pixel on both axes (so shapes are not
// distorted), centred on the data box, with a relative margin.
void equal_aspect_ranges(const PlotArea& area, AxisRange data_x, AxisRange data_y, double margin,
                         AxisRange* x, AxisRange* y);

struct AxisLabels {
  std::string x;
  std::string y;
  std::string title;
};

class PlotFrame {
 public:
  PlotFrame(const PlotArea& area, const AxisRange& x, const AxisRange& y);

  Point2 to_pixel(double x, double y) const;
  const PlotArea& area() const { return area_; }
  const AxisRange& x_range() const { return x_; }
  const AxisRange& y_range() const { return y_; }

  // Grid and frame; draw before the data.
  void draw_background(SvgDocument& svg, double x_step, double y_step) const;
  // Ticks, tick labels, axis labels and title; draw after the data.
  void draw_axes(SvgDocument& svg, double x_step, double y_step, const AxisLabels& labels) const;

 private:
  PlotArea area_;
  AxisRange x_;
  AxisRange y_;
};

}  // namespace depot::eval
