// `depot slam run DATASET --system FILE -o traj.txt`: another SLAM system
// (a system file, tools/system/system_spec.h) run on a dataset through the
// same path a sweep takes, its trajectory written in TUM format with the
// states beside it, and its per-keypoint decisions (when it writes them)
// scored against a simulated dataset's labels as the built-in modes are.
#include <sys/ioctl.h>
#include <unistd.h>

#include <fmt/format.h>

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

// The system's progress on one line of stderr, as the built-in run's
// (common/progress.h): redrawn in place on a terminal, otherwise a line every
// 10 s and one when it ends (CI logs). Belongs to the thread running it.
class SystemProgressLine {
 public:
  explicit SystemProgressLine(std::string name)
      : name_(std::move(name)), tty_(isatty(STDERR_FILENO) != 0) {}

  void operator()(const system::SystemProgress& p) {
    const int decade = static_cast<int>(p.seconds / 10);
    if (!tty_ && !p.finished && decade == last_decade_) return;
    last_decade_ = decade;
    std::string line =
        fmt::format("system {}: {}{:.0f} s", name_, p.finished ? "ended after " : "", p.seconds);
    if (p.poses > 0)
      line += ", " + std::to_string(p.poses) + " of " + std::to_string(p.frames) +
              " frames in its trajectory";
    if (!p.log_line.empty()) line += ", log: " + printable(p.log_line);
    if (tty_) {
      // One terminal row, or the redraw would leave the rest behind.
      winsize size{};
      const size_t columns =
          ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 ? size.ws_col - 1 : 99;
      if (line.size() > columns) line.resize(columns);
      std::fprintf(stderr, "\r%s\033[K%s", line.c_str(), p.finished ? "\n" : "");
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
    std::fflush(stderr);
  }

 private:
  // The system's text without control characters (colours, '\r') that
  // would garble the line.
  static std::string printable(const std::string& text) {
    std::string out;
    for (char c : text) out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? ' ' : c;
    return out;
  }

  std::string name_;
  bool tty_;
  int last_decade_ = 0;
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
  system::SystemRunRequest request;
  request.dataset = a.dataset;
  request.log_path = log_path;
  if (!a.quiet) request.on_progress = SystemProgressLine(spec.name);
  const system::SystemRunResult r = system::run_system(spec, request);

  const std::vector<slam::StampedFrameState> states = system::frame_states(r);
  const slam::TrackedShare share = slam::tracked_share(states);
  eval::KeypointFileScore score;
  const bool scored = spec.writes_keypoints && eval::MotionTruth::available(a.dataset);
  if (scored) {
    try {
      score = eval::score_dataset_keypoints(a.dataset, r.keypoints_path, a.scale_factor);
    } catch (const Error& e) {
      // Its keypoint file is in the work folder, gone once depot exits.
      fail("system " + spec.name, system::name_work_paths(r, e.what()));
    }
  }
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
