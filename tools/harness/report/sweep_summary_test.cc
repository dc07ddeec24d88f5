#include "tools/harness/report/sweep_summary.h"

#include <gtest/gtest.h>

#include <cmath>

namespace depot::harness {
namespace {

SweepPlan two_level_plan() {
  SweepSpec s;
  s.scenarios = {{"walk", "/x/walk.yaml"}};
  s.vary = {{"load", {"0", "2"}}};
  s.modes = {"orb", "full"};
  s.seeds = 2;
  return make_sweep_plan(s);
}

RunRecord record(const std::string& id, const std::string& mode, int seed, double ate,
                 double precision) {
  RunRecord r;
  r.id = id;
  r.mode = mode;
  r.seed = seed;
  r.ate_rmse = ate;
  r.precision = precision;
  r.frames = 100;
  r.tracked = 90;
  r.lost = 1;
  return r;
}

TEST(MeanStd, SkipsNaNAndUsesThePopulationStd) {
  const MeanStd m = mean_std({1.0, NAN, 3.0});
  EXPECT_EQ(m.count, 2);
  EXPECT_DOUBLE_EQ(m.mean, 2.0);
  EXPECT_DOUBLE_EQ(m.std, 1.0);
  EXPECT_TRUE(std::isnan(mean_std({NAN}).mean));
}

TEST(SweepSummary, GroupsRecordsByCellAndMode) {
  const SweepPlan plan = two_level_plan();
  std::vector<RunRecord> records = {
      record("walk__load-2__s1__orb", "orb", 1, 0.6, NAN),
      record("walk__load-2__s2__orb", "orb", 2, 0.8, NAN),
      record("walk__load-2__s1__full", "full", 1, 0.01, 0.5),
      record("walk__load-0__s1__full", "full", 1, 0.005, NAN),
      record("elsewhere__s1__orb", "orb", 1, 9.0, NAN),  // not in this plan: ignored
  };
  RunRecord failed = record("walk__load-2__s2__full", "full", 2, NAN, NAN);
  failed.ok = false;
  failed.tracked = 0;
  records.push_back(failed);
  const SweepSummary s = summarize_records(plan, records);
  EXPECT_EQ(s.expected_runs, 8u);
  EXPECT_EQ(s.runs.size(), 5u);
  const CellModeSummary* orb = s.find(1, "orb");
  ASSERT_NE(orb, nullptr);
  EXPECT_EQ(orb->runs, 2);
  EXPECT_DOUBLE_EQ(orb->ate_rmse.mean, 0.7);
  EXPECT_NEAR(orb->ate_rmse.std, 0.1, 1e-12);
  EXPECT_EQ(orb->lost, 2);
  const CellModeSummary* full = s.find(1, "full");
  EXPECT_EQ(full->runs, 2);
  EXPECT_EQ(full->without_trajectory, 1);
  EXPECT_DOUBLE_EQ(full->ate_rmse.mean, 0.01);  // the failed run has no ATE
  EXPECT_DOUBLE_EQ(full->tracked_share.mean, 0.45);
  EXPECT_EQ(s.find(0, "orb")->runs, 0);
  EXPECT_EQ(s.find(0, "orb+lk"), nullptr);
}

TEST(SweepSummary, ASharedRunCountsInEveryCellItStandsFor) {
  SweepSpec spec;
  spec.scenarios = {{"walk", "/x/walk.yaml"}};
  spec.vary = {{"rejection.background_margin", {"0", "0.4"}}};
  spec.modes = {"orb", "full"};
  spec.seeds = 1;
  const SweepPlan plan = make_sweep_plan(spec);
  const SweepSummary s = summarize_records(
      plan, {record("walk__s1__orb", "orb", 1, 0.6, NAN),
             record("walk__rejection.background_margin-0__s1__full", "full", 1, 0.01, 0.4),
             record("walk__rejection.background_margin-0.4__s1__full", "full", 1, 0.02, 0.7)});
  EXPECT_EQ(s.expected_runs, 3u);  // one orb run for both margins
  EXPECT_EQ(s.runs.size(), 3u);
  EXPECT_DOUBLE_EQ(s.find(0, "orb")->ate_rmse.mean, 0.6);
  EXPECT_DOUBLE_EQ(s.find(1, "orb")->ate_rmse.mean, 0.6);
  EXPECT_DOUBLE_EQ(s.find(1, "full")->precision.mean, 0.7);
  EXPECT_NEAR(paired_improvement(*s.find(1, "orb"), *s.find(1, "full"), &RunRecord::ate_rmse),
              100.0 * (0.6 - 0.02) / 0.6, 1e-9);
}

TEST(SweepSummary, Eq9ComparesOnlySeedsBothModesFinished) {
  SweepSpec spec;
  spec.scenarios = {{"walk", "/x/walk.yaml"}};
  spec.modes = {"orb", "full"};
  spec.seeds = 3;
  const SweepPlan plan = make_sweep_plan(spec);
  const SweepSummary s = summarize_records(
      plan,
      {record("walk__s1__orb", "orb", 1, 1.0, NAN), record("walk__s2__orb", "orb", 2, 0.5, NAN),
       record("walk__s3__orb", "orb", 3, 0.3, NAN), record("walk__s1__full", "full", 1, 0.01, 0.5),
       record("walk__s2__full", "full", 2, NAN, NAN),  // failed
       record("walk__s3__full", "full", 3, 0.03, 0.5)});
  // Seeds 1 and 3: orb 0.65, full 0.02.
  EXPECT_NEAR(paired_improvement(*s.find(0, "orb"), *s.find(0, "full"), &RunRecord::ate_rmse),
              100.0 * (0.65 - 0.02) / 0.65, 1e-9);
  EXPECT_TRUE(
      std::isnan(paired_improvement(*s.find(0, "orb"), *s.find(0, "full"), &RunRecord::precision)));
  // Differences full - orb on seeds 1 and 3: -0.99 and -0.27.
  const PairedDifference d =
      paired_difference(*s.find(0, "orb"), *s.find(0, "full"), &RunRecord::ate_rmse);
  EXPECT_EQ(d.difference.count, 2);
  EXPECT_NEAR(d.difference.mean, -0.63, 1e-12);
  EXPECT_NEAR(d.difference.std, 0.36, 1e-12);
  // Sample std 0.36 sqrt(2), so t = -0.63 / (0.36 sqrt(2) / sqrt(2)) = -1.75.
  EXPECT_NEAR(d.t, -1.75, 1e-9);
  EXPECT_TRUE(std::isnan(
      paired_difference(*s.find(0, "orb"), *s.find(0, "full"), &RunRecord::precision).t));
}

}  // namespace
}  // namespace depot::harness
