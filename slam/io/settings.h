#pragma once
// SLAM settings: camera intrinsics, depth factor, ORB and tracking
// parameters, read from YAML. A dataset's calibration.yaml (written by the
// simulator) has the same `camera:` and `depth:` sections, so it can serve as
// settings directly.
#include <string>

#include "slam/camera/pinhole_camera.h"
#include "slam/feature/orb_extractor.h"
#include "slam/track/tracker.h"

namespace depot::slam {

struct SlamSettings {
  PinholeCamera camera;
  OrbParams orb;
  TrackerParams tracker;
  bool threaded_mapping = true;
};

// Reads `path`; keys not present keep their defaults. Every problem throws
// depot::Error "<path>: <what>".
SlamSettings load_settings(const std::string& path, const SlamSettings& defaults = {});

}  // namespace depot::slam
