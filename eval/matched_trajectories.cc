#include "eval/matched_trajectories.h"

#include <fmt/format.h>

#include "common/error.h"
#include "dataset/ros2/bag_trajectory.h"

namespace depot::eval {
namespace {

std::vector<double> stamps_of(const std::vector<StampedPose>& poses) {
  std::vector<double> out;
  out.reserve(poses.size());
  for (const StampedPose& p : poses) out.push_back(p.timestamp);
  return out;
}

std::string time_range(const std::vector<StampedPose>& poses) {
  return fmt::format("{:.3f}..{:.3f} s", poses.front().timestamp, poses.back().timestamp);
}

std::string seconds(double s) {
  return fmt::format("{:g} s", s);
}

}  // namespace

MatchedTrajectories match_trajectories(const std::vector<StampedPose>& reference,
                                       const std::vector<StampedPose>& estimate,
                                       const AssociationOptions& options,
                                       const std::string& reference_name,
                                       const std::string& estimate_name) {
  if (reference.empty()) fail(reference_name, "no poses in trajectory");
  if (estimate.empty()) fail(estimate_name, "no poses in trajectory");
  const std::vector<TimestampMatch> matches =
      associate(stamps_of(reference), stamps_of(estimate), options);

  const std::string against = " of ground truth " + reference_name + " (estimate " +
                              time_range(estimate) + ", ground truth " + time_range(reference) +
                              ", offset " + seconds(options.offset) + ")";
  if (matches.empty()) {
    fail(estimate_name, "no timestamp lies within " + seconds(options.max_difference) + against);
  }
  if (matches.size() < kMinMatchedPairs) {
    fail(estimate_name, "only " + std::to_string(matches.size()) +
                            " timestamps match (need at least " + std::to_string(kMinMatchedPairs) +
                            ") within " + seconds(options.max_difference) + against);
  }

  MatchedTrajectories out;
  out.reference_name = reference_name;
  out.estimate_name = estimate_name;
  out.reference_size = reference.size();
  out.estimate_size = estimate.size();
  out.association = options;
  for (const TimestampMatch& m : matches) {
    out.reference_stamps.push_back(reference[m.reference_index].timestamp);
    out.estimate_stamps.push_back(estimate[m.estimate_index].timestamp);
    out.reference.push_back(reference[m.reference_index].pose);
    out.estimate.push_back(estimate[m.estimate_index].pose);
  }
  return out;
}

MatchedTrajectories load_matched_trajectories(const std::string& reference_path,
                                              const std::string& estimate_path,
                                              const AssociationOptions& options) {
  const std::vector<StampedPose> reference = ros2::read_trajectory(reference_path);
  const std::vector<StampedPose> estimate = read_tum_trajectory(estimate_path);
  return match_trajectories(reference, estimate, options, reference_path, estimate_path);
}

}  // namespace depot::eval
