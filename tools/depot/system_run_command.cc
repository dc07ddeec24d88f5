// `depot slam run DATASET --system FILE -o traj.txt`: another SLAM system
// (a system file, tools/system/system_spec.h) run on a dataset through the
// same path a sweep takes, its trajectory written in TUM format with the
// states beside it, and its per-keypoint decisions (when it writes them)
// scored against a simulated dataset's labels as the built-in modes are.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "common/error.h"
#include "common/staged_file.h"
#include "eval/keypoint_score.h"
#include "eval/motion_truth.h"
#include "slam/io/frame_states_file.h"
#include "tools/depot/commands.h"
#include "tools/depot/system_run_command.h"
#include "tools/system/system_run.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

// A scratch folder of our own, removed when the run ends either way.
struct ScratchFolder {
  std::string path;
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "depot-system-XXXXXX").string();
    if (!mkdtemp(pattern.data())) fail(pattern, "cannot create a scratch folder");
    path = pattern;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

std::string system_log_path(const std::string& trajectory_path) {
  const fs::path p(trajectory_path);
  return p.extension() == ".txt" ? (p.parent_path() / (p.stem().string() + ".system.log")).string()
                                 : trajectory_path + ".system.log";
}

void print_rejection_vs_truth(const eval::RejectionScore& s) {
  std::printf(
      "rejection vs ground truth: precision %.3f recall %.3f with boundary points left out; "
      "precision %.3f with them counted as static (%ld of %ld static points thrown away, %ld of "
      "them boundary points)\n",
      s.precision_without_boundary(), s.recall(), s.precision(), s.false_positive,
      s.static_points(), s.boundary_false_positive);
}

void run_external_system(const SystemRunArgs& a) {
  const system::SystemSpec spec = system::load_system_spec(system::find_system_file(a.system));
  const std::string states_path = slam::frame_states_path(a.output);
  const std::string log_path = system_log_path(a.output);
  for (const std::string* path : {&a.output, &states_path, &log_path, &a.keypoints})
    if (!path->empty()) check_output_file(*path);
  if (!a.keypoints.empty() && !spec.writes_keypoints)
    fail("--keypoints", "system " + spec.name +
                            " writes no keypoint file (its command never "
                            "names {keypoints})");
  if (!a.quiet)
    std::fprintf(stderr, "depot slam run: %s, system %s (%s); its output goes to %s\n",
                 a.dataset.c_str(), spec.name.c_str(), spec.path.c_str(), log_path.c_str());
  ScratchFolder scratch;
  system::SystemRunRequest request;
  request.dataset = a.dataset;
  request.work_dir = scratch.path;
  request.log_path = log_path;
  const system::SystemRunResult r = system::run_system(spec, request);

  const std::vector<slam::StampedFrameState> states = system::frame_states(r);
  const slam::TrackedShare share = slam::tracked_share(states);
  eval::KeypointFileScore score;
  const bool scored = spec.writes_keypoints && eval::MotionTruth::available(a.dataset);
  if (scored) score = eval::score_dataset_keypoints(a.dataset, r.keypoints_path, a.scale_factor);
  // Everything read and checked: the outputs appear together.
  const std::string header = "system " + spec.name + " on " + a.dataset;
  StagedFile trajectory(a.output), states_file(states_path);
  trajectory.stream() << format_tum_trajectory(r.trajectory, header + ": tracked frames only");
  states_file.stream() << slam::format_frame_states(states, header + ": the state of every frame");
  std::unique_ptr<StagedFile> keypoints;
  if (!a.keypoints.empty()) {
    keypoints = std::make_unique<StagedFile>(a.keypoints);
    std::ifstream in(r.keypoints_path, std::ios::binary);
    keypoints->stream() << in.rdbuf();
  }
  trajectory.commit();
  states_file.commit();
  if (keypoints) keypoints->commit();
  std::printf(
      "tracked %zu of %zu frames (%.1f %%) with system %s: %.1f s wall time, %.1f ms per frame; "
      "wrote %s and %s (its output: %s)\n",
      share.tracked, share.frames, 100.0 * share.share(), spec.name.c_str(), r.seconds, r.frame_ms,
      a.output.c_str(), states_path.c_str(), log_path.c_str());
  if (scored) print_rejection_vs_truth(score.score);
}

}  // namespace depot::cli
