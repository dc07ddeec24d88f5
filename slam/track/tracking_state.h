#pragma once
// Two kinds of state, kept apart on purpose:
//
// TrackingState is the tracker's state machine (what track() returns): not
// initialised yet, tracking, lost, or relocalised on this frame.
//
// FrameState is the final record of one frame given to the system, what the
// states file beside a trajectory holds (`<trajectory>.states.txt`, one
// "timestamp STATE [MAP]" line per frame). A frame is *tracked* (has a pose in the
// trajectory) when its state is NEW_MAP, OK or RELOCALIZED; every other frame
// has no pose and is left out of the trajectory (ORB-SLAM2 does the same):
//   NOT_INITIALIZED  no map yet: too few keypoints with depth to start one
//   NEW_MAP          a map was (re)initialised on this frame (its first keyframe)
//   OK               tracked in the current map
//   RELOCALIZED      tracking was lost and recovered on this frame
//   LOST             tracking failed on this frame: no pose
//   ABANDONED        was tracked (NEW_MAP, OK or RELOCALIZED), but in a map that
//                    a later reset threw away (lost within the first keyframes):
//                    its pose belongs to a discarded coordinate frame, so it
//                    left the trajectory
//   OTHER_MAP        was tracked, in a map of the atlas (slam/data/map.h) that
//                    was never merged into the main one (the map holding most
//                    tracked frames): its pose is in another coordinate frame,
//                    so it is not in the trajectory either
// The tracked share of a run is tracked frames / frames given.
#include <optional>
#include <string>

namespace depot::slam {

enum class TrackingState { kNotInitialized, kOk, kLost, kRelocalized };

inline const char* tracking_state_name(TrackingState s) {
  switch (s) {
    case TrackingState::kNotInitialized:
      return "NOT_INITIALIZED";
    case TrackingState::kOk:
      return "OK";
    case TrackingState::kLost:
      return "LOST";
    case TrackingState::kRelocalized:
      return "RELOCALIZED";
  }
  return "?";
}

enum class FrameState { kNotInitialized, kNewMap, kOk, kRelocalized, kLost, kAbandoned, kOtherMap };

inline const char* frame_state_name(FrameState s) {
  switch (s) {
    case FrameState::kNotInitialized:
      return "NOT_INITIALIZED";
    case FrameState::kNewMap:
      return "NEW_MAP";
    case FrameState::kOk:
      return "OK";
    case FrameState::kRelocalized:
      return "RELOCALIZED";
    case FrameState::kLost:
      return "LOST";
    case FrameState::kAbandoned:
      return "ABANDONED";
    case FrameState::kOtherMap:
      return "OTHER_MAP";
  }
  return "?";
}

// The state named as frame_state_name() writes it; nothing for another word.
inline std::optional<FrameState> parse_frame_state(const std::string& name) {
  for (FrameState s :
       {FrameState::kNotInitialized, FrameState::kNewMap, FrameState::kOk, FrameState::kRelocalized,
        FrameState::kLost, FrameState::kAbandoned, FrameState::kOtherMap})
    if (name == frame_state_name(s)) return s;
  return std::nullopt;
}

// True for the states whose frames have a pose in the trajectory.
inline bool is_tracked(FrameState s) {
  return s == FrameState::kNewMap || s == FrameState::kOk || s == FrameState::kRelocalized;
}

// True for the states whose frames have a pose in some map of the atlas.
inline bool has_pose(FrameState s) {
  return is_tracked(s) || s == FrameState::kOtherMap;
}

struct StampedFrameState {
  double timestamp = 0;
  FrameState state = FrameState::kNotInitialized;
  // For a frame with a pose (has_pose): its map, numbered by the frames it
  // holds: 0 is the main map (the trajectory's), 1.. the others. -1 for a
  // frame without a pose, or when not known (a states file of two columns).
  int map = -1;
};

}  // namespace depot::slam
