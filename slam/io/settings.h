#pragma once
// SLAM settings: camera intrinsics, depth factor, ORB and tracking
// parameters, read from YAML. A dataset's calibration.yaml (written by the
// simulator) has the same `camera:` and `depth:` sections, so it can serve as
// settings directly.
#include <string>

#include "dataset/calibration.h"
#include "slam/camera/pinhole_camera.h"
#include "slam/feature/orb_extractor.h"
#include "slam/loop/loop_closer.h"
#include "slam/track/tracker.h"

namespace depot::slam {

struct SlamSettings {
  PinholeCamera camera;
  OrbParams orb;
  TrackerParams tracker;
  bool threaded_mapping = true;
  // The place-recognition vocabulary (slam/place/vocabulary_file.h); empty:
  // default_vocabulary_path(). YAML: place_recognition: {vocabulary: FILE,
  // relocalisation_candidates: N}.
  std::string vocabulary;
  // Loop closing (YAML loop_closing: {enabled, min_loop_matches, ...}).
  bool loop_closing = true;
  LoopCloserParams loop_closer;
};

// The settings' camera as calibration.yaml's sections describe one (the
// defaults a calibration is read over).
dataset::CameraCalibration camera_calibration_of(const SlamSettings& s);
// Sets the settings' camera from a calibration (`source` names it in
// errors): intrinsics, lens, bf, depth factor, ThDepth.
void set_camera(SlamSettings& s, const dataset::CameraCalibration& c, const std::string& source);

// Reads `path`; keys not present keep their defaults. Every problem throws
// depot::Error "<path>: <what>".
SlamSettings load_settings(const std::string& path, const SlamSettings& defaults = {});

}  // namespace depot::slam
