// `depot slam ...`: run the SLAM system over a TUM RGB-D folder, with the
// paper's dynamic-feature rejection in one of its ablation modes.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "common/error.h"
#include "common/staged_file.h"
#include "common/tum_io.h"
#include "common/yaml_overrides.h"
#include "dataset/ros2/bag_layout.h"
#include "slam/io/frame_states_file.h"
#include "slam/reject/rejection_settings.h"
#include "tools/depot/cli_errors.h"
#include "tools/depot/commands.h"
#include "tools/depot/detector_options.h"
#include "tools/depot/output_paths.h"
#include "tools/depot/system_run_command.h"
#include "tools/runner/rejection_overlay.h"
#include "tools/runner/slam_runner.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

// A rejection setting of the table (slam/reject/rejection_settings.h) that a
// flag of its own sets.
const slam::RejectionSetting& setting(const char* key) {
  const slam::RejectionSetting* s = slam::find_rejection_setting(key);
  if (!s) throw std::logic_error(std::string("no rejection setting ") + key);
  return *s;
}

// Options a mode does not use are refused rather than silently ignored.
void check_options_used_by_mode(const std::string& mode, const CLI::App& cmd) {
  const slam::RejectionMode m = slam::parse_rejection_mode(mode);
  const bool detector = slam::mode_uses_detector(m);
  const struct {
    const char* option;
    bool used;
  } options[] = {
      {"--detector", detector},
      {"--detector-config", detector},
      {"--detections", detector},
      {"--detector-seed", detector},
      {"--detector-set", detector},
      {"--classes", detector},
      {"--no-run-ahead", detector},
      {"--rejection-set", m == slam::RejectionMode::kFull || m == slam::RejectionMode::kMasked},
      {"--keypoints", m != slam::RejectionMode::kOrb},
      {"--overlays", m != slam::RejectionMode::kOrb},
      {"--background-margin", setting("background_margin").acts_in(m)},
      {"--ego-flow", setting("ego_flow").acts_in(m)},
      {"--test-static", setting("test_static").acts_in(m)},
      {"--person-mask", setting("person_mask").acts_in(m)},
      {"--segmenter", m == slam::RejectionMode::kMasked}};
  for (const auto& o : options)
    if (!o.used && cmd.count(o.option))
      fail_usage(o.option, std::string("has no effect in --mode ") + mode +
                               " (drop it, or choose a mode that uses it)");
}

struct RunArgs {
  runner::RunOptions options;
  std::string output;
  std::string keyframes;
  size_t frames = 0;
  std::string system;
};

// --dense-mask's default follows the mode: the rejection's masks where it
// makes them, else none (plain orb and orb+lk make none), said once.
void choose_dense_mask(RunArgs& a, const CLI::App& cmd) {
  if (a.options.outputs.dense_map.empty()) return;
  const slam::RejectionMode m = slam::parse_rejection_mode(a.options.rejection.mode);
  const bool masks = m != slam::RejectionMode::kOrb && m != slam::RejectionMode::kOrbLk;
  if (cmd.count("--dense-mask")) {
    if (a.options.outputs.dense_mask == "rejection" && !masks)
      fail_usage("--dense-mask rejection",
                 "mode " + a.options.rejection.mode +
                     " leaves no moving mask (orb+yolo, full and masked do); give --dense-mask "
                     "labels or none");
    return;
  }
  if (masks) return;
  a.options.outputs.dense_mask = "none";
  if (!a.options.quiet)
    std::fprintf(stderr,
                 "depot slam run: mode %s rejects nothing, so the dense map keeps every pixel "
                 "(--dense-mask labels leaves a simulated dataset's movers out)\n",
                 a.options.rejection.mode.c_str());
}

// --detector-set keys are checked against the simulated detector's table
// before any work: a wrong key is a wrong command line, not a failed run.
void check_detector_settings(const runner::RunOptions& o) {
  if (o.perception.detector_overrides.empty()) return;
  const std::string type = o.perception.detector.empty() ? "sim" : o.perception.detector;
  if (type != "sim")
    fail_usage("--detector-set", "applies to the simulated detector only (edit the " + type +
                                     " detector's YAML instead)");
  // The file's own problems are a failed read (exit 1); the overrides' a usage error.
  const slam::SimDetectorConfig base = slam::load_sim_detector_config_file(
      o.perception.detector_config.empty() ? runner::default_detector_config("sim")
                                           : o.perception.detector_config);
  try {
    slam::load_sim_detector_config(
        overrides_to_node(o.perception.detector_overrides, "--detector-set"), "--detector-set",
        base);
  } catch (const Error& e) {
    throw CLI::ValidationError(e.what());
  }
}

// Another program as the system: only the options it can honour.
void run_slam_system(const RunArgs& a, const CLI::App& cmd) {
  for (const CLI::Option* option : cmd.get_options()) {
    const std::string name = option->get_name();
    if (option->count() == 0 || name == "dataset" || name == "--output" || name == "--system" ||
        name == "--keypoints" || name == "--quiet")
      continue;
    fail_usage(name, "has no effect with --system (the system's own file sets how it runs)");
  }
  OutputPaths outputs;
  outputs.add_input_folder("the dataset", a.options.input.dataset);
  outputs.add_file("-o", a.output);
  outputs.add_file("the states file of -o", slam::frame_states_path(a.output));
  outputs.add_file("the system log of -o", system_log_path(a.output));
  outputs.add_file("--keypoints", a.options.outputs.keypoints_csv);
  outputs.check();
  SystemRunArgs s;
  s.dataset = a.options.input.dataset;
  s.system = a.system;
  s.output = a.output;
  s.keypoints = a.options.outputs.keypoints_csv;
  s.quiet = a.options.quiet;
  run_external_system(s);
}

void run_slam(RunArgs& a, const CLI::App& cmd) {
  if (!a.system.empty()) return run_slam_system(a, cmd);
  check_options_used_by_mode(a.options.rejection.mode, cmd);
  if (cmd.count("--segmenter") &&
      a.options.rejection.params.person_mask == slam::RejectionParams::PersonMask::kDepth)
    fail_usage("--segmenter",
               "has no effect with --person-mask depth (choose segmentation or both)");
  if (a.options.outputs.dense_map.empty())
    for (const char* option : {"--dense-mask", "--dense-voxel", "--dense-max-depth",
                               "--dense-min-views", "--dense-no-free-space"})
      if (cmd.count(option)) fail_usage(option, "has no effect without --dense-map");
  if (a.options.map.localise_only && a.options.map.load_map.empty())
    fail_usage("--localise-only", "needs a map to localise in (--load-map M)");
  if (a.options.map.localise_only && !a.options.outputs.dense_map.empty())
    fail_usage("--dense-map",
               "has nothing to fuse with --localise-only (a localisation run adds no keyframes, "
               "and a saved map keeps no depth images; make the dense map in the run that builds "
               "the map)");
  choose_dense_mask(a, cmd);
  check_detector_settings(a.options);
  // Every output must be writable before a long run starts, not after it,
  // and no two of them (or an input) may be one file.
  const std::string states_path = slam::frame_states_path(a.output);
  const std::string atlas_path = slam::atlas_trajectory_path(a.output);
  OutputPaths outputs;
  outputs.add_input_folder("the dataset", a.options.input.dataset);
  outputs.add_input("--load-map", a.options.map.load_map);
  outputs.add_input("--settings", a.options.input.settings);
  outputs.add_input("--vocabulary", a.options.input.vocabulary);
  outputs.add_file("-o", a.output);
  outputs.add_file("the states file of -o", states_path);
  outputs.add_file("the atlas trajectory of -o", atlas_path);
  outputs.add_file("--keyframes", a.keyframes);
  outputs.add_file("--stats", a.options.outputs.stats_csv);
  outputs.add_file("--keypoints", a.options.outputs.keypoints_csv);
  outputs.add_file("--dense-map", a.options.outputs.dense_map);
  outputs.add_file("--save-map", a.options.map.save_map);
  outputs.add_folder("--overlays", a.options.outputs.overlays);
  outputs.check();
  for (const std::string* path : std::initializer_list<const std::string*>{
           &a.output, &states_path, &atlas_path, &a.keyframes, &a.options.outputs.stats_csv,
           &a.options.outputs.keypoints_csv, &a.options.outputs.dense_map, &a.options.map.save_map})
    if (!path->empty()) check_output_file(*path);
  if (!a.options.outputs.overlays.empty())
    check_replaceable(a.options.outputs.overlays, runner::overlay_folder_kind(), false);
  if (cmd.count("--frames")) a.options.input.frames = a.frames;
  if (!a.options.quiet)
    std::fprintf(stderr, "depot slam run: %s, mode %s\n", a.options.input.dataset.c_str(),
                 a.options.rejection.mode.c_str());
  runner::RunSummary s = runner::run_sequence(a.options);
  // The trajectory, its states and the atlas trajectory appear together:
  // all staged, then committed.
  const std::string header =
      "depot-slam (" + a.options.rejection.mode + ") of " + a.options.input.dataset;
  StagedFile trajectory(a.output), states(states_path), atlas(atlas_path);
  trajectory.stream() << format_tum_trajectory(s.trajectory, header + ": tracked frames only");
  states.stream() << slam::format_frame_states(s.frame_states,
                                               header + ": the state of every frame given");
  atlas.stream() << format_tum_trajectory(
      s.atlas_trajectory,
      header + ": every frame with a pose, each in its own atlas map's frame (map numbers in " +
          fs::path(states_path).filename().string() + ")");
  trajectory.commit();
  states.commit();
  atlas.commit();
  if (!a.keyframes.empty())
    write_tum_trajectory(a.keyframes, s.keyframes_trajectory, "depot-slam keyframes");
  std::printf(
      "tracked %zu of %zu frames (%.1f %%; %d lost, %d relocalised) in mode %s: %zu keyframes, %zu "
      "map points; per frame median %.1f ms, p95 %.1f ms (extraction %.1f, tracking %.1f",
      s.tracked, s.frames, 100.0 * s.tracked_share(), s.lost, s.relocalized,
      a.options.rejection.mode.c_str(), s.keyframes, s.map_points, s.median_ms, s.p95_ms,
      s.extract_ms, s.track_ms);
  if (a.options.rejection.mode != "orb")
    std::printf(
        ", rejection %.1f incl. flow %.1f, waited %.1f (p95 %.1f) for the %s detector "
        "taking %.1f",
        s.filter_ms, s.flow_ms, s.wait_ms, s.wait_p95_ms,
        s.detector_name.empty() ? "(no)" : s.detector_name.c_str(), s.detect_ms);
  std::printf("); wrote %s, %s and %s\n", a.output.c_str(), states_path.c_str(),
              atlas_path.c_str());
  std::vector<slam::LoopClosure> loops, merges;
  for (const slam::LoopClosure& l : s.loops) (l.merge ? merges : loops).push_back(l);
  std::printf("loops closed: %zu", loops.size());
  for (const slam::LoopClosure& l : loops)
    std::printf("%s keyframe %ld (t %.2f) with %ld, %d matches, moved %.3f m after %.1f m",
                &l == &loops.front() ? " (" : "; ", l.keyframe, l.timestamp, l.matched, l.matches,
                l.correction_m, l.path_m);
  std::printf(
      "%s, %d global bundle adjustments, %d look-alike places refused; relocalisation median "
      "%.1f ms over %d lost frames\n",
      loops.empty() ? "" : ")", s.global_adjustments, s.loops_refused, s.lost_ms, s.lost);
  std::printf("atlas: %d map%s left, %zu merge%s", s.maps, s.maps == 1 ? "" : "s", merges.size(),
              merges.size() == 1 ? "" : "s");
  for (const slam::LoopClosure& l : merges)
    std::printf("%s keyframe %ld (t %.2f) with %ld, %d matches: map %d (%d keyframes) into map %d",
                &l == &merges.front() ? " (" : "; ", l.keyframe, l.timestamp, l.matched, l.matches,
                l.moved_map, l.moved_keyframes, l.into_map);
  std::printf(
      "%s, %d not confirmed by the keyframe's neighbours; %d young map%s rejoined an older one "
      "(a frame relocalised there)\n",
      merges.empty() ? "" : ")", s.merges_unconfirmed, s.maps_rejoined,
      s.maps_rejoined == 1 ? "" : "s");
  if (!a.options.outputs.dense_map.empty())
    std::printf("dense map: %zu points from %d keyframes (masks: %s%s%s), wrote %s\n",
                s.dense_points, s.dense_keyframes, a.options.outputs.dense_mask.c_str(),
                s.dense_left_out ? "; left out: " : "",
                s.dense_left_out ? (std::to_string(s.dense_left_out) +
                                    " of the loaded map's keyframes, with no frame in this "
                                    "dataset or no rejection mask of this run")
                                       .c_str()
                                 : "",
                a.options.outputs.dense_map.c_str());
  for (const auto& other : s.dense_other_maps) {
    if (other.path.empty())
      std::printf("dense map of atlas map %d: none (%s)\n", other.map, other.reason.c_str());
    else
      std::printf(
          "dense map of atlas map %d (its own frame): %zu points from %d keyframes, wrote %s\n",
          other.map, other.points, other.keyframes, other.path.c_str());
  }
  if (a.options.pacing.rate_hz > 0) {
    std::printf("input %g Hz, run-ahead %s: %zu frames handled after their turn\n",
                a.options.pacing.rate_hz, a.options.pacing.run_ahead ? "on" : "off", s.late_frames);
  }
  if (s.scored && a.options.rejection.mode != "orb") {
    print_rejection_vs_truth(s.score);
    const eval::RejectionScore& d = s.score_with_depth;
    const long moving = s.score.true_positive + s.score.false_negative;
    const long moving_d = d.true_positive + d.false_negative;
    std::printf(
        "  keypoints with depth (can start map points; %ld of %ld moving ones): precision %.3f "
        "recall %.3f with boundary points left out\n",
        moving_d, moving, d.precision_without_boundary(), d.recall());
  }
}

}  // namespace

void add_rejection_options(CLI::App* cmd, runner::RunOptions& o) {
  cmd->add_option("--mode", o.rejection.mode,
                  "Rejection mode: the paper's ablation (orb = plain ORB-SLAM2, no rejection; "
                  "orb+yolo, orb+lk, full) or masked (objects segmented inside tracked boxes)")
      ->check(CLI::IsMember({"orb", "orb+yolo", "orb+lk", "full", "masked"}));
  cmd->add_option(
         "--detector", o.perception.detector,
         "Detector: sim (simulated datasets), darknet (Yolo-Fastest), xl (Yolo-Fastest XL), "
         "fastestdet, yolov5, file")
      ->default_str("sim on simulated datasets, else darknet");
  cmd->add_option("--detector-config", o.perception.detector_config,
                  "Detector YAML (dnn models, or the simulated detector)")
      ->default_str("scenes/detectors/ of the detector");
  cmd->add_option("--detections", o.perception.detections, "Detections file for --detector file");
  cmd->add_option("--classes", o.perception.classes, "A-priori class table YAML")
      ->default_str("scenes/apriori/depot.yaml for sim, else coco.yaml");
  cmd->add_option("--detector-seed", o.perception.detector_seed,
                  "Seed of the simulated detector's errors");
  add_detector_set_option(
      cmd, o.perception.detector_overrides,
      "Change a simulated-detector key, e.g. --detector-set miss_rate=0.2 (repeatable)");
  cmd->add_option("--settings", o.input.settings, "Settings YAML")
      ->default_str("the dataset's calibration.yaml");
  const slam::RejectionSetting& margin = setting("background_margin");
  cmd->add_option("--background-margin", margin.real(o.rejection.params), margin.help)
      ->check(CLI::Range(margin.lo, margin.hi));
  cmd->add_flag("--ego-flow", setting("ego_flow").flag(o.rejection.params),
                setting("ego_flow").help);
  cmd->add_flag("--test-static", setting("test_static").flag(o.rejection.params),
                setting("test_static").help);
  cmd->add_option_function<std::string>(
         "--person-mask",
         [&o](const std::string& v) {
           o.rejection.params.person_mask = slam::parse_person_mask(v);
         },
         setting("person_mask").help)
      ->check(CLI::IsMember({"depth", "segmentation", "both"}))
      ->default_str("depth");
  cmd->add_option("--segmenter", o.perception.segmenter, "masked: person segmenter YAML")
      ->default_str("scenes/segmenters/selfie.yaml");
  cmd->add_option_function<std::vector<std::string>>(
      "--rejection-set",
      [&o](const std::vector<std::string>& texts) {
        for (const auto& t : texts)
          slam::apply_rejection_setting(o.rejection.params,
                                        parse_yaml_override(t, "--rejection-set"),
                                        "--rejection-set " + t);
      },
      "Change a rejection setting as a sweep's rejection.KEY, e.g. --rejection-set "
      "mask.extent=0.8, or motion=true for masked to reject movers no detector names "
      "(repeatable; keys: " +
          slam::rejection_setting_keys() +
          "; each explained in slam/reject/rejection_settings.cc)");
  cmd->add_option_function<std::string>(
         "--mapping", [&o](const std::string& v) { o.input.sync = v == "sync"; },
         "Local mapping: threaded (its own thread, as ORB-SLAM2; faster, not reproducible) or "
         "sync (in the tracking thread, reproducible)")
      ->check(CLI::IsMember({"sync", "threaded"}))
      ->default_str("threaded");
}

void register_slam_commands(CLI::App& app) {
  CLI::App* slam = app.add_subcommand("slam", "Run the RGB-D SLAM system");
  slam->require_subcommand(1);
  auto args = std::make_shared<RunArgs>();
  CLI::App* run =
      slam->add_subcommand("run", "Track a TUM RGB-D folder and write the trajectory (TUM format)");
  run->add_option("dataset", args->options.input.dataset,
                  "TUM RGB-D folder (associations.txt or rgb.txt + depth.txt) or ROS 2 bag (.mcap)")
      ->required();
  slam::BagTopics& topics = args->options.input.topics;
  run->add_option("--colour-topic", topics.colour, "A bag's colour images (sensor_msgs/Image)")
      ->default_str(ros2::kColourTopic);
  run->add_option("--depth-topic", topics.depth,
                  "A bag's depth images registered to colour (16UC1 mm or 32FC1 m)")
      ->default_str(ros2::kDepthTopic);
  run->add_option("--camera-info-topic", topics.colour_info,
                  "A bag's colour camera_info (the camera, unless --settings names one)")
      ->default_str(ros2::kColourInfoTopic);
  run->add_option("-o,--output", args->output,
                  "Trajectory file (tracked frames, camera-to-world); the state of every frame "
                  "goes beside it (run.txt -> run.states.txt)")
      ->required();
  run->add_option("--keyframes", args->keyframes, "Also write the keyframe trajectory here");
  run->add_option("--frames", args->frames, "Only the first N frames")
      ->check(CLI::Range(1, 10000000))
      ->default_str("all");
  run->add_option("--stats", args->options.outputs.stats_csv,
                  "Per-frame statistics CSV (|Z| |Q| |Q->P| |P|, flow, times)");
  run->add_option("--keypoints", args->options.outputs.keypoints_csv,
                  "Per-keypoint CSV: position, set (Z/Q/P), kept, depth and, on simulated data, "
                  "whether it is on a moving object or its boundary, and the instance there");
  run->add_option("--overlays", args->options.outputs.overlays,
                  "Folder of per-frame pictures of the rejection (boxes, object masks, keypoints "
                  "coloured by decision and, on simulated data, by truth)");
  run->add_option("--overlays-every", args->options.outputs.overlays_every,
                  "A picture of every n-th frame")
      ->check(CLI::Range(1, 1000000));
  run->add_option("--vocabulary", args->options.input.vocabulary,
                  "Place-recognition vocabulary (default: the settings' place_recognition."
                  "vocabulary, else the one the build trained; `depot slam vocabulary train`)");
  run->add_flag_callback(
      "--no-loop-closing", [args] { args->options.input.loop_closing = false; },
      "Do not detect or close loops (place recognition still relocalises)");
  run->add_option("--load-map", args->options.map.load_map,
                  "Start from a map saved by --save-map (same vocabulary and camera); the first "
                  "frame relocalises in it");
  run->add_flag("--localise-only", args->options.map.localise_only,
                "Track against the loaded map without changing it: no keyframes, no points");
  run->add_option("--save-map", args->options.map.save_map,
                  "Write the map at the end (versioned binary with a checksum; staged)");
  run->add_option("--dense-map", args->options.outputs.dense_map,
                  "Write a dense static map at the end (PLY): the final keyframes' depth fused "
                  "into voxels, moving pixels left out (--dense-mask)");
  run->add_option("--dense-mask", args->options.outputs.dense_mask,
                  "What leaves moving pixels out of the dense map: the rejection's masks "
                  "(orb+yolo, full, masked), the simulated dataset's labels, or none")
      ->check(CLI::IsMember({"rejection", "labels", "none"}))
      ->capture_default_str();
  run->add_option("--dense-voxel", args->options.outputs.dense.voxel_m, "Dense map voxel edge (m)")
      ->check(CLI::Range(0.001, 1.0))
      ->capture_default_str();
  run->add_option("--dense-max-depth", args->options.outputs.dense.max_depth_m,
                  "Depth beyond this (m) stays out of the dense map")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  run->add_option("--dense-min-views", args->options.outputs.dense.min_views,
                  "Dense map voxels seen from fewer keyframes are left out")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  run->add_flag_callback(
      "--dense-no-free-space", [args] { args->options.outputs.dense.free_space = false; },
      "Keep dense map voxels that other keyframes see through (by default they are left out: "
      "something was there and moved away)");
  run->add_flag("-q,--quiet", args->options.quiet, "No progress line");
  run->add_option("--rate", args->options.pacing.rate_hz,
                  "Input rate (Hz) of an emulated camera: frame i arrives at i / HZ s (0 = as "
                  "fast as possible)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  run->add_flag_callback(
      "--no-run-ahead", [args] { args->options.pacing.run_ahead = false; },
      "Track each frame as it arrives, its detector started then (default: hand frame i+1 to the "
      "detector before tracking frame i, tracking it once frame i+1 has arrived)");
  add_rejection_options(run, args->options);
  run->add_option("--system", args->system,
                  "Run another SLAM system instead: a system YAML file (command template, "
                  "trajectory format, time limit; see scenes/systems/) or a shipped system's "
                  "name, e.g. open3d_odometry");
  run->callback([args, run] { run_slam(*args, *run); });
  register_vocabulary_commands(slam);
  register_map_commands(slam);
}

}  // namespace depot::cli
