// Breaking points along a varied parameter, from synthetic records: the first
// level over a bound, per mode, with its measured moving share; the plots
// ring the same points and draw the bounds.
#include "tools/harness/report/breaking_points.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tools/harness/report/sweep_figures.h"

namespace depot::harness {
namespace {

using ::testing::HasSubstr;

// Load 0, 1, 2, 3: orb's ATE passes 5 cm at load 1; full's tracked share
// falls below 90 % at load 3 and its ATE never passes; masked keeps no
// trajectory at load 3.
SweepPlan plan_with(std::vector<RunRecord>& records) {
  SweepSpec s;
  s.scenarios = {{"walk", "/x/walk.yaml"}};
  s.vary = {{"load", {"0", "1", "2", "3"}}};
  s.modes = {"orb", "full", "masked"};
  s.seeds = 2;
  const SweepPlan plan = make_sweep_plan(s);
  for (const auto& job : plan.jobs) {
    if (job.kind != JobKind::kSlam) continue;
    const double load = std::stod(plan.cells[job.cell].levels[0]);
    RunRecord r;
    r.id = job.id;
    r.mode = job.mode;
    r.seed = job.seed;
    r.frames = 100;
    r.moving_share = 0.1 * load + 0.01 * job.seed;
    r.ate_rmse = job.mode == "orb" ? 0.01 + 0.06 * load : 0.01;
    r.tracked = job.mode == "full" && load >= 3 ? 80 : 100;
    // masked keeps no trajectory at load 3: past both bounds there.
    if (job.mode == "masked" && load >= 3) r.ate_rmse = NAN, r.tracked = 0, r.ok = false;
    records.push_back(r);
  }
  return plan;
}

TEST(BreakingPoints, TheFirstLevelOverEachBoundPerMode) {
  std::vector<RunRecord> records;
  const SweepPlan plan = plan_with(records);
  const SweepSummary summary = summarize_records(plan, records);
  const std::vector<SweepAxis> axes = sweep_axes(plan, 0);
  ASSERT_EQ(axes.size(), 1u);
  ASSERT_TRUE(numeric_axis(axes[0]));
  const std::vector<BreakingPoint> b = breaking_points(plan, summary, axes[0]);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].mode, "orb");
  EXPECT_EQ(b[0].ate, 1);
  EXPECT_EQ(b[0].tracked, -1);
  EXPECT_EQ(b[1].ate, -1);
  EXPECT_EQ(b[1].tracked, 3);
  EXPECT_EQ(b[2].ate, 3);
  EXPECT_EQ(b[2].tracked, 3);

  const Table t = breaking_point_table(plan, summary);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0][3].text, "1 (moving 11.5 %)");  // seeds 1 and 2: 0.11 and 0.12
  EXPECT_EQ(t.rows[0][4].text, "holds to 3 (moving 31.5 %)");
  EXPECT_EQ(t.rows[1][4].text, "3 (moving 31.5 %)");
}

TEST(BreakingPoints, ThePlotsRingThemAndDrawTheBounds) {
  std::vector<RunRecord> records;
  const SweepPlan plan = plan_with(records);
  const std::vector<Figure> figures = sweep_figures(plan, summarize_records(plan, records));
  std::string ate, tracked;
  for (const Figure& f : figures) {
    if (f.file == "ate_vs_load.svg") ate = f.svg;
    if (f.file == "tracked_vs_load.svg") tracked = f.svg;
  }
  EXPECT_THAT(ate, HasSubstr(">5 cm<"));
  EXPECT_THAT(ate, HasSubstr(">orb &gt; 5 cm<"));
  EXPECT_THAT(ate, ::testing::Not(HasSubstr("full &gt; 5 cm")));
  EXPECT_THAT(tracked, HasSubstr(">90 %<"));
  EXPECT_THAT(tracked, HasSubstr(">full &lt; 90 %<"));
  // Each load level shows the moving share measured.
  EXPECT_THAT(ate, HasSubstr(">1 (12 %)<"));
}

}  // namespace
}  // namespace depot::harness
