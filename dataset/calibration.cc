#include "dataset/calibration.h"

#include <iomanip>
#include <sstream>
#include <utility>

#include "common/error.h"
#include "common/image_size.h"
#include "common/number_text.h"
#include "common/yaml_fields.h"
#include "common/yaml_file.h"

namespace depot::dataset {

namespace {

// The camera keys' accepted ranges, for calibration.yaml and for a camera
// stated by its intrinsics alike.
struct Range {
  const char* key;
  double lo, hi;
};
constexpr Range kFx{"fx", 1, 1e5}, kFy{"fy", 1, 1e5}, kCx{"cx", 0, 8192}, kCy{"cy", 0, 8192};
constexpr Range kK1{"k1", -10, 10}, kK2{"k2", -10, 10}, kP1{"p1", -1, 1}, kP2{"p2", -1, 1},
    kK3{"k3", -10, 10};

}  // namespace

CameraCalibration read_camera_sections(const YAML::Node& root, const std::string& path,
                                       const CameraCalibration& defaults) {
  CameraCalibration c = defaults;
  const YamlFields cam(root["camera"], path, "camera");
  c.width = cam.number<int>("width", c.width, kMinImageSide, kMaxImageSide);
  c.height = cam.number<int>("height", c.height, kMinImageSide, kMaxImageSide);
  const auto number = [&cam](const Range& r, double fallback) {
    return cam.number(r.key, fallback, r.lo, r.hi);
  };
  c.fx = number(kFx, c.fx);
  c.fy = number(kFy, c.fy);
  c.cx = number(kCx, c.cx);
  c.cy = number(kCy, c.cy);
  c.lens.k1 = number(kK1, c.lens.k1);
  c.lens.k2 = number(kK2, c.lens.k2);
  c.lens.p1 = number(kP1, c.lens.p1);
  c.lens.p2 = number(kP2, c.lens.p2);
  c.lens.k3 = number(kK3, c.lens.k3);
  // Absent, the baseline keeps the defaults' bf under the new fx.
  c.baseline = cam.number("baseline", defaults.bf / c.fx, 0.001, 1.0);
  c.bf = c.baseline * c.fx;
  const YamlFields depth(root["depth"], path, "depth");
  c.depth_factor = depth.number("factor", c.depth_factor, 1e-3, 1e6);
  c.close_baselines = depth.number("close_baselines", c.close_baselines, 1, 1000);
  return c;
}

CameraCalibration calibration_of_intrinsics(const CameraCalibration& defaults, int width,
                                            int height, double fx, double fy, double cx, double cy,
                                            const LensCoefficients& lens,
                                            const std::string& where) {
  const auto check = [&where](const Range& r, double v) {
    if (!(v >= r.lo && v <= r.hi))
      fail(where, std::string(r.key) + " " + shortest_number(v) + " is outside [" +
                      shortest_number(r.lo) + ", " + shortest_number(r.hi) + "]");
  };
  check({"width", kMinImageSide, kMaxImageSide}, width);
  check({"height", kMinImageSide, kMaxImageSide}, height);
  const std::pair<Range, double> values[] = {{kFx, fx},      {kFy, fy},      {kCx, cx},
                                             {kCy, cy},      {kK1, lens.k1}, {kK2, lens.k2},
                                             {kP1, lens.p1}, {kP2, lens.p2}, {kK3, lens.k3}};
  for (const auto& [range, value] : values) check(range, value);
  CameraCalibration c = defaults;
  c.width = width;
  c.height = height;
  c.fx = fx;
  c.fy = fy;
  c.cx = cx;
  c.cy = cy;
  c.lens = lens;
  // As read_camera_sections keeps an absent baseline.
  c.baseline = defaults.bf / c.fx;
  c.bf = c.baseline * c.fx;
  return c;
}

CameraCalibration read_calibration(const std::string& path) {
  const YAML::Node root = load_yaml_file(path, "file (the dataset's camera calibration)");
  if (!root.IsMap() || !root["camera"] || !root["camera"].IsMap() || !root["camera"]["width"] ||
      !root["camera"]["height"])
    fail(path, "no camera: width/height");
  return read_camera_sections(root, path);
}

std::string calibration_text(const CameraCalibration& c) {
  std::ostringstream text;
  const auto fixed = [&text](int digits, double v) -> std::ostringstream& {
    text << std::fixed << std::setprecision(digits) << v;
    return text;
  };
  const auto general = [&text](double v) -> std::ostringstream& {
    text << std::defaultfloat << std::setprecision(9) << v;
    return text;
  };
  text << "# Intrinsics of the images: pinhole with OpenCV's radial-tangential distortion\n"
          "# (k1 k2 p1 p2 k3, on normalised coordinates); depth and labels are registered\n"
          "# to the colour camera and share its lens.\n"
          "camera:\n  model: pinhole\n  width: "
       << c.width << "\n  height: " << c.height << "\n  fx: ";
  fixed(6, c.fx) << "\n  fy: ";
  fixed(6, c.fy) << "\n  cx: ";
  fixed(6, c.cx) << "\n  cy: ";
  fixed(6, c.cy) << "\n  k1: ";
  general(c.lens.k1) << "\n  k2: ";
  general(c.lens.k2) << "\n  p1: ";
  general(c.lens.p1) << "\n  p2: ";
  general(c.lens.p2) << "\n  k3: ";
  general(c.lens.k3) << "\ndepth:\n  factor: ";
  fixed(1, c.depth_factor) << "  # PNG value per metre\n  min: ";
  fixed(3, c.depth_min) << "\n  max: ";
  fixed(3, c.depth_max) << "\n  model: " << c.depth_model << "\n  baseline: ";
  fixed(4, c.depth_baseline) << "\n";
  return text.str();
}

}  // namespace depot::dataset
