#pragma once
// Running a system under test (system_spec.h) on one TUM RGB-D folder: its
// inputs written into the run's work folder, the program started in its own
// process group with its output in the run's log, stopped (the whole group)
// at its time limit or on Ctrl-C, and its trajectory read back and checked
// against the dataset's frames.
#include <atomic>
#include <string>
#include <vector>

#include "common/tum_io.h"
#include "slam/track/tracking_state.h"
#include "tools/system/system_spec.h"

namespace depot::system {

struct SystemRunRequest {
  std::string dataset;
  std::string work_dir;       // created; generated inputs, raw outputs, scratch
  std::string log_path;       // the system's stdout and stderr
  std::string depot_program;  // for {depot}; "" = this process's own program
  // Polled while the system runs; when it becomes true the system's process
  // group is stopped and run_system throws "interrupted". null = Ctrl-C's
  // flag (common/interrupt.h).
  const std::atomic<bool>* stop = nullptr;
};

struct SystemRunResult {
  std::vector<StampedPose> trajectory;   // camera-to-world, at frames' rgb timestamps
  size_t frames = 0;                     // frames the dataset gave
  std::vector<double> frame_timestamps;  // their rgb timestamps, in order
  double seconds = 0;                    // the system's wall time
  double frame_ms = 0;                   // per frame given (wall time / frames)
  std::string keypoints_path;            // the per-keypoint file it wrote ("" if none)
  std::string trajectory_path;           // its trajectory as it wrote it
};

// Throws depot::Error with one line naming the system and the reason when
// it cannot start, exits non-zero or by a signal, runs past its time limit,
// writes no trajectory (or no keypoint file it promised), or writes one
// that does not read (NaN, unsorted, not its format) or whose timestamps
// are no frames of the dataset (a KITTI file: not one pose per frame). The
// reason ends with the last line of its log when there is one.
SystemRunResult run_system(const SystemSpec& spec, const SystemRunRequest& request);

// The state of every frame given: the first pose NEW_MAP, later frames with
// a pose OK, frames before it NOT_INITIALIZED and frames after it without
// one LOST (an external system reports no more than its poses).
std::vector<slam::StampedFrameState> frame_states(const SystemRunResult& result);

// The last `lines` non-empty lines of a log file ("" when there is none).
std::string log_tail(const std::string& path, int lines);

}  // namespace depot::system
