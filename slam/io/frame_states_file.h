#pragma once
// The states file beside a trajectory: one line "timestamp STATE [MAP]" for
// every frame given to the system, STATE as tracking_state.h names it
// (NEW_MAP, OK, RELOCALIZED, LOST, NOT_INITIALIZED, ABANDONED, OTHER_MAP),
// after '#' comment lines; MAP, on the lines of frames with a pose, numbers
// the atlas map the frame was tracked in (0 = the trajectory's). The
// trajectory holds the tracked frames' poses only; this file says what
// became of the others, and gives the tracked share. The atlas trajectory
// beside both (run.txt -> run.atlas.txt) holds every frame with a pose, each
// in its own map's coordinate frame, in the order of this file's lines.
#include <string>
#include <vector>

#include "slam/track/tracking_state.h"

namespace depot::slam {

// Where the states of `trajectory_path` go: "run.txt" -> "run.states.txt"
// (any other name gets ".states.txt" appended).
std::string frame_states_path(const std::string& trajectory_path);

// Where the atlas trajectory of `trajectory_path` goes: "run.txt" ->
// "run.atlas.txt" (any other name gets ".atlas.txt" appended).
std::string atlas_trajectory_path(const std::string& trajectory_path);

// The file's text: `header` as a comment (if any), a comment naming the
// columns and the tracked states, then one line per frame.
std::string format_frame_states(const std::vector<StampedFrameState>& states,
                                const std::string& header = "");

// Throws depot::Error("<path>:<line>: ...") for a line that is not
// "timestamp STATE [MAP]", an unknown state, a timestamp that does not
// increase, a MAP on a frame without a pose or a tracked frame's MAP other
// than 0 (an OTHER_MAP frame's other than 1..), and for a file without frames.
std::vector<StampedFrameState> read_frame_states(const std::string& path);

struct TrackedShare {
  size_t tracked = 0;  // frames with a pose (is_tracked)
  size_t frames = 0;   // frames given
  double share() const { return frames ? static_cast<double>(tracked) / frames : 0.0; }
};
TrackedShare tracked_share(const std::vector<StampedFrameState>& states);

// The map of each frame with a pose, in order (the atlas trajectory's lines);
// empty when the states name no maps.
std::vector<int> maps_of_posed_frames(const std::vector<StampedFrameState>& states);

}  // namespace depot::slam
