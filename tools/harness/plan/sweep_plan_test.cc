#include "tools/harness/plan/sweep_plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "common/error.h"
#include "common/testing/error_of.h"
#include "common/testing/scratch_folder.h"
#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_job_state.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

SweepSpec grid_spec() {
  SweepSpec s;
  s.scenarios = {{"depot_walking_xyz", "/x/walking.yaml"}};
  s.vary = {{"load", {"0", "1", "2"}}, {"miss_rate", {"0.05", "0.3"}}};
  s.fixed = {{"rgb_noise", {"3"}}};
  s.modes = {"orb", "orb+yolo"};
  s.seeds = 2;
  return s;
}

TEST(SweepPlan, ExpandsTheGridIntoCellsAndJobsWithUniqueIds) {
  const SweepPlan plan = make_sweep_plan(grid_spec());
  ASSERT_EQ(plan.cells.size(), 6u);
  EXPECT_EQ(plan.cells[1].id, "depot_walking_xyz__load-0__miss_rate-0.3");
  EXPECT_EQ(plan.cells[1].label, "depot_walking_xyz load=0 miss_rate=0.3");
  // Renders per load level and seed only: miss_rate acts on the detector.
  // orb runs no detector, so it runs once per load level and seed too.
  ASSERT_EQ(plan.jobs.size(), 3u * 2 + 3u * 2 + 6u * 2);
  std::set<std::string> ids;
  for (const auto& job : plan.jobs) EXPECT_TRUE(ids.insert(job.id).second) << job.id;
  const SweepJob& run =
      find_job(plan, "depot_walking_xyz__load-2__miss_rate-0.05__s2__orb+yolo", "sweep");
  EXPECT_EQ(run.kind, JobKind::kSlam);
  EXPECT_EQ(run.dataset_id, "depot_walking_xyz__load-2__s2");
  EXPECT_EQ(find_job(plan, run.dataset_id, "sweep").kind, JobKind::kRender);
  EXPECT_EQ(run.seed, 2);
  EXPECT_EQ(run.cells, (std::vector<size_t>{4}));
  const SweepJob& orb = find_job(plan, "depot_walking_xyz__load-2__s2__orb", "sweep");
  EXPECT_EQ(orb.dataset_id, "depot_walking_xyz__load-2__s2");
  EXPECT_EQ(orb.cells, (std::vector<size_t>{4, 5}));  // both miss rates at load 2
  EXPECT_NE(error_of([&] { find_job(plan, "nope", "sweep"); }).find("no job 'nope'"),
            std::string::npos);
}

TEST(SweepPlan, ParametersMatterOnlyToTheModesTheyReach) {
  auto affects = [](const std::string& name, const std::string& mode) {
    return parameter_affects_mode(resolve_parameter(name), mode);
  };
  EXPECT_TRUE(affects("load", "orb"));
  EXPECT_FALSE(affects("miss_rate", "orb"));
  EXPECT_FALSE(affects("miss_rate", "orb+lk"));
  EXPECT_TRUE(affects("miss_rate", "orb+yolo"));
  EXPECT_TRUE(affects("miss_rate", "full"));
  EXPECT_TRUE(affects("miss_rate", "masked"));
  EXPECT_FALSE(affects("rejection.ego_flow", "orb+yolo"));
  EXPECT_TRUE(affects("rejection.ego_flow", "full"));
  EXPECT_TRUE(affects("rejection.ego_flow", "masked"));
  // The object masks' keys change masked runs only.
  EXPECT_TRUE(affects("rejection.mask.top_min_share", "masked"));
  EXPECT_FALSE(affects("rejection.mask.top_min_share", "full"));
  EXPECT_TRUE(affects("rejection.tracking.max_missed", "masked"));
  EXPECT_FALSE(affects("rejection.person_mask", "full"));
  EXPECT_FALSE(affects("rejection.background_margin", "masked"));
}

TEST(SweepPlan, TheDetectorIsAnAxisOfTheModesThatRunOne) {
  SweepSpec s = grid_spec();
  s.vary = {{"detector", {"sim", "darknet"}}};
  s.modes = {"orb", "full", "masked"};
  s.seeds = 1;
  const SweepPlan plan = make_sweep_plan(s);
  ASSERT_EQ(plan.cells.size(), 2u);
  // One render serves both detectors; orb runs once, full and masked twice.
  ASSERT_EQ(plan.jobs.size(), 1u + 1u + 2u * 2);
  EXPECT_EQ(find_job(plan, "depot_walking_xyz__s1__orb", "sweep").cells,
            (std::vector<size_t>{0, 1}));
  const SweepJob& darknet =
      find_job(plan, "depot_walking_xyz__detector-darknet__s1__masked", "sweep");
  EXPECT_EQ(darknet.dataset_id, "depot_walking_xyz__s1");
  const auto choice =
      cell_overrides(plan, plan.cells[darknet.cell], ParameterTarget::kDetectorChoice);
  ASSERT_EQ(choice.size(), 1u);
  EXPECT_EQ(choice[0].value, "darknet");
  EXPECT_TRUE(cell_overrides(plan, plan.cells[darknet.cell], ParameterTarget::kDetector).empty());
  EXPECT_FALSE(parameter_affects_mode(resolve_parameter("detector"), "orb+lk"));
  EXPECT_TRUE(parameter_affects_mode(resolve_parameter("detector"), "orb+yolo"));
}

TEST(SweepPlan, RefusesLevelsThatWouldShareAFolder) {
  SweepSpec s = grid_spec();
  s.vary = {{"scenario.name", {"a b", "a_b"}}};
  EXPECT_THAT(error_of([&] { make_sweep_plan(s); }), ::testing::HasSubstr("share the folder"));
}

TEST(SweepPlan, SendsEachParameterToItsTarget) {
  const SweepPlan plan = make_sweep_plan(grid_spec());
  const SweepCell& cell = plan.cells[5];  // load 2, miss_rate 0.3
  const auto scenario = cell_overrides(plan, cell, ParameterTarget::kScenario);
  const auto detector = cell_overrides(plan, cell, ParameterTarget::kDetector);
  ASSERT_EQ(scenario.size(), 2u);
  EXPECT_EQ(scenario[0].key, "sensor.rgb_noise");
  EXPECT_EQ(scenario[1].key, "dynamic_load");
  EXPECT_EQ(scenario[1].value, "2");
  ASSERT_EQ(detector.size(), 1u);
  EXPECT_EQ(detector[0].key, "miss_rate");
  EXPECT_EQ(detector[0].value, "0.3");
}

TEST(SweepPlan, AFolderHoldsOneSweepAndRecordsMarkFinishedJobs) {
  const testkit::ScratchFolder scratch("plan_test");
  const fs::path root = scratch.path() / "sweep";
  const SweepLayout layout{root.string()};
  write_or_check_spec(layout, grid_spec());
  write_or_check_spec(layout, grid_spec());  // same sweep: fine
  SweepSpec other = grid_spec();
  other.seeds = 3;
  EXPECT_NE(error_of([&] { write_or_check_spec(layout, other); }).find("'seeds' differs"),
            std::string::npos);
  EXPECT_EQ(to_json(read_spec(layout)), to_json(grid_spec()));

  const SweepPlan plan = make_sweep_plan(grid_spec());
  const SweepJob& render = plan.jobs.front();
  EXPECT_FALSE(job_finished(layout, render));
  fs::create_directories(root / "data");
  DatasetRecord d;
  d.id = render.id;
  write_record(layout.dataset_record(render.id), to_json(d));
  EXPECT_TRUE(job_finished(layout, render));
}

TEST(SweepJobState, ARecordIsDoneOnlyWhenItReadsBackAsThisJobs) {
  const testkit::ScratchFolder scratch("sweep_job_state");
  const fs::path root = scratch.path() / "sweep";
  const SweepLayout layout{root.string()};
  const SweepPlan plan = make_sweep_plan(grid_spec());
  const SweepJob& render = plan.jobs[0];
  const SweepJob& other = plan.jobs[1];
  EXPECT_EQ(job_record_state(layout, render).state, RecordState::kNotStarted);

  write_failure_record(layout, render.id, {{"id", render.id}});
  EXPECT_EQ(job_record_state(layout, render).state, RecordState::kFailed);

  fs::create_directories(root / "data");
  std::ofstream(layout.dataset_record(render.id)) << "{\"id\": \"" << render.id << "\", \"fr";
  JobRecordState s = job_record_state(layout, render);
  EXPECT_EQ(s.state, RecordState::kCorrupt);
  EXPECT_EQ(s.problem.rfind(layout.dataset_record(render.id) + ": corrupt record", 0), 0u)
      << s.problem;
  EXPECT_FALSE(job_finished(layout, render));

  DatasetRecord d;
  d.id = other.id;  // another job's record in its place
  write_record(layout.dataset_record(render.id), to_json(d));
  s = job_record_state(layout, render);
  EXPECT_EQ(s.state, RecordState::kCorrupt);
  EXPECT_THAT(s.problem, ::testing::HasSubstr("the record of job '" + other.id + "'")) << s.problem;

  d.id = render.id;
  write_record(layout.dataset_record(render.id), to_json(d));
  EXPECT_EQ(job_record_state(layout, render).state, RecordState::kDone);  // the record wins
}

}  // namespace
}  // namespace depot::harness
