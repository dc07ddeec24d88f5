#include "slam/io/settings.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/config_path.h"
#include "common/error.h"
#include "common/image_size.h"
#include "common/yaml_file.h"
#include "slam/camera/lens_distortion.h"

namespace depot::slam {
namespace {

// A bound as a user wrote it: 10000, 0.5 (not 10000.000000).
std::string shortest(double x) {
  std::ostringstream text;
  text << x;
  return text.str();
}

template <typename T>
T read(const YAML::Node& n, const char* key, T fallback, const std::string& path, double lo,
       double hi) {
  if (!n || !n[key]) return fallback;
  T v;
  try {
    v = n[key].as<T>();
  } catch (const YAML::Exception&) {
    fail(path + ":" + std::to_string(n[key].Mark().line + 1),
         std::string("bad value for '") + key + "'");
  }
  const double d = static_cast<double>(v);
  if (!std::isfinite(d) || d < lo || d > hi)
    fail(path + ":" + std::to_string(n[key].Mark().line + 1),
         std::string("'") + key + "' out of range [" + shortest(lo) + ", " + shortest(hi) + "]");
  return v;
}

}  // namespace

SlamSettings load_settings(const std::string& path, const SlamSettings& defaults) {
  YAML::Node root = load_yaml_file(path, "settings file");
  if (!root.IsMap()) fail(path, "settings must be a YAML map");
  SlamSettings s = defaults;
  const YAML::Node cam = root["camera"];
  s.camera.width = read<int>(cam, "width", s.camera.width, path, kMinImageSide, kMaxImageSide);
  s.camera.height = read<int>(cam, "height", s.camera.height, path, kMinImageSide, kMaxImageSide);
  s.camera.fx = read<double>(cam, "fx", s.camera.fx, path, 1, 1e5);
  s.camera.fy = read<double>(cam, "fy", s.camera.fy, path, 1, 1e5);
  s.camera.cx = read<double>(cam, "cx", s.camera.cx, path, 0, 8192);
  s.camera.cy = read<double>(cam, "cy", s.camera.cy, path, 0, 8192);
  // Lens distortion (OpenCV's k1 k2 p1 p2 k3); a file without them keeps
  // the defaults' (a later file describes the same camera).
  s.camera.lens.k1 = read<double>(cam, "k1", s.camera.lens.k1, path, -10, 10);
  s.camera.lens.k2 = read<double>(cam, "k2", s.camera.lens.k2, path, -10, 10);
  s.camera.lens.p1 = read<double>(cam, "p1", s.camera.lens.p1, path, -1, 1);
  s.camera.lens.p2 = read<double>(cam, "p2", s.camera.lens.p2, path, -1, 1);
  s.camera.lens.k3 = read<double>(cam, "k3", s.camera.lens.k3, path, -10, 10);
  set_undistorted_bounds(s.camera, path);
  // Virtual stereo baseline (ORB-SLAM2's Camera.bf); default 0.08 m x fx.
  const double baseline =
      read<double>(cam, "baseline", s.camera.bf / s.camera.fx, path, 0.001, 1.0);
  s.camera.bf = baseline * s.camera.fx;
  const YAML::Node depth = root["depth"];
  s.camera.depth_factor = read<double>(depth, "factor", s.camera.depth_factor, path, 1e-3, 1e6);
  // Close/far threshold in baselines (ORB-SLAM2's ThDepth, default 40).
  const double th_depth = read<double>(depth, "close_baselines", 40.0, path, 1, 1000);
  s.camera.close_depth = th_depth * baseline;
  const YAML::Node orb = root["orb"];
  s.orb.n_features = read<int>(orb, "features", s.orb.n_features, path, 50, 20000);
  s.orb.scale_factor = read<float>(orb, "scale_factor", s.orb.scale_factor, path, 1.01, 2.0);
  s.orb.n_levels = read<int>(orb, "levels", s.orb.n_levels, path, 1, 16);
  s.orb.ini_fast = read<int>(orb, "ini_fast", s.orb.ini_fast, path, 1, 255);
  s.orb.min_fast = read<int>(orb, "min_fast", s.orb.min_fast, path, 1, 255);
  const YAML::Node tr = root["tracking"];
  s.tracker.max_frames_between_kf =
      read<int>(tr, "max_frames_between_keyframes", s.tracker.max_frames_between_kf, path, 1, 1000);
  s.tracker.min_init_points =
      read<int>(tr, "min_init_points", s.tracker.min_init_points, path, 10, 10000);
  s.tracker.weak_inliers = read<int>(tr, "weak_inliers", s.tracker.weak_inliers, path, 0, 10000);
  if (tr && tr["atlas"]) {
    try {
      s.tracker.atlas = tr["atlas"].as<bool>();
    } catch (const YAML::Exception&) {
      fail(path + ":" + std::to_string(tr["atlas"].Mark().line + 1),
           "bad value for 'atlas' (true or false)");
    }
  }
  const YAML::Node places = root["place_recognition"];
  if (places && places["vocabulary"]) {
    try {
      s.vocabulary = resolve_config_path(places["vocabulary"].as<std::string>(),
                                         std::filesystem::path(path).parent_path().string());
    } catch (const YAML::Exception&) {
      fail(path + ":" + std::to_string(places["vocabulary"].Mark().line + 1),
           "bad value for 'vocabulary' (a file path)");
    }
  }
  s.tracker.relocalisation_candidates = read<int>(
      places, "relocalisation_candidates", s.tracker.relocalisation_candidates, path, 1, 1000);
  const YAML::Node loops = root["loop_closing"];
  if (loops && loops["enabled"]) {
    try {
      s.loop_closing = loops["enabled"].as<bool>();
    } catch (const YAML::Exception&) {
      fail(path + ":" + std::to_string(loops["enabled"].Mark().line + 1),
           "bad value for 'enabled' (true or false)");
    }
  }
  LoopCloserParams& lc = s.loop_closer;
  lc.consistency = read<int>(loops, "consistency", lc.consistency, path, 1, 100);
  lc.min_loop_matches = read<int>(loops, "min_loop_matches", lc.min_loop_matches, path, 10, 10000);
  lc.keyframes_between_loops =
      read<int>(loops, "keyframes_between_loops", lc.keyframes_between_loops, path, 1, 100000);
  lc.global_ba_iterations =
      read<int>(loops, "global_ba_iterations", lc.global_ba_iterations, path, 0, 1000);
  const YAML::Node mapping = root["mapping"];
  if (mapping && mapping["threaded"]) s.threaded_mapping = mapping["threaded"].as<bool>();
  return s;
}

}  // namespace depot::slam
