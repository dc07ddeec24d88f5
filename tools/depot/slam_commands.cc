// `depot slam ...`: run the SLAM system over a TUM RGB-D folder.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "common/tum_io.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/system/system.h"
#include "tools/depot/commands.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

struct RunArgs {
  std::string dataset;
  std::string output;
  std::string settings;
  std::string keyframes;
  int frames = 0;
  bool sync = false;
  bool quiet = false;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

void run_slam(const RunArgs& a, const CLI::App& cmd) {
  slam::TumSequence sequence(a.dataset);
  slam::SlamSettings settings;
  std::string source = "defaults (TUM fr3 Kinect)";
  if (!sequence.calibration_path().empty()) {
    settings = slam::load_settings(sequence.calibration_path(), settings);
    source = sequence.calibration_path();
  }
  if (!a.settings.empty()) {
    settings = slam::load_settings(a.settings, settings);
    source = a.settings;
  }
  if (a.sync) settings.threaded_mapping = false;
  sequence.set_depth_factor(settings.camera.depth_factor);
  const size_t n = cmd.count("--frames") ? std::min<size_t>(a.frames, sequence.size()) : sequence.size();
  // Fail before any work if the output cannot be written.
  {
    fs::path out(a.output);
    std::error_code ec;
    fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
    if (!fs::is_directory(parent, ec)) fail(a.output, "output folder does not exist");
  }
  if (!a.quiet) std::fprintf(stderr, "depot slam run: %zu frames of %s; settings from %s\n", n, a.dataset.c_str(), source.c_str());

  slam::System system(settings);
  std::vector<double> total, extract, track;
  int lost = 0, relocalized = 0;
  Progress progress("slam", n, !a.quiet);
  cv::Mat bgr, depth;
  for (size_t i = 0; i < n; ++i) {
    throw_if_interrupted(a.dataset);
    sequence.load(i, bgr, depth);
    slam::TrackResult r = system.track(bgr, depth, sequence.entry(i).rgb_timestamp);
    total.push_back(r.timing.total_ms);
    extract.push_back(r.timing.extract_ms);
    track.push_back(r.timing.track_ms);
    lost += r.state == slam::TrackingState::kLost;
    relocalized += r.state == slam::TrackingState::kRelocalized;
    char detail[128];
    std::snprintf(detail, sizeof(detail), "frame %zu %s features %d inliers %d %.1f ms", i,
                  slam::tracking_state_name(r.state), r.kept, r.stats.inliers, r.timing.total_ms);
    progress.update(i + 1, detail);
  }
  progress.finish();
  system.finish();
  auto trajectory = system.trajectory();
  if (trajectory.empty()) fail(a.dataset, "tracking never initialised (too few keypoints with depth?)");
  write_tum_trajectory(a.output, trajectory, "depot-slam trajectory of " + a.dataset);
  if (!a.keyframes.empty()) write_tum_trajectory(a.keyframes, system.keyframe_trajectory(), "depot-slam keyframes");
  const auto ms = system.mapping_stats();
  std::printf(
      "tracked %zu frames (%d lost, %d relocalised): %zu keyframes, %zu map points; per frame median %.1f ms, p95 %.1f "
      "ms (extraction %.1f, tracking %.1f); local BA %.0f ms in total; wrote %s\n",
      n, lost, relocalized, system.n_keyframes(), system.n_map_points(), percentile(total, 0.5), percentile(total, 0.95),
      percentile(extract, 0.5), percentile(track, 0.5), ms.ba_ms, a.output.c_str());
}

}  // namespace

void register_slam_commands(CLI::App& app) {
  CLI::App* slam = app.add_subcommand("slam", "Run the RGB-D SLAM system");
  slam->require_subcommand(1);
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = slam->add_subcommand("run", "Track a TUM RGB-D folder and write the trajectory (TUM format)");
  run->add_option("dataset", args->dataset, "TUM RGB-D folder (associations.txt or rgb.txt + depth.txt)")->required();
  run->add_option("-o,--output", args->output, "Trajectory file (every frame, camera-to-world)")->required();
  run->add_option("--settings", args->settings, "Settings YAML (default: the dataset's calibration.yaml)");
  run->add_option("--keyframes", args->keyframes, "Also write the keyframe trajectory here");
  run->add_option("--frames", args->frames, "Only the first N frames")->check(CLI::Range(1, 10000000));
  run->add_flag("--sync", args->sync, "Run local mapping in the tracking thread (reproducible)");
  run->add_flag("-q,--quiet", args->quiet, "No progress line");
  run->callback([args, run] { run_slam(*args, *run); });
}

}  // namespace depot::cli
