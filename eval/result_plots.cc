#include "eval/result_plots.h"

#include <fmt/format.h>

#include <cmath>

#include "eval/alignment.h"

namespace depot::eval {
namespace {

std::vector<Eigen::Vector3d> positions_of(const std::vector<Pose>& poses) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(poses.size());
  for (const Pose& p : poses) out.push_back(p.translation());
  return out;
}

std::string summary(const char* what, const ErrorStatistics& s) {
  return fmt::format("{}: rmse {:.4f}, mean {:.4f}, median {:.4f}, std {:.4f}, max {:.4f}", what,
                     s.rmse, s.mean, s.median, s.std, s.max);
}

}  // namespace

TrajectoryPlot ate_plot(const MatchedTrajectories& matched, const AteResult& ate) {
  TrajectoryPlot plot;
  plot.title = "ATE: " + matched.estimate_name + " vs " + matched.reference_name;
  plot.subtitle = to_string(ate.alignment_kind) + " alignment, " +
                  std::to_string(ate.statistics.count) + " matched poses | " +
                  summary("ATE (m)", ate.statistics);
  plot.reference = ate.reference_positions;
  plot.estimate = ate.aligned_estimate_positions;
  plot.estimate_colour_values = ate.errors;
  plot.colour_label = "ATE (m)";
  plot.series.push_back({"ATE", "m", ate.stamps, ate.errors});
  plot.time_origin = matched.reference_stamps.front();
  return plot;
}

TrajectoryPlot rpe_plot(const MatchedTrajectories& matched, const RpeResult& rpe) {
  TrajectoryPlot plot;
  const std::string delta =
      fmt::format("delta {:g} {}", rpe.selection.delta, to_string(rpe.selection.unit));
  plot.title = "RPE: " + matched.estimate_name + " vs " + matched.reference_name;
  const std::string rotation =
      fmt::format("rotation (deg): rmse {:.4f}, std {:.4f}", rpe.rotation_statistics.rmse,
                  rpe.rotation_statistics.std);
  plot.subtitle = delta + ", " + std::to_string(rpe.pairs.size()) + " pairs | " +
                  summary("translation (m)", rpe.translation_statistics) + " | " + rotation;

  plot.reference = positions_of(matched.reference);
  const std::vector<Eigen::Vector3d> estimate = positions_of(matched.estimate);
  const SimilarityTransform display = align_points(estimate, plot.reference, AlignmentKind::kRigid);
  for (const Eigen::Vector3d& p : estimate) plot.estimate.push_back(display.apply(p));

  plot.estimate_colour_values.assign(estimate.size(), NAN);
  for (size_t k = 0; k < rpe.pairs.size(); ++k) {
    plot.estimate_colour_values[rpe.pairs[k].i] = rpe.translation[k];
  }
  plot.colour_label = "RPE translation (m)";
  plot.series.push_back({"RPE translation", "m", rpe.stamps, rpe.translation});
  plot.series.push_back({"RPE rotation", "deg", rpe.stamps, rpe.rotation});
  plot.time_origin = matched.reference_stamps.front();
  return plot;
}

}  // namespace depot::eval
