// The report from records on disk (synthetic figures, real files): tables,
// CSVs, plots and the self-contained HTML page.
#include "tools/harness/report/sweep_report.h"
#include "common/testing/scratch_folder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/tum_io.h"
#include "tools/harness/plan/run_record.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SweepReportTest : ::testing::Test {
  testkit::ScratchFolder scratch{"report_test"};
  fs::path root = scratch.path() / "sweep";
  SweepLayout layout{root.string()};
  SweepPlan plan;
  void SetUp() override {
    fs::remove_all(root);
    SweepSpec s;
    s.scenarios = {{"walk", "/x/walk.yaml"}};
    s.vary = {{"load", {"0", "1", "2"}}};
    s.modes = {"orb", "orb+yolo", "full"};
    s.seeds = 2;
    plan = make_sweep_plan(s);
    // orb degrades with load, full stays near 1 cm; seed 2 of load 0 missing.
    for (const auto& job : plan.jobs) {
      if (job.kind != JobKind::kSlam || (job.cell == 0 && job.seed == 2)) continue;
      RunRecord r;
      r.id = job.id;
      r.mode = job.mode;
      r.seed = job.seed;
      r.frames = 100;
      r.tracked = job.mode == "full" ? 90 : 100;
      r.posed = job.mode == "full" ? 95 : 100;
      r.maps = job.mode == "full" ? 2 : 1;
      r.ate_all_maps_rmse = 0.02;
      const double load = static_cast<double>(job.cell);
      r.ate_rmse = job.mode == "orb" ? 0.01 + 0.4 * load : 0.01 + 0.001 * job.seed;
      r.ate_std = r.ate_rmse / 2;
      r.rpe_trans_rmse = r.ate_rmse / 10;
      r.rpe_rot_rmse = 1.0;
      if (job.mode != "orb") r.precision = 0.5, r.recall = 0.8;
      fs::create_directories(layout.run_dir(job.id));
      write_record(layout.run_record(job.id), to_json(r));
      write_text_file_atomic((fs::path(layout.run_dir(job.id)) / "ate.svg").string(),
                             "<?xml version=\"1.0\"?>\n<svg id=\"traj-" + job.id + "\"></svg>\n");
    }
  }
};

TEST_F(SweepReportTest, WritesTablesCsvPlotsAndOneSelfContainedPage) {
  const ReportFiles files = write_sweep_report(plan, layout);
  EXPECT_EQ(files.runs_found, 15u);
  EXPECT_EQ(files.runs_expected, 18u);
  const std::string md = read(files.markdown);
  // load 2: orb 0.81, full (0.011 + 0.012) / 2 = 0.0115 -> Eq. 9 = 98.6 %;
  // paired differences -799 and -798 mm, t = -798.5 / (0.5 sqrt(2) / sqrt(2)).
  EXPECT_NE(md.find("| walk | 2 | – | 0.8100 ± 0.0000 | 0.0115 ± 0.0005 | 0.0115 ± 0.0005 | 98.6 % "
                    "| -798.50 ± 0.50 | -1597.0 | 6 of 6 |"),
            std::string::npos)
      << md;
  EXPECT_THAT(md, ::testing::HasSubstr("| walk | 0 |"));
  EXPECT_THAT(md, ::testing::HasSubstr("3 of 6"));
  EXPECT_THAT(md, ::testing::HasSubstr("paper Table 3"));
  EXPECT_THAT(md, ::testing::HasSubstr("paper Table 4"));
  // Every frame counted: full's trajectory holds 90 %, its two maps 95 %.
  EXPECT_NE(md.find("| walk | 2 | full | 0.0115 ± 0.0005 | 90.0 % | 95.0 % | 2.0 ± 0.0 | "
                    "0.0200 ± 0.0000 |"),
            std::string::npos)
      << md;
  for (const char* csv : {"table2_ablation.csv", "table3_ate_vs_orb.csv", "table4_rpe_vs_orb.csv",
                          "rejection.csv", "frames.csv", "runs.csv", "ate_vs_load.svg",
                          "tracked_vs_load.svg", "rejection_vs_load.svg"})
    EXPECT_TRUE(fs::is_regular_file(root / "report" / csv)) << csv;

  const std::string html = read(files.html);
  EXPECT_THAT(html, ::testing::Not(
                        ::testing::HasSubstr("<?xml")));  // SVGs are inlined without declarations
  EXPECT_THAT(html, ::testing::Not(::testing::HasSubstr("src=")));  // nothing loaded from elsewhere
  EXPECT_THAT(html, ::testing::Not(::testing::HasSubstr("href=")));
  EXPECT_THAT(html, ::testing::HasSubstr("ATE RMSE vs load"));
  EXPECT_THAT(html, ::testing::HasSubstr("15 of 18 runs finished"));
  // Default trajectory figures: orb and full of the last level, seed 1.
  EXPECT_THAT(html, ::testing::HasSubstr("traj-walk__load-2__s1__orb\""));
  EXPECT_THAT(html, ::testing::HasSubstr("traj-walk__load-2__s1__full\""));
  EXPECT_THAT(html, ::testing::Not(::testing::HasSubstr("traj-walk__load-1__s1__orb\"")));
}

TEST_F(SweepReportTest, ShowsTheTrajectoryFiguresAskedFor) {
  const ReportFiles files = write_sweep_report(plan, layout, {"walk__load-1__s2__orb+yolo"});
  const std::string html = read(files.html);
  EXPECT_THAT(html, ::testing::HasSubstr("traj-walk__load-1__s2__orb+yolo\""));
  EXPECT_THAT(html, ::testing::Not(::testing::HasSubstr("traj-walk__load-2__s1__orb\"")));
}

TEST_F(SweepReportTest, RefusesAnUnknownFigureRunBeforeWritingAnything) {
  EXPECT_THROW(write_sweep_report(plan, layout, {"walk__load-9__s1__orb"}), Error);
  EXPECT_FALSE(fs::exists(root / "report"));
}

}  // namespace
}  // namespace depot::harness
