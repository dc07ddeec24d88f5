#include "slam/io/settings.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"
#include "dataset/calibration.h"
#include "slam/camera/lens_distortion.h"

namespace depot::slam {

dataset::CameraCalibration camera_calibration_of(const SlamSettings& s) {
  dataset::CameraCalibration c;
  c.width = s.camera.width;
  c.height = s.camera.height;
  c.fx = s.camera.fx;
  c.fy = s.camera.fy;
  c.cx = s.camera.cx;
  c.cy = s.camera.cy;
  c.lens = s.camera.lens;
  c.bf = s.camera.bf;
  c.depth_factor = s.camera.depth_factor;
  return c;
}

void set_camera(SlamSettings& s, const dataset::CameraCalibration& c, const std::string& source) {
  s.camera.width = c.width;
  s.camera.height = c.height;
  s.camera.fx = c.fx;
  s.camera.fy = c.fy;
  s.camera.cx = c.cx;
  s.camera.cy = c.cy;
  // Lens distortion; a file without it keeps the defaults' (a later file
  // describes the same camera).
  s.camera.lens = c.lens;
  set_undistorted_bounds(s.camera, source);
  s.camera.bf = c.bf;
  s.camera.depth_factor = c.depth_factor;
  s.camera.close_depth = c.close_baselines * c.baseline;
}

SlamSettings load_settings(const std::string& path, const SlamSettings& defaults) {
  YAML::Node root = load_yaml_file(path, "settings file");
  if (!root.IsMap()) fail(path, "settings must be a YAML map");
  SlamSettings s = defaults;
  // The camera and depth sections are calibration.yaml's (dataset/calibration.h).
  set_camera(s, dataset::read_camera_sections(root, path, camera_calibration_of(s)), path);
  const YamlFields orb(root["orb"], path, "orb");
  s.orb.n_features = orb.number<int>("features", s.orb.n_features, 50, 20000);
  s.orb.scale_factor = orb.number<float>("scale_factor", s.orb.scale_factor, 1.01, 2.0);
  s.orb.n_levels = orb.number<int>("levels", s.orb.n_levels, 1, 16);
  s.orb.ini_fast = orb.number<int>("ini_fast", s.orb.ini_fast, 1, 255);
  s.orb.min_fast = orb.number<int>("min_fast", s.orb.min_fast, 1, 255);
  const YamlFields tr(root["tracking"], path, "tracking");
  s.tracker.max_frames_between_kf =
      tr.number<int>("max_frames_between_keyframes", s.tracker.max_frames_between_kf, 1, 1000);
  s.tracker.min_init_points =
      tr.number<int>("min_init_points", s.tracker.min_init_points, 10, 10000);
  s.tracker.weak_inliers = tr.number<int>("weak_inliers", s.tracker.weak_inliers, 0, 10000);
  s.tracker.atlas = tr.flag("atlas", s.tracker.atlas);
  s.tracker.reset_keyframes = tr.number<int>("reset_keyframes", s.tracker.reset_keyframes, 0, 1000);
  const YamlFields places(root["place_recognition"], path, "place_recognition");
  if (places.has("vocabulary")) {
    s.vocabulary = resolve_config_path(places.str("vocabulary"),
                                       std::filesystem::path(path).parent_path().string());
  }
  s.tracker.relocalisation_candidates =
      places.number<int>("relocalisation_candidates", s.tracker.relocalisation_candidates, 1, 1000);
  const YamlFields loops(root["loop_closing"], path, "loop_closing");
  s.loop_closing = loops.flag("enabled", s.loop_closing);
  LoopCloserParams& lc = s.loop_closer;
  lc.consistency = loops.number<int>("consistency", lc.consistency, 1, 100);
  lc.min_loop_matches = loops.number<int>("min_loop_matches", lc.min_loop_matches, 10, 10000);
  lc.keyframes_between_loops =
      loops.number<int>("keyframes_between_loops", lc.keyframes_between_loops, 1, 100000);
  lc.global_ba_iterations =
      loops.number<int>("global_ba_iterations", lc.global_ba_iterations, 0, 1000);
  const YamlFields mapping(root["mapping"], path, "mapping");
  s.threaded_mapping = mapping.flag("threaded", s.threaded_mapping);
  return s;
}

}  // namespace depot::slam
