#include "tools/system/system_run.h"

#include <stdlib.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include "common/child_process.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/stale_partials.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"

namespace fs = std::filesystem;

namespace depot::system {
namespace {

// Within this of a frame's rgb timestamp, a pose is that frame's.
constexpr double kTimestampTolerance = 1e-3;

std::string format_double(double v) {
  return fmt::format("{:.9g}", v);
}

// ORB-SLAM2's RGB-D settings file (Examples/RGB-D/TUM1.yaml's keys) for
// systems built on it.
std::string orbslam_settings(const slam::SlamSettings& s, double fps) {
  const slam::PinholeCamera& c = s.camera;
  std::string y = "%YAML:1.0\n# Written by depot for a system under test (ORB-SLAM2 RGB-D keys).\n";
  auto line = [&](const std::string& key, const std::string& value) {
    y += key + ": " + value + "\n";
  };
  line("Camera.fx", format_double(c.fx));
  line("Camera.fy", format_double(c.fy));
  line("Camera.cx", format_double(c.cx));
  line("Camera.cy", format_double(c.cy));
  line("Camera.k1", format_double(c.lens.k1));
  line("Camera.k2", format_double(c.lens.k2));
  line("Camera.p1", format_double(c.lens.p1));
  line("Camera.p2", format_double(c.lens.p2));
  line("Camera.k3", format_double(c.lens.k3));
  line("Camera.width", std::to_string(c.width));
  line("Camera.height", std::to_string(c.height));
  line("Camera.fps", format_double(fps));
  line("Camera.bf", format_double(c.bf));
  line("Camera.RGB", "1");
  line("ThDepth", format_double(c.close_depth * c.fx / c.bf));
  line("DepthMapFactor", format_double(c.depth_factor));
  line("ORBextractor.nFeatures", std::to_string(s.orb.n_features));
  line("ORBextractor.scaleFactor", format_double(s.orb.scale_factor));
  line("ORBextractor.nLevels", std::to_string(s.orb.n_levels));
  line("ORBextractor.iniThFAST", std::to_string(s.orb.ini_fast));
  line("ORBextractor.minThFAST", std::to_string(s.orb.min_fast));
  line("Viewer.KeyFrameSize", "0.05");
  line("Viewer.KeyFrameLineWidth", "1");
  line("Viewer.GraphLineWidth", "0.9");
  line("Viewer.PointSize", "2");
  line("Viewer.CameraSize", "0.08");
  line("Viewer.CameraLineWidth", "3");
  line("Viewer.ViewpointX", "0");
  line("Viewer.ViewpointY", "-0.7");
  line("Viewer.ViewpointZ", "-1.8");
  line("Viewer.ViewpointF", "500");
  return y;
}

std::string with_log(const std::string& reason, const std::string& log_path,
                     const std::string& log_name) {
  const std::string last = log_tail(log_path, 1);
  return last.empty() ? reason + " (log " + log_name + " is empty)"
                      : reason + " (log " + log_name + " ends: " + last + ")";
}

// Lines as a log shows them: a progress line redrawn with '\r' is what it
// ended as; blank lines are left out.
void add_log_lines(std::istream& in, int keep, std::deque<std::string>& tail) {
  std::string line;
  while (std::getline(in, line)) {
    const size_t cr = line.find_last_of('\r', line.size() >= 2 ? line.size() - 2 : 0);
    if (cr != std::string::npos && cr + 1 < line.size()) line = line.substr(cr + 1);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    tail.push_back(line);
    if (static_cast<int>(tail.size()) > keep) tail.pop_front();
  }
}

// The log's last line, from its last few kilobytes only (it is read twice
// a second while the system runs, and a log may grow large).
std::string last_log_line(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - 4096));
  std::deque<std::string> tail;
  add_log_lines(in, 1, tail);
  return tail.empty() ? "" : tail.back();
}

// Poses in a trajectory file being written: its data lines.
size_t count_poses(const std::string& path) {
  std::ifstream in(path);
  size_t n = 0;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && line.find_first_not_of(" \t\r") != std::string::npos)
      ++n;
  return n;
}

// Paths in the work folder by their placeholders: the folder is gone when a
// user reads the message.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string name_paths(std::string message, const std::map<std::string, std::string>& values) {
  for (const char* key :
       {"trajectory", "keypoints", "timestamps", "intrinsics", "orbslam_settings"}) {
    auto it = values.find(key);
    if (it != values.end())
      message = replace_all(message, it->second, std::string("{") + key + "}");
  }
  auto work = values.find("work");
  return work == values.end() ? message : replace_all(message, work->second, "{work}");
}

// A scratch folder of this run in the temp directory, named with this
// process's id so that the next run removes it if this one is killed.
std::string make_scratch_folder() {
  const fs::path temp = fs::temp_directory_path();
  remove_stale_scratch(temp.string(), "depot-system-");
  std::string pattern = (temp / ("depot-system-" + std::to_string(getpid()) + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data()))
    fail(pattern, std::string("cannot create a scratch folder: ") + std::strerror(errno));
  return pattern;
}

// The system's trajectory, in the dataset's frames' timestamps. A KITTI
// file's poses take the timestamps file the system wrote ({timestamps}), or
// else are one per frame in order.
std::vector<StampedPose> read_system_trajectory(const SystemSpec& spec, const std::string& path,
                                                const std::string& timestamps_path,
                                                const std::vector<double>& frame_times) {
  std::vector<StampedPose> out;
  if (spec.trajectory_format == TrajectoryFormat::kKitti) {
    const std::vector<Pose> poses = read_kitti_poses(path);
    std::vector<double> times = frame_times;
    if (spec.writes_timestamps) {
      if (!fs::is_regular_file(timestamps_path))
        fail(timestamps_path, "no timestamps file written for the KITTI trajectory");
      times = read_timestamps(timestamps_path);
      for (size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]))
          fail(timestamps_path, "timestamps must increase (line " + std::to_string(i + 1) + ")");
    }
    if (poses.size() != times.size())
      fail(path,
           std::to_string(poses.size()) + " KITTI poses for " + std::to_string(times.size()) +
               (spec.writes_timestamps ? " timestamps in " + timestamps_path
                                       : " frames (one pose per frame without {timestamps})"));
    for (size_t i = 0; i < poses.size(); ++i) out.push_back({times[i], poses[i]});
    if (!spec.writes_timestamps) return out;
  } else {
    out = spec.trajectory_format == TrajectoryFormat::kEuroc ? read_euroc_trajectory(path)
                                                             : read_tum_trajectory(path);
  }
  std::vector<double> sorted = frame_times;
  std::sort(sorted.begin(), sorted.end());
  for (StampedPose& p : out) {
    auto it = std::lower_bound(sorted.begin(), sorted.end(), p.timestamp);
    double nearest = INFINITY;
    if (it != sorted.end()) nearest = *it;
    if (it != sorted.begin() && std::abs(*(it - 1) - p.timestamp) < std::abs(nearest - p.timestamp))
      nearest = *(it - 1);
    if (!(std::abs(nearest - p.timestamp) <= kTimestampTolerance))
      fail(path, fmt::format("timestamp {:.6f} is no frame of the dataset (nearest {:.6f}; "
                             "allowed {:.0f} ms)",
                             p.timestamp, nearest, 1000 * kTimestampTolerance));
    p.timestamp = nearest;  // the frame's own timestamp, for exact matching
  }
  return out;
}

}  // namespace

std::vector<slam::StampedFrameState> frame_states(const SystemRunResult& result) {
  std::vector<slam::StampedFrameState> states;
  size_t next = 0;  // the next pose (poses carry frames' own timestamps, in order)
  bool started = false;
  for (double t : result.frame_timestamps) {
    slam::FrameState state = started ? slam::FrameState::kLost : slam::FrameState::kNotInitialized;
    if (next < result.trajectory.size() && result.trajectory[next].timestamp == t) {
      state = started ? slam::FrameState::kOk : slam::FrameState::kNewMap;
      started = true;
      ++next;
    }
    states.push_back({t, state});
  }
  return states;
}

std::string log_tail(const std::string& path, int lines) {
  std::ifstream in(path);
  if (!in) return "";
  std::deque<std::string> tail;
  add_log_lines(in, lines, tail);
  std::string out;
  for (const auto& l : tail) out += (out.empty() ? "" : "\n") + l;
  return out;
}

WorkFolder::~WorkFolder() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string name_work_paths(const SystemRunResult& result, const std::string& message) {
  std::map<std::string, std::string> values;
  if (!result.trajectory_path.empty()) values["trajectory"] = result.trajectory_path;
  if (!result.keypoints_path.empty()) values["keypoints"] = result.keypoints_path;
  if (result.work) values["work"] = result.work->path();
  return name_paths(message, values);
}

SystemRunResult run_system(const SystemSpec& spec, const SystemRunRequest& request) {
  const std::string who = "system " + spec.name;
  // What systems of killed depot processes left running goes first.
  remove_stale_process_trees();
  const slam::TumSequence sequence(request.dataset);
  auto work_folder = std::make_shared<WorkFolder>(request.work_dir.empty() ? make_scratch_folder()
                                                                           : request.work_dir);
  fs::create_directories(work_folder->path());
  const fs::path work = fs::absolute(work_folder->path());
  const std::string log_name = request.log_name.empty() ? request.log_path : request.log_name;

  std::map<std::string, std::string> values;
  values["dataset"] = fs::absolute(request.dataset).string();
  values["work"] = work.string();
  values["system_dir"] = fs::absolute(spec.path).parent_path().string();
  values["depot"] = request.depot_program.empty() ? own_program_path() : request.depot_program;
  const std::string extension =
      spec.trajectory_format == TrajectoryFormat::kEuroc ? ".csv" : ".txt";
  values["trajectory"] = (work / ("trajectory" + extension)).string();
  values["keypoints"] = (work / "keypoints.csv").string();
  values["timestamps"] = (work / "timestamps.txt").string();
  // The calibration and what is derived from it, when the dataset has one.
  const std::string calibration = sequence.calibration_path();
  if (!calibration.empty()) {
    const slam::SlamSettings settings = slam::load_settings(calibration);
    const slam::PinholeCamera& c = settings.camera;
    double fps = 30;
    if (sequence.size() > 1)
      fps = (sequence.size() - 1) /
            (sequence.entry(sequence.size() - 1).rgb_timestamp - sequence.entry(0).rgb_timestamp);
    values["calibration"] = fs::absolute(calibration).string();
    values["intrinsics"] = (work / "intrinsics.txt").string();
    values["orbslam_settings"] = (work / "orbslam_settings.yaml").string();
    values["depth_factor"] = format_double(c.depth_factor);
    write_text_file_atomic(values["intrinsics"], format_double(c.fx) + " " + format_double(c.fy) +
                                                     " " + format_double(c.cx) + " " +
                                                     format_double(c.cy) + "\n");
    write_text_file_atomic(values["orbslam_settings"], orbslam_settings(settings, fps));
  }
  for (const std::string& arg : spec.command)
    for (const char* needs :
         {"{calibration}", "{intrinsics}", "{orbslam_settings}", "{depth_factor}"})
      if (calibration.empty() && arg.find(needs) != std::string::npos)
        fail(request.dataset,
             std::string("has no calibration.yaml, which ") + needs + " needs (" + who + ")");
  // A stale output from an earlier run must not pass for this one's.
  fs::remove(values["trajectory"]);
  fs::remove(values["keypoints"]);
  fs::remove(values["timestamps"]);

  ChildSpec child;
  child.argv = expand_command(spec, values);
  child.log_path = request.log_path;
  child.working_dir = work.string();
  child.env = spec.env;
  const auto start = std::chrono::steady_clock::now();
  auto seconds_since_start = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::unique_ptr<ProcessTree> tree;
  try {
    tree = std::make_unique<ProcessTree>(child, request.tracking);
  } catch (const Error& e) {
    fail(who, std::string("command not started: ") + e.what());
  }
  auto report = [&](bool finished) {
    if (!request.on_progress) return;
    SystemProgress p;
    p.seconds = seconds_since_start();
    p.frames = sequence.size();
    p.poses = count_poses(values["trajectory"]);
    p.log_line = last_log_line(request.log_path);
    p.finished = finished;
    request.on_progress(p);
  };
  const std::atomic<bool>& stop = request.stop ? *request.stop : interrupt_flag();
  constexpr auto kGrace = std::chrono::seconds(5);
  int status = 0;
  bool interrupted = false, timed_out = false;
  double last_report = 0;
  while (true) {
    std::optional<int> done;
    try {
      done = tree->poll();
    } catch (const Error& e) {
      fail(who, std::string("lost its process: ") + e.what());
    }
    if (done) {
      status = *done;
      break;
    }
    const double seconds = seconds_since_start();
    if (stop.load()) {
      tree->stop(kGrace);
      interrupted = true;
      break;
    }
    if (seconds > spec.time_limit_s) {
      tree->stop(kGrace);
      timed_out = true;
      break;
    }
    if (seconds - last_report >= 0.5) {
      last_report = seconds;
      report(false);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  tree->kill_all();  // nothing the system started outlives it
  tree.reset();
  report(true);
  if (interrupted) fail(who, "interrupted");
  if (timed_out)
    fail(who, with_log("stopped at its time limit of " + format_double(spec.time_limit_s) + " s",
                       request.log_path, log_name));
  SystemRunResult result;
  result.work = work_folder;
  result.seconds = seconds_since_start();
  result.frames = sequence.size();
  for (size_t i = 0; i < sequence.size(); ++i)
    result.frame_timestamps.push_back(sequence.entry(i).rgb_timestamp);
  result.frame_ms = result.frames ? 1000.0 * result.seconds / result.frames : 0.0;
  const int code = exit_code_of(status);
  if (code != 0)
    fail(who, with_log(code > 128 ? "killed by signal " + std::to_string(code - 128)
                                  : "exited with code " + std::to_string(code),
                       request.log_path, log_name));
  result.trajectory_path = values["trajectory"];
  if (!fs::is_regular_file(result.trajectory_path))
    fail(who, with_log("wrote no trajectory to {trajectory}", request.log_path, log_name));
  try {
    result.trajectory = read_system_trajectory(spec, result.trajectory_path, values["timestamps"],
                                               result.frame_timestamps);
  } catch (const Error& e) {
    fail(who, "its trajectory: " + name_paths(e.what(), values));
  }
  if (spec.writes_keypoints) {
    result.keypoints_path = values["keypoints"];
    if (!fs::is_regular_file(result.keypoints_path))
      fail(who, with_log("wrote no keypoint file to {keypoints}", request.log_path, log_name));
  }
  return result;
}

}  // namespace depot::system
