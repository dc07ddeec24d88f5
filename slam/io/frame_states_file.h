#pragma once
// The states file beside a trajectory: one line "timestamp STATE" for every
// frame given to the system, STATE as tracking_state.h names it (NEW_MAP,
// OK, RELOCALIZED, LOST, NOT_INITIALIZED, ABANDONED, OTHER_MAP), after '#' comment
// lines. The trajectory holds the tracked frames' poses only; this file says
// what became of the others, and gives the tracked share.
#include <string>
#include <vector>

#include "slam/track/tracking_state.h"

namespace depot::slam {

// Where the states of `trajectory_path` go: "run.txt" -> "run.states.txt"
// (any other name gets ".states.txt" appended).
std::string frame_states_path(const std::string& trajectory_path);

// The file's text: `header` as a comment (if any), a comment naming the
// columns and the tracked states, then one line per frame.
std::string format_frame_states(const std::vector<StampedFrameState>& states,
                                const std::string& header = "");

// Throws depot::Error("<path>:<line>: ...") for a line that is not
// "timestamp STATE", an unknown state or a timestamp that does not increase,
// and for a file without frames.
std::vector<StampedFrameState> read_frame_states(const std::string& path);

struct TrackedShare {
  size_t tracked = 0;  // frames with a pose (is_tracked)
  size_t frames = 0;   // frames given
  double share() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};
TrackedShare tracked_share(const std::vector<StampedFrameState>& states);

}  // namespace depot::slam
