#include "eval/rpe.h"

#include <fmt/format.h>

#include <cmath>

#include "common/error.h"

namespace depot::eval {
namespace {

std::string delta_text(const PairSelection& selection) {
  return fmt::format("{:g} {}", selection.delta, to_string(selection.unit));
}

}  // namespace

Pose relative_pose_error(const Pose& reference_i, const Pose& reference_j, const Pose& estimate_i,
                         const Pose& estimate_j) {
  const Pose reference_motion = reference_i.inverse() * reference_j;
  const Pose estimate_motion = estimate_i.inverse() * estimate_j;
  return reference_motion.inverse() * estimate_motion;
}

double rotation_angle_deg(const Pose& pose) {
  // atan2 form: accurate for small angles, unlike acos((trace - 1) / 2).
  const Eigen::Quaterniond q(pose.linear());
  const double angle = 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
  return angle * 180.0 / M_PI;
}

RpeResult compute_rpe(const MatchedTrajectories& matched, const PairSelection& selection) {
  RpeResult out;
  out.selection = selection;
  out.pairs = select_pose_pairs(matched.reference_stamps, selection);
  if (out.pairs.empty()) {
    fail(matched.estimate_name, "no pose pairs " + delta_text(selection) + " apart among the " +
                                    std::to_string(matched.size()) +
                                    " poses matched with the ground truth; use a smaller delta");
  }
  for (const PosePair& p : out.pairs) {
    const Pose error = relative_pose_error(matched.reference[p.i], matched.reference[p.j],
                                           matched.estimate[p.i], matched.estimate[p.j]);
    out.stamps.push_back(matched.reference_stamps[p.i]);
    out.translation.push_back(error.translation().norm());
    out.rotation.push_back(rotation_angle_deg(error));
  }
  out.translation_statistics = compute_statistics(out.translation);
  out.rotation_statistics = compute_statistics(out.rotation);
  return out;
}

}  // namespace depot::eval
