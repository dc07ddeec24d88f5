// `depot eval ate|rpe GT EST`: trajectory accuracy as TUM's tools and evo
// compute it, printed as a block of figures, optionally as JSON and SVG.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "common/staged_file.h"
#include "common/tum_io.h"
#include "dataset/ros2/bag_trajectory.h"
#include "eval/ate.h"
#include "eval/improvement.h"
#include "eval/maps_ate.h"
#include "eval/matched_trajectories.h"
#include "eval/report_json.h"
#include "eval/result_plots.h"
#include "eval/rpe.h"
#include "eval/trajectory_plot.h"
#include "slam/io/frame_states_file.h"
#include "tools/depot/commands.h"
#include "tools/depot/output_paths.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

struct CommonArgs {
  std::string reference_path;
  std::string estimate_path;
  AssociationOptions association;
  std::string json_path;
  std::string plot_path;
};

struct AteArgs {
  CommonArgs common;
  std::string states_path;  // "" = the estimate's states file when it exists
  bool sim3 = false;
  double baseline_rmse = 0.0;
  CLI::Option* baseline_option = nullptr;  // tells whether --baseline-rmse was given
};

struct RpeArgs {
  CommonArgs common;
  double delta = 1.0;
  std::string delta_unit = "s";
};

// A readable check for options that must be > 0 (CLI11's own prints DBL_MAX).
CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || v <= 0.0) {
          return "must be a positive number, got '" + text + "'";
        }
        return "";
      },
      "POSITIVE");
}

void add_common_options(CLI::App* command, CommonArgs& args) {
  command
      ->add_option(
          "GT", args.reference_path,
          "ground-truth trajectory (TUM format, or a ROS 2 bag: its /depot/ground_truth/pose)")
      ->required();
  command->add_option("EST", args.estimate_path, "estimated trajectory (TUM format)")->required();
  command
      ->add_option("--max-dt", args.association.max_difference,
                   "largest |dt| (s) for associating poses by timestamp")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--offset", args.association.offset,
                   "time offset (s) added to the estimate's timestamps")
      ->capture_default_str();
  command->add_option("--json", args.json_path, "also write a JSON report to this file");
  command->add_option("--plot", args.plot_path, "also write an SVG figure to this file");
}

void print_header(const char* metric, const eval::MatchedTrajectories& m) {
  std::printf("%s  %s  vs ground truth  %s\n", metric, m.estimate_name.c_str(),
              m.reference_name.c_str());
  std::printf(
      "  matched poses  %zu of %zu estimated (%zu ground truth), |dt| < %g s, offset %g s\n",
      m.size(), m.estimate_size, m.reference_size, m.association.max_difference,
      m.association.offset);
}

void print_outputs(const CommonArgs& args) {
  if (!args.json_path.empty()) std::printf("  json           %s\n", args.json_path.c_str());
  if (!args.plot_path.empty()) std::printf("  plot           %s\n", args.plot_path.c_str());
}

// --json and --plot must be writable before the work, not after it, and
// neither may be the other or an input.
void check_outputs(const CommonArgs& args) {
  OutputPaths outputs;
  outputs.add_input("GT", args.reference_path);
  outputs.add_input("EST", args.estimate_path);
  outputs.add_file("--json", args.json_path);
  outputs.add_file("--plot", args.plot_path);
  outputs.check();
  if (!args.json_path.empty()) check_output_file(args.json_path);
  if (!args.plot_path.empty()) check_output_file(args.plot_path);
}

// The estimate's frame states: --states, or else the file `depot slam run`
// writes beside the trajectory, when it is there. Empty path: none.
std::string states_file(const AteArgs& args) {
  if (!args.states_path.empty()) return args.states_path;
  const std::string beside = slam::frame_states_path(args.common.estimate_path);
  std::error_code ec;
  return fs::is_regular_file(beside, ec) ? beside : "";
}

// ATE over every map of the atlas (eval/maps_ate.h), when the states name
// each frame's map and the atlas trajectory is beside the estimate.
std::optional<eval::MapsAte> maps_ate(const AteArgs& args,
                                      const std::vector<StampedPose>& reference,
                                      const std::string& states_path,
                                      const std::vector<slam::StampedFrameState>& states,
                                      eval::AlignmentKind alignment) {
  const std::vector<int> maps = slam::maps_of_posed_frames(states);
  const std::string atlas_path = slam::atlas_trajectory_path(args.common.estimate_path);
  std::error_code ec;
  if (maps.empty() || !fs::is_regular_file(atlas_path, ec)) return std::nullopt;
  const std::vector<StampedPose> atlas = read_tum_trajectory(atlas_path);
  if (atlas.size() != maps.size()) {
    std::fprintf(stderr,
                 "depot: warning: %s: holds %zu poses but %s names %zu frames with a pose (is it "
                 "the atlas trajectory of this run?); no ATE over all maps\n",
                 atlas_path.c_str(), atlas.size(), states_path.c_str(), maps.size());
    return std::nullopt;
  }
  return eval::compute_maps_ate(reference, atlas, maps, states.size(), args.common.association,
                                alignment, args.common.reference_path, atlas_path);
}

void run_ate(const AteArgs& args) {
  check_outputs(args.common);
  const std::vector<StampedPose> reference = ros2::read_trajectory(args.common.reference_path);
  const eval::MatchedTrajectories matched = eval::match_trajectories(
      reference, read_tum_trajectory(args.common.estimate_path), args.common.association,
      args.common.reference_path, args.common.estimate_path);
  // ATE only sees the frames with a pose; the states say how many were given.
  const std::string states_path = states_file(args);
  std::vector<slam::StampedFrameState> states;
  std::optional<slam::TrackedShare> tracked;
  if (!states_path.empty()) {
    states = slam::read_frame_states(states_path);
    tracked = slam::tracked_share(states);
    if (tracked->tracked != matched.estimate_size)
      std::fprintf(stderr,
                   "depot: warning: %s: lists %zu tracked frames but %s has %zu poses (is it the "
                   "states file of this trajectory?)\n",
                   states_path.c_str(), tracked->tracked, args.common.estimate_path.c_str(),
                   matched.estimate_size);
  }
  eval::AteOptions options;
  options.alignment = args.sim3 ? eval::AlignmentKind::kSimilarity : eval::AlignmentKind::kRigid;
  const eval::AteResult ate = eval::compute_ate(matched, options);
  const std::optional<eval::MapsAte> all_maps =
      states_path.empty() ? std::nullopt
                          : maps_ate(args, reference, states_path, states, options.alignment);

  nlohmann::json report = eval::ate_report_json(matched, ate);
  double improvement = 0.0;
  const bool has_baseline = args.baseline_option && args.baseline_option->count() > 0;
  if (has_baseline) {
    improvement = eval::improvement_percent(args.baseline_rmse, ate.statistics.rmse);
    report["baseline_rmse"] = args.baseline_rmse;
    report["improvement_percent"] = improvement;
  }
  if (tracked) {
    report["states"] = states_path;
    report["frames_given"] = tracked->frames;
    report["frames_tracked"] = tracked->tracked;
    report["tracked_share"] = tracked->share();
  }
  if (all_maps) {
    const eval::ErrorStatistics& m = all_maps->statistics;
    report["all_maps"] = {
        {"atlas_trajectory", slam::atlas_trajectory_path(args.common.estimate_path)},
        {"rmse", m.rmse},
        {"mean", m.mean},
        {"median", m.median},
        {"max", m.max},
        {"posed", all_maps->posed},
        {"posed_share", all_maps->posed_share()},
        {"main_map_share", all_maps->main_map_share()},
        {"maps", all_maps->maps},
        {"maps_left_out", all_maps->maps_left_out},
        {"poses_left_out", all_maps->poses_left_out}};
  }
  if (!args.common.json_path.empty()) eval::write_json_file(args.common.json_path, report);
  if (!args.common.plot_path.empty()) {
    eval::write_trajectory_plot_svg(args.common.plot_path, eval::ate_plot(matched, ate));
  }

  const eval::ErrorStatistics& s = ate.statistics;
  print_header("ATE", matched);
  if (tracked)
    std::printf("  tracked share  %.1f %% (%zu of %zu frames given; states %s)\n",
                100.0 * tracked->share(), tracked->tracked, tracked->frames, states_path.c_str());
  if (all_maps) {
    std::printf(
        "  all maps       rmse %.6f m over the %zu frames with a pose in any of %zu maps "
        "(%.1f %% of those given), each map aligned on its own; the trajectory's map holds "
        "%.1f %%\n",
        all_maps->statistics.rmse, all_maps->posed, all_maps->maps, 100.0 * all_maps->posed_share(),
        100.0 * all_maps->main_map_share());
    if (all_maps->maps_left_out)
      std::printf("                 %zu maps (%zu poses) too small to align are not in the rmse\n",
                  all_maps->maps_left_out, all_maps->poses_left_out);
  }
  std::printf("  alignment      %s, scale %.6g\n", eval::to_string(ate.alignment_kind).c_str(),
              ate.alignment.scale);
  std::printf("  translational error (m)\n");
  std::printf("        rmse  %.6f\n        mean  %.6f\n      median  %.6f\n", s.rmse, s.mean,
              s.median);
  std::printf("         std  %.6f\n         min  %.6f\n         max  %.6f\n", s.std, s.min, s.max);
  if (has_baseline) {
    std::printf("  improvement over baseline rmse %.6g m (Eq. 9): %.2f %%\n", args.baseline_rmse,
                improvement);
  }
  print_outputs(args.common);
}

void run_rpe(const RpeArgs& args) {
  check_outputs(args.common);
  const eval::MatchedTrajectories matched = eval::load_matched_trajectories(
      args.common.reference_path, args.common.estimate_path, args.common.association);
  eval::PairSelection selection;
  selection.delta = args.delta;
  selection.unit = args.delta_unit == "f" ? eval::DeltaUnit::kFrames : eval::DeltaUnit::kSeconds;
  const eval::RpeResult rpe = eval::compute_rpe(matched, selection);

  if (!args.common.json_path.empty()) {
    eval::write_json_file(args.common.json_path, eval::rpe_report_json(matched, rpe));
  }
  if (!args.common.plot_path.empty()) {
    eval::write_trajectory_plot_svg(args.common.plot_path, eval::rpe_plot(matched, rpe));
  }

  const eval::ErrorStatistics& t = rpe.translation_statistics;
  const eval::ErrorStatistics& r = rpe.rotation_statistics;
  print_header("RPE", matched);
  std::printf("  delta          %g %s, %zu pairs\n", selection.delta,
              eval::to_string(selection.unit).c_str(), rpe.pairs.size());
  std::printf("              translation (m)  rotation (deg)\n");
  const struct {
    const char* name;
    double t, r;
  } rows[] = {{"rmse", t.rmse, r.rmse}, {"mean", t.mean, r.mean}, {"median", t.median, r.median},
              {"std", t.std, r.std},    {"min", t.min, r.min},    {"max", t.max, r.max}};
  for (const auto& row : rows) std::printf("  %10s  %15.6f  %14.6f\n", row.name, row.t, row.r);
  print_outputs(args.common);
}

}  // namespace

void register_eval_commands(CLI::App& app) {
  CLI::App* group = app.add_subcommand(
      "eval",
      "Trajectory accuracy (ATE, RPE as TUM / evo), rejection, detectors and person segmenters");
  group->require_subcommand(1);
  register_perception_eval_commands(group);
  register_cloud_eval_command(group);
  register_realism_eval_command(group);
  register_rejection_eval_command(group);

  auto ate_args = std::make_shared<AteArgs>();
  CLI::App* ate = group->add_subcommand(
      "ate", "Absolute trajectory error after aligning the estimate (evo_ape -a)");
  add_common_options(ate, ate_args->common);
  ate->add_flag("--sim3", ate_args->sim3, "align with scale (Sim(3)) instead of SE(3)");
  ate->add_option("--states", ate_args->states_path,
                  "frame states of the estimate (`depot slam run` writes them beside the "
                  "trajectory): also print the tracked share, and with the atlas trajectory "
                  "beside EST (run.atlas.txt) the ATE over the frames of every map")
      ->default_str("EST's states file (run.txt -> run.states.txt) when it exists");
  ate_args->baseline_option =
      ate->add_option("--baseline-rmse", ate_args->baseline_rmse,
                      "a baseline's ATE RMSE (m): also print the improvement, paper Eq. 9")
          ->check(positive_number());
  ate->callback([ate_args] { run_ate(*ate_args); });

  auto rpe_args = std::make_shared<RpeArgs>();
  CLI::App* rpe = group->add_subcommand(
      "rpe", "Relative pose error over a fixed delta (evo_rpe, TUM evaluate_rpe.py)");
  add_common_options(rpe, rpe_args->common);
  rpe->add_option("--delta", rpe_args->delta, "distance between compared poses")
      ->check(positive_number())
      ->capture_default_str();
  rpe->add_option("--delta-unit", rpe_args->delta_unit,
                  "unit of --delta: s (seconds) or f (frames)")
      ->check(CLI::IsMember({"s", "f"}))
      ->capture_default_str();
  rpe->callback([rpe_args] { run_rpe(*rpe_args); });
}

}  // namespace depot::cli
