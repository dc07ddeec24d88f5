#pragma once
// A line chart of summary figures against a parameter: one series per mode,
// points at mean with error bars of +-std, optionally a logarithmic y axis
// (ATE spans mm to m across modes). The x axis is numeric when every level
// is a number, else categorical (scenario names). SVG by our own code.
#include <string>
#include <vector>

namespace depot::eval {

// The shape drawn at each point, so series of one colour (a mode's
// precision and recall) can be told apart, also in print.
enum class PlotMarker { kCircle, kSquare };

struct PlotSeries {
  std::string name;
  std::string colour;        // "#rrggbb"
  std::string dash;          // SVG dasharray, empty = solid
  std::vector<double> mean;  // one per x level; NaN = no value (gap)
  std::vector<double> std;   // same length; NaN or 0 = no error bar
  PlotMarker marker = PlotMarker::kCircle;
};

// One point ringed and labelled in its series' colour, e.g. where a mode
// first breaks a bound.
struct PlotRing {
  size_t series = 0;  // index into SeriesPlot::series
  size_t level = 0;   // index into x_levels
  std::string label;
};

// A bound drawn across the plot as a dashed grey line with its label.
struct PlotThreshold {
  double y = 0.0;
  std::string label;
};

struct SeriesPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<std::string> x_levels;  // as the user wrote them
  bool log_y = false;
  // Fixed y range (linear plots only), e.g. [0, 1] for precision; when
  // lo >= hi the range follows the data.
  double y_lo = 0.0, y_hi = 0.0;
  std::vector<PlotSeries> series;
  std::vector<PlotThreshold> thresholds;  // inside the y range drawn
  std::vector<PlotRing> rings;
};

// Throws depot::Error when there are no levels, a series has the wrong
// length, or a log plot has no positive value.
std::string render_series_plot_svg(const SeriesPlot& plot);

// Distinct colours for up to 8 series (then they repeat).
std::string series_colour(size_t index);

}  // namespace depot::eval
