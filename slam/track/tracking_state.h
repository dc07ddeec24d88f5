#pragma once

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

}  // namespace depot::slam
