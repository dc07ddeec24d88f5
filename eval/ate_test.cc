#include "eval/ate.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/error.h"
#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::deg;
using testing::helix_trajectory;
using testing::moved;
using testing::rotation_about;

MatchedTrajectories match(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& est) {
  return match_trajectories(gt, est, {}, "gt.txt", "est.txt");
}

TEST(Ate, IdenticalTrajectoryUnderARigidTransformIsZero) {
  const auto gt = helix_trajectory(300, 30.0);
  const Pose world_change = rotation_about({0.4, -1.0, 0.3}, deg(137.0), {5.0, -2.0, 1.5});
  const AteResult ate = compute_ate(match(gt, moved(gt, world_change)));
  EXPECT_EQ(ate.statistics.count, 300u);
  EXPECT_LT(ate.statistics.max, 1e-9);
  EXPECT_LT(ate.statistics.rmse, 1e-9);
  // The alignment is the inverse of the world change.
  EXPECT_TRUE(ate.alignment.rotation.isApprox(world_change.linear().transpose(), 1e-9));
}

// Points on a circle in the x-y plane, each pushed along z by +a, +b, -a, -b,
// ... This perturbation has zero mean and no moment about any axis through
// the centroid, so the optimal alignment cannot reduce it: after alignment
// every error is exactly a or b.
TEST(Ate, ZeroMeanPerturbationThatAlignmentCannotRemove) {
  const double a = 0.01, b = 0.03;
  const double signed_offset[4] = {a, b, -a, -b};
  std::vector<StampedPose> gt, est;
  for (int k = 0; k < 16; ++k) {
    const double angle = k * M_PI / 8.0;
    const Eigen::Vector3d p(2.0 * std::cos(angle), 2.0 * std::sin(angle), 0.0);
    const double t = 1.0 + 0.1 * k;
    gt.push_back({t, make_pose(Eigen::Matrix3d::Identity(), p)});
    est.push_back({t, make_pose(Eigen::Matrix3d::Identity(),
                                p + Eigen::Vector3d(0, 0, signed_offset[k % 4]))});
  }
  const Pose world_change = rotation_about({1.0, 2.0, -0.5}, deg(63.0), {-3.0, 0.5, 8.0});
  const AteResult ate = compute_ate(match(gt, moved(est, world_change)));
  for (double e : ate.errors) EXPECT_NEAR(std::min(std::abs(e - a), std::abs(e - b)), 0.0, 1e-12);
  EXPECT_NEAR(ate.statistics.rmse, std::sqrt((a * a + b * b) / 2.0), 1e-12);
  EXPECT_NEAR(ate.statistics.mean, (a + b) / 2.0, 1e-12);
  EXPECT_NEAR(ate.statistics.median, (a + b) / 2.0, 1e-12);
  EXPECT_NEAR(ate.statistics.std, (b - a) / 2.0, 1e-12);
  EXPECT_NEAR(ate.statistics.min, a, 1e-12);
  EXPECT_NEAR(ate.statistics.max, b, 1e-12);
}

TEST(Ate, Sim3RecoversScaleAndRemovesIt) {
  const auto gt = helix_trajectory(200, 30.0);
  std::vector<StampedPose> est = moved(gt, rotation_about({0, 0, 1}, deg(30), {1, 2, 3}));
  for (StampedPose& p : est) p.pose.translation() *= 0.4;  // monocular-like scale
  const MatchedTrajectories m = match(gt, est);

  const AteResult sim3 = compute_ate(m, {AlignmentKind::kSimilarity});
  EXPECT_NEAR(sim3.alignment.scale, 2.5, 1e-9);
  EXPECT_LT(sim3.statistics.max, 1e-9);

  const AteResult se3 = compute_ate(m, {AlignmentKind::kRigid});
  EXPECT_EQ(se3.alignment.scale, 1.0);
  EXPECT_GT(se3.statistics.rmse, 0.1);
}

TEST(Ate, NoAlignmentComparesRawPositions) {
  const auto gt = helix_trajectory(50, 30.0);
  const auto est = moved(gt, make_pose(Eigen::Matrix3d::Identity(), {0.0, 0.0, 0.05}));
  const AteResult ate = compute_ate(match(gt, est), {AlignmentKind::kNone});
  EXPECT_NEAR(ate.statistics.min, 0.05, 1e-12);
  EXPECT_NEAR(ate.statistics.max, 0.05, 1e-12);
}

// A small hand-made case checked against TUM evaluate_ate.py's definition:
// association by associate.py's rule, Horn alignment of the estimate onto the
// ground truth, error per matched pose. The expected figures come from an
// independent python3 implementation (TUM's greedy association + Horn's
// quaternion method with a Jacobi eigen-solver, no numpy).
TEST(Ate, CrossCheckWithTumEvaluateAte) {
  const std::vector<std::pair<double, Eigen::Vector3d>> gt_points = {
      {1.00, {0.00, 0.00, 0.00}}, {1.10, {0.30, 0.05, 0.02}}, {1.20, {0.55, 0.20, 0.05}},
      {1.30, {0.70, 0.45, 0.03}}, {1.40, {0.72, 0.75, 0.10}}, {1.50, {0.60, 1.00, 0.18}},
      {1.60, {0.35, 1.15, 0.22}}, {1.70, {0.05, 1.10, 0.20}}, {1.80, {-0.20, 0.90, 0.15}}};
  const std::vector<std::pair<double, Eigen::Vector3d>> est_points = {
      {0.950, {9.0, 9.0, 9.0}},  // no ground-truth partner
      {1.004, {1.010, 2.000, 0.480}},
      {1.093, {1.000, 2.290, 0.520}},
      {1.215, {0.840, 2.560, 0.540}},
      {1.301, {0.600, 2.700, 0.540}},
      {1.399, {0.260, 2.740, 0.560}},
      {1.512, {0.020, 2.600, 0.680}},
      {1.590, {-0.120, 2.370, 0.700}},
      {1.711, {-0.110, 2.050, 0.690}},
      {1.785, {0.110, 1.810, 0.640}},
      {1.845, {0.300, 1.600, 0.600}}};  // 0.045 s from any ground truth: dropped
  std::vector<StampedPose> gt, est;
  for (const auto& [t, p] : gt_points) gt.push_back({t, make_pose(Eigen::Matrix3d::Identity(), p)});
  for (const auto& [t, p] : est_points) {
    est.push_back({t, make_pose(Eigen::Matrix3d::Identity(), p)});
  }

  const AteResult ate = compute_ate(match(gt, est));
  const ErrorStatistics& s = ate.statistics;
  ASSERT_EQ(s.count, 9u);  // "compared_pose_pairs 9 pairs"
  EXPECT_NEAR(s.rmse, 0.0235623858901935, 1e-12);
  EXPECT_NEAR(s.mean, 0.0215018505665493, 1e-12);
  EXPECT_NEAR(s.median, 0.0193584648908893, 1e-12);
  EXPECT_NEAR(s.std, 0.00963620522053019, 1e-12);
  EXPECT_NEAR(s.min, 0.00629974729563088, 1e-12);
  EXPECT_NEAR(s.max, 0.0374401061938059, 1e-12);

  // What evaluate_ate.py prints ("absolute_translational_error.rmse %f m").
  char printed[32];
  std::snprintf(printed, sizeof(printed), "%f", s.rmse);
  EXPECT_STREQ(printed, "0.023562");

  const Eigen::Matrix3d horn_rotation{
      {0.017646647292140383, 0.9998384668700636, 0.003411159079581309},
      {-0.9998099913667154, 0.017674196347374216, -0.008222161927481967},
      {-0.008281123271275628, -0.003265417338393549, 0.9999603792385836}};
  EXPECT_TRUE(ate.alignment.rotation.isApprox(horn_rotation, 1e-10));
  EXPECT_TRUE(ate.alignment.translation.isApprox(
      Eigen::Vector3d(-2.0142825020106807, 0.9866692898099253, -0.47788083997002734), 1e-10));
}

TEST(Ate, Sim3WithAllEstimatesAtOnePointNamesTheEstimate) {
  const auto gt = helix_trajectory(10, 10.0);
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.pose.translation().setZero();
  try {
    compute_ate(match(gt, est), {AlignmentKind::kSimilarity});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("est.txt: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace depot::eval
