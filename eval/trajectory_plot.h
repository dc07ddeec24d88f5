#pragma once
// One SVG figure of a trajectory evaluation: top view (x-y) and side view
// (x-z) of the ground truth and the aligned estimate, the estimate coloured by
// its error with a colour bar, and below them one panel per error series over
// time (with RMSE, mean and median lines). Written by our own code; no
// plotting library.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace depot::eval {

struct ErrorSeries {
  std::string name;            // e.g. "APE", "RPE translation"
  std::string unit;            // e.g. "m", "deg"
  std::vector<double> stamps;  // s, absolute
  std::vector<double> values;  // same length as stamps
};

struct TrajectoryPlot {
  std::string title;
  std::string subtitle;
  std::vector<Eigen::Vector3d> reference;  // ground-truth positions, m
  std::vector<Eigen::Vector3d> estimate;   // aligned estimate positions, m
  // One per estimate position; NaN draws that part grey (no value).
  std::vector<double> estimate_colour_values;
  std::string colour_label;  // e.g. "APE (m)"
  std::vector<ErrorSeries> series;
  // Time axes show stamp - time_origin; NaN uses the first series stamp.
  double time_origin = std::numeric_limits<double>::quiet_NaN();
};

// Throws depot::Error when the plot has no positions or lists differ in length.
std::string render_trajectory_plot_svg(const TrajectoryPlot& plot);

// Renders and writes the file atomically.
void write_trajectory_plot_svg(const std::string& path, const TrajectoryPlot& plot);

}  // namespace depot::eval
