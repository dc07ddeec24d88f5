#include "eval/report_json.h"

#include <gtest/gtest.h>

#include "eval/test_trajectories.h"

namespace depot::eval {
namespace {

using testing::helix_trajectory;

MatchedTrajectories drifting_pair() {
  const auto gt = helix_trajectory(61, 10.0);
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.pose.translation().y() += 0.02 * (p.timestamp - 100.0);
  return match_trajectories(gt, est, {}, "gt.txt", "est.txt");
}

TEST(ReportJson, AteReportCarriesFiguresAndPerPoseErrors) {
  const MatchedTrajectories m = drifting_pair();
  const AteResult ate = compute_ate(m);
  const nlohmann::json j = ate_report_json(m, ate);
  EXPECT_EQ(j["metric"], "ate");
  EXPECT_EQ(j["unit"], "m");
  EXPECT_EQ(j["reference"], "gt.txt");
  EXPECT_EQ(j["estimate"], "est.txt");
  EXPECT_EQ(j["matched_poses"], 61);
  EXPECT_EQ(j["association"]["max_difference_s"], 0.02);
  EXPECT_EQ(j["alignment"]["kind"], "SE(3)");
  EXPECT_EQ(j["statistics"]["rmse"], ate.statistics.rmse);
  EXPECT_EQ(j["statistics"]["std"], ate.statistics.std);
  EXPECT_EQ(j["per_pose"]["errors"].size(), 61u);
  EXPECT_EQ(j["per_pose"]["timestamps"][0], 100.0);
  EXPECT_EQ(j["alignment"]["rotation"].size(), 3u);
}

TEST(ReportJson, RpeReportRoundTripsThroughAFile) {
  const MatchedTrajectories m = drifting_pair();
  const RpeResult rpe = compute_rpe(m, {1.0, DeltaUnit::kSeconds});
  const std::string path = testing::scratch_path("rpe.json");
  write_json_file(path, rpe_report_json(m, rpe));
  const nlohmann::json j = nlohmann::json::parse(testing::read_whole_file(path));
  EXPECT_EQ(j["metric"], "rpe");
  EXPECT_EQ(j["delta"], 1.0);
  EXPECT_EQ(j["delta_unit"], "s");
  EXPECT_EQ(j["pairs"], 51);
  EXPECT_NEAR(j["translation"]["statistics"]["rmse"].get<double>(), 0.02, 1e-12);
  EXPECT_EQ(j["rotation"]["unit"], "deg");
  EXPECT_EQ(j["per_pair"]["translation"].size(), 51u);
  EXPECT_EQ(j["per_pair"]["j"][0], 10);
}

}  // namespace
}  // namespace depot::eval
