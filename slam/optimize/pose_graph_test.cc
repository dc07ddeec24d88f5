// The pose graph on a loop: odometry edges with a drift, one loop edge with
// the true relative pose; optimisation spreads the error and brings the
// poses back near the truth.
#include "slam/optimize/pose_graph.h"

#include <cmath>

#include <gtest/gtest.h>

namespace depot::slam {
namespace {

// A camera driving a 4 m circle, looking along its path: 40 poses T_cw.
std::vector<Pose> circle(double yaw_drift_per_step) {
  std::vector<Pose> out;
  double yaw_error = 0;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * M_PI * i / 40.0;
    const Eigen::Vector3d c(2 * std::cos(a), 0, 2 * std::sin(a));
    const Eigen::Matrix3d R_wc =
        Eigen::AngleAxisd(-a + yaw_error, Eigen::Vector3d::UnitY()).toRotationMatrix();
    Pose T_wc = make_pose(R_wc, c);
    out.push_back(T_wc.inverse());
    yaw_error += yaw_drift_per_step;
  }
  return out;
}

double max_position_error(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, (a[i].inverse().translation() - b[i].inverse().translation()).norm());
  return worst;
}

TEST(PoseGraph, ALoopEdgeCorrectsDrift) {
  const std::vector<Pose> truth = circle(0);
  // Drifted estimate: accumulate true relative motions with a rotation error.
  std::vector<Pose> estimate = {truth[0]};
  const Pose bias = make_pose(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                              Eigen::Vector3d(0.01, 0, 0));
  for (size_t i = 1; i < truth.size(); ++i) {
    const Pose T_i_prev = truth[i] * truth[i - 1].inverse();
    estimate.push_back(bias * T_i_prev * estimate.back());
  }
  std::vector<PoseGraphEdge> edges;
  for (size_t i = 1; i < truth.size(); ++i)
    edges.push_back({i - 1, i, estimate[i - 1] * estimate[i].inverse()});
  const double before = max_position_error(estimate, truth);
  ASSERT_GT(before, 0.3);
  edges.push_back({truth.size() - 1, 0, truth.back() * truth[0].inverse()});  // the loop
  std::vector<bool> fixed(truth.size(), false);
  fixed[0] = true;
  optimize_pose_graph(estimate, fixed, edges, 50);
  const double after = max_position_error(estimate, truth);
  EXPECT_LT(after, 0.25 * before) << "before " << before << " after " << after;
  EXPECT_TRUE(estimate[0].isApprox(truth[0]));  // fixed
}

TEST(PoseGraph, ConsistentEdgesLeaveThePosesAlone) {
  std::vector<Pose> poses = circle(0);
  const std::vector<Pose> start = poses;
  std::vector<PoseGraphEdge> edges;
  for (size_t i = 1; i < poses.size(); ++i)
    edges.push_back({i - 1, i, poses[i - 1] * poses[i].inverse()});
  std::vector<bool> fixed(poses.size(), false);
  fixed[0] = true;
  EXPECT_LT(optimize_pose_graph(poses, fixed, edges), 1e-12);
  EXPECT_LT(max_position_error(poses, start), 1e-6);
}

}  // namespace
}  // namespace depot::slam
