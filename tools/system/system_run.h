#pragma once
// Running a system under test (system_spec.h) on one TUM RGB-D folder: its
// inputs written into the run's work folder, the program started as a
// process tree of its own (process_tree.h) with its output in the run's log,
// stopped (everything it started) at its time limit or on Ctrl-C, and its
// trajectory read back and checked against the dataset's frames. Nothing it
// started outlives the run.
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/tum_io.h"
#include "slam/track/tracking_state.h"
#include "tools/system/process_tree.h"
#include "tools/system/system_spec.h"

namespace depot::system {

// How a run is going, for a progress line.
struct SystemProgress {
  double seconds = 0;     // since the system started
  size_t frames = 0;      // frames the dataset gives
  size_t poses = 0;       // poses in its trajectory file so far (most write it at the end)
  std::string log_line;   // its log's last line ("" if none yet)
  bool finished = false;  // its processes have ended (any way); the last report
};

struct SystemRunRequest {
  std::string dataset;
  // Created; generated inputs, raw outputs, scratch. Removed with the
  // result (or when the run fails). "" = a scratch folder
  // "depot-system-<pid>-XXXXXX" in the temp directory, which the next run
  // removes if this process is killed.
  std::string work_dir;
  std::string log_path;  // the system's stdout and stderr
  // How errors name the log: where it will be once the run is over when
  // log_path is staged ("" = log_path).
  std::string log_name;
  std::string depot_program;  // for {depot}; "" = this process's own program
  // Polled while the system runs; when it becomes true everything it
  // started is stopped and run_system throws "interrupted". null = Ctrl-C's
  // flag (common/interrupt.h).
  const std::atomic<bool>* stop = nullptr;
  // Called about twice a second while the system runs, and once when it has
  // ended; on the caller's thread.
  std::function<void(const SystemProgress&)> on_progress;
  Tracking tracking = Tracking::kAuto;
};

// The work folder, removed when the last owner lets go of it.
class WorkFolder {
 public:
  explicit WorkFolder(std::string path) : path_(std::move(path)) {}
  ~WorkFolder();
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

struct SystemRunResult {
  std::vector<StampedPose> trajectory;   // camera-to-world, at frames' rgb timestamps
  size_t frames = 0;                     // frames the dataset gave
  std::vector<double> frame_timestamps;  // their rgb timestamps, in order
  double seconds = 0;                    // the system's wall time
  double frame_ms = 0;                   // per frame given (wall time / frames)
  std::string keypoints_path;            // the per-keypoint file it wrote ("" if none)
  std::string trajectory_path;           // its trajectory as it wrote it
  std::shared_ptr<WorkFolder> work;      // holds both files until the result goes
};

// Throws depot::Error with one line naming the system and the reason when
// it cannot start, exits non-zero or by a signal, runs past its time limit,
// writes no trajectory (or no keypoint file it promised), or writes one
// that does not read (NaN, unsorted, not its format) or whose timestamps
// are no frames of the dataset (a KITTI file: not one pose per frame). The
// reason ends with the last line of its log when there is one. Files in the
// work folder are named by their placeholders ("{trajectory}"), since the
// folder is gone once the run is over.
SystemRunResult run_system(const SystemSpec& spec, const SystemRunRequest& request);

// The state of every frame given: the first pose NEW_MAP, later frames with
// a pose OK, frames before it NOT_INITIALIZED and frames after it without
// one LOST (an external system reports no more than its poses).
std::vector<slam::StampedFrameState> frame_states(const SystemRunResult& result);

// The last `lines` non-empty lines of a log file ("" when there is none).
std::string log_tail(const std::string& path, int lines);

// `message` with the paths of the result's work folder and files replaced by
// their placeholders, e.g. for an error reading its keypoint file.
std::string name_work_paths(const SystemRunResult& result, const std::string& message);

}  // namespace depot::system
