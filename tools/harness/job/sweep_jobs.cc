#include "tools/harness/job/sweep_jobs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/staged_directory.h"
#include "common/tum_io.h"
#include "eval/ate.h"
#include "eval/keypoint_score.h"
#include "eval/maps_ate.h"
#include "eval/matched_trajectories.h"
#include "eval/motion_truth.h"
#include "eval/result_plots.h"
#include "eval/rpe.h"
#include "eval/trajectory_plot.h"
#include "sim/dataset/contact_sheet.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/sim_detector_config.h"
#include "slam/io/frame_states_file.h"
#include "slam/reject/rejection_settings.h"
#include "tools/runner/slam_runner.h"
#include "tools/system/system_run.h"

namespace fs = std::filesystem;

namespace depot::harness {
namespace {

// The cell's `detector` level; sweeps render simulated datasets, so "sim"
// when the sweep does not name one.
std::string cell_detector(const SweepPlan& plan, const SweepCell& cell) {
  const std::vector<YamlOverride> choice =
      cell_overrides(plan, cell, ParameterTarget::kDetectorChoice);
  return choice.empty() ? "sim" : choice.front().value;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A system under test (another program) on the job's dataset: its
// trajectory, states and keypoint file into `folder`, its accuracy and
// rejection into `r`. A system that fails (exit code, time limit, a bad or
// missing trajectory) is an outcome of the sweep: r.ok = false with the
// reason and its log's tail; only an interruption throws. `folder` is the
// staged run folder, `final_folder` where it goes: the error names the log
// there. Its scratch (generated inputs, raw outputs) goes either way.
void run_system_into(const std::string& dataset, const SweepJob& job, const std::string& folder,
                     const std::string& final_folder, RunRecord& r) {
  const fs::path out(folder);
  try {
    const system::SystemSpec spec = system::load_system_spec(job.system_file);
    system::SystemRunRequest request;
    request.dataset = dataset;
    request.work_dir = (out / "system").string();  // removed with the result, or on failure
    request.log_path = (out / "system.log").string();
    request.log_name = (fs::path(final_folder) / "system.log").string();
    const system::SystemRunResult s = system::run_system(spec, request);
    const std::vector<slam::StampedFrameState> states = system::frame_states(s);
    const slam::TrackedShare share = slam::tracked_share(states);
    r.frames = static_cast<int>(share.frames);
    r.tracked = static_cast<int>(share.tracked);
    r.lost = static_cast<int>(std::count_if(states.begin(), states.end(), [](const auto& f) {
      return f.state == slam::FrameState::kLost;
    }));
    r.median_frame_ms = s.frame_ms;  // from its wall time: it reports none of its own
    if (spec.writes_keypoints && eval::MotionTruth::available(dataset)) {
      try {
        add_rejection(eval::score_dataset_keypoints(dataset, s.keypoints_path, 1.2f).score, r);
      } catch (const Error& e) {
        fail("system " + spec.name, system::name_work_paths(s, e.what()));
      }
    }
    write_tum_trajectory((out / "trajectory.txt").string(), s.trajectory,
                         "depot sweep run " + job.id + ": system " + spec.name);
    write_text_file_atomic((out / "states.txt").string(),
                           slam::format_frame_states(states, "depot sweep run " + job.id));
    const std::vector<StampedPose> truth =
        read_tum_trajectory((fs::path(dataset) / "groundtruth.txt").string());
    add_accuracy(truth, s.trajectory, (out / "ate.svg").string(), r);
    add_atlas_accuracy(truth, s.trajectory, states, r);
  } catch (const Error& e) {
    throw_if_interrupted(job.id);
    r.ok = false;
    r.error = e.what();
    r.log_tail = system::log_tail((out / "system.log").string(), 10);
  }
}

}  // namespace

void add_atlas_accuracy(const std::vector<StampedPose>& truth,
                        const std::vector<StampedPose>& atlas,
                        const std::vector<slam::StampedFrameState>& states, RunRecord& r) {
  const std::vector<int> maps = slam::maps_of_posed_frames(states);
  if (maps.empty()) {
    // States without maps (another system): its trajectory is all it has.
    r.posed = r.tracked;
    r.maps = r.tracked > 0 ? 1 : 0;
    r.ate_all_maps_rmse = r.ate_rmse;
    return;
  }
  r.posed = static_cast<int>(maps.size());
  r.maps = static_cast<int>(*std::max_element(maps.begin(), maps.end()) + 1);
  if (!r.ok) return;  // the main map is too short to align: so is the score
  r.ate_all_maps_rmse = eval::compute_maps_ate(truth, atlas, maps, states.size(), {},
                                               eval::AlignmentKind::kRigid, "groundtruth", r.mode)
                            .statistics.rmse;
}

void add_rejection(const eval::RejectionScore& score, RunRecord& r) {
  r.precision = score.precision();
  r.precision_without_boundary = score.precision_without_boundary();
  r.recall = score.recall();
  r.true_positive = score.true_positive;
  r.false_positive = score.false_positive;
  r.false_positive_boundary = score.boundary_false_positive;
  r.true_negative_boundary = score.boundary_true_negative;
  r.false_negative = score.false_negative;
  r.true_negative = score.true_negative;
}

void check_sweep_inputs(const SweepPlan& plan) {
  for (const auto& cell : plan.cells) {
    try {
      sim::Scenario scenario =
          sim::load_scenario(plan.spec.scenarios[cell.scenario].path,
                             cell_overrides(plan, cell, ParameterTarget::kScenario));
      sim::scale_camera(scenario.camera, plan.spec.width);  // the rendered size must be usable
    } catch (const Error& e) {
      // Name the sweep's levels too: an override's error points into the file.
      fail("sweep cell " + cell.label, e.what());
    }
    const std::string detector = cell_detector(plan, cell);
    const std::vector<YamlOverride> detector_keys =
        cell_overrides(plan, cell, ParameterTarget::kDetector);
    if (detector != "sim") {
      try {  // a known detector whose files load now, not in its first job
        slam::load_detector_config(runner::default_detector_config(detector));
      } catch (const Error& e) {
        fail("sweep cell " + cell.label, e.what());
      }
      if (!detector_keys.empty())
        fail("sweep cell " + cell.label,
             "detector." + detector_keys.front().key +
                 " applies to the simulated detector only, not to detector=" + detector);
    }
    slam::load_sim_detector_config(overrides_to_node(detector_keys, "detector"),
                                   cell.label + " (detector settings)",
                                   runner::sim_detector_config(runner::PerceptionChoice{}));
    slam::RejectionParams params;
    for (const auto& s : cell_overrides(plan, cell, ParameterTarget::kRejection))
      slam::apply_rejection_setting(params, s, cell.label + " (rejection." + s.key + ")");
  }
}

DatasetRecord run_render_job(const SweepPlan& plan, const SweepLayout& layout,
                             const SweepJob& job) {
  const auto start = std::chrono::steady_clock::now();
  const SweepCell& cell = plan.cells.at(job.cell);
  const SweepScenario& source = plan.spec.scenarios.at(cell.scenario);
  sim::Scenario scenario =
      sim::load_scenario(source.path, cell_overrides(plan, cell, ParameterTarget::kScenario));
  sim::RenderRequest request;
  request.dataset.output = layout.dataset_dir(job.id);
  request.dataset.overwrite = true;  // a dataset without its record is from a killed job
  request.frames = plan.spec.frames;
  request.seed = static_cast<uint64_t>(job.seed);
  request.width = plan.spec.width;
  request.progress = false;
  fs::create_directories(fs::path(request.dataset.output).parent_path());
  const sim::RenderSummary rendered = sim::render_dataset(scenario, request);

  DatasetRecord record;
  record.id = job.id;
  record.frames = rendered.frames;
  const eval::MotionTruth truth(request.dataset.output);
  double sum = 0;
  size_t n = 0;
  for (double t : truth.timestamps()) {
    throw_if_interrupted(request.dataset.output);
    const double share = truth.moving_fraction(t);
    sum += share;
    record.moving_share_max = std::max(record.moving_share_max, share);
    ++n;
  }
  record.moving_share_mean = n ? sum / n : 0.0;
  sim::ContactSheetOptions sheet;
  sheet.rows = 1;
  sim::write_contact_sheet(request.dataset.output, layout.dataset_preview(job.id), sheet);
  record.render_seconds = seconds_since(start);
  write_record(layout.dataset_record(job.id), to_json(record));
  return record;
}

void add_accuracy(const std::vector<StampedPose>& truth, const std::vector<StampedPose>& trajectory,
                  const std::string& plot_path, RunRecord& r) {
  // A run that keeps too few poses to align (it lost the camera and began a
  // new map near the end) is an outcome of the sweep, not a failed job.
  if (trajectory.size() < 3) {
    r.ok = false;
    r.error = "only " + std::to_string(trajectory.size()) +
              " poses in the final trajectory: too few to evaluate";
    return;
  }
  const eval::MatchedTrajectories matched =
      eval::match_trajectories(truth, trajectory, {}, "groundtruth", r.mode);
  const eval::AteResult ate = eval::compute_ate(matched);
  r.ate_rmse = ate.statistics.rmse;
  r.ate_mean = ate.statistics.mean;
  r.ate_median = ate.statistics.median;
  r.ate_std = ate.statistics.std;
  r.ate_max = ate.statistics.max;
  eval::TrajectoryPlot plot = eval::ate_plot(matched, ate);
  plot.title = r.id;
  eval::write_trajectory_plot_svg(plot_path, plot);
  try {
    eval::PairSelection pairs;
    pairs.delta = r.rpe_delta_s;
    const eval::RpeResult rpe = eval::compute_rpe(matched, pairs);
    r.rpe_trans_rmse = rpe.translation_statistics.rmse;
    r.rpe_trans_std = rpe.translation_statistics.std;
    r.rpe_rot_rmse = rpe.rotation_statistics.rmse;
    r.rpe_rot_std = rpe.rotation_statistics.std;
  } catch (const Error&) {
    // Too short for the delta: RPE stays undefined (NaN), ATE still counts.
  }
}

RunRecord run_slam_job(const SweepPlan& plan, const SweepLayout& layout, const SweepJob& job) {
  const auto start = std::chrono::steady_clock::now();
  const SweepCell& cell = plan.cells.at(job.cell);
  const std::string dataset = layout.dataset_dir(job.dataset_id);
  if (!fs::is_directory(dataset) || !fs::is_regular_file(layout.dataset_record(job.dataset_id)))
    fail(dataset, "not rendered yet (run job " + job.dataset_id + " first)");

  RunRecord r;
  r.id = job.id;
  r.scenario = plan.spec.scenarios.at(cell.scenario).name;
  for (const auto& [name, level] : run_levels(plan.spec, cell, job.mode))
    r.parameters[name] = level;
  r.seed = job.seed;
  r.mode = job.mode;
  r.moving_share = read_dataset_record(layout.dataset_record(job.dataset_id)).moving_share_mean;

  fs::create_directories(fs::path(layout.run_dir(job.id)).parent_path());
  static const OutputKind kRunFolder{
      "sweep run",
      "result.json",
      {"result.json", "trajectory.txt", "states.txt", "atlas.txt", "stats.csv", "ate.svg",
       "system.log", "keypoints.csv", "system"}};
  StagedDirectory out(layout.run_dir(job.id), kRunFolder, /*overwrite=*/true);
  if (system::is_system_mode(job.mode)) {
    run_system_into(dataset, job, out.path(), out.final_path(), r);
    r.seconds = seconds_since(start);
    write_record((fs::path(out.path()) / "result.json").string(), to_json(r));
    out.commit();
    return r;
  }
  runner::RunOptions options;
  options.input.dataset = dataset;
  options.rejection.mode = job.mode;
  options.input.sync = plan.spec.sync_mapping;
  options.quiet = true;
  options.perception.detector = cell_detector(plan, cell);
  options.perception.detector_seed = static_cast<uint64_t>(job.seed);
  options.perception.detector_overrides = cell_overrides(plan, cell, ParameterTarget::kDetector);
  for (const auto& setting : cell_overrides(plan, cell, ParameterTarget::kRejection))
    slam::apply_rejection_setting(options.rejection.params, setting, "rejection." + setting.key);
  options.outputs.stats_csv = (fs::path(out.path()) / "stats.csv").string();
  try {
    const runner::RunSummary s = runner::run_sequence(options);
    r.frames = static_cast<int>(s.frames);
    r.tracked = static_cast<int>(s.tracked);
    r.lost = s.lost;
    r.keyframes = static_cast<int>(s.keyframes);
    r.median_frame_ms = s.median_ms;
    if (job.mode != "orb") {
      r.rejection_ms = s.filter_ms;
      add_rejection(s.score, r);
      r.precision_with_depth = s.score_with_depth.precision_without_boundary();
      r.recall_with_depth = s.score_with_depth.recall();
    }
    write_tum_trajectory((fs::path(out.path()) / "trajectory.txt").string(), s.trajectory,
                         "depot sweep run " + job.id + ": tracked frames only");
    write_text_file_atomic((fs::path(out.path()) / "states.txt").string(),
                           slam::format_frame_states(s.frame_states, "depot sweep run " + job.id));
    write_tum_trajectory((fs::path(out.path()) / "atlas.txt").string(), s.atlas_trajectory,
                         "depot sweep run " + job.id +
                             ": every frame with a pose, each in its own atlas map's frame");
    const std::vector<StampedPose> truth =
        read_tum_trajectory((fs::path(dataset) / "groundtruth.txt").string());
    add_accuracy(truth, s.trajectory, (fs::path(out.path()) / "ate.svg").string(), r);
    add_atlas_accuracy(truth, s.atlas_trajectory, s.frame_states, r);
  } catch (const Error& e) {
    throw_if_interrupted(job.id);
    // A run that tracks no frame is an outcome of the sweep, not a crash.
    if (std::string(e.what()).find(runner::kNoFrameTracked) == std::string::npos) throw;
    r.ok = false;
    r.error = e.what();
    r.frames = plan.spec.frames;
  }
  r.seconds = seconds_since(start);
  write_record((fs::path(out.path()) / "result.json").string(), to_json(r));
  out.commit();
  return r;
}

}  // namespace depot::harness
