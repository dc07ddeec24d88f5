#include "slam/detect/truth_boxes.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/text_records.h"
#include "common/tum_io.h"
#include "common/yaml_file.h"
#include "slam/detect/class_names.h"

namespace depot::slam {
namespace {

constexpr double kMatchTolerance = 1e-4;  // s

std::string join(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}

long parse_int(const std::string& where, const std::string& s, const char* what) {
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || errno == ERANGE)
    fail(where, std::string(what) + " '" + s + "' is not an integer");
  return v;
}

cv::Size read_image_size(const std::string& path) {
  YAML::Node root = load_yaml_file(path, "file (the dataset's camera calibration)");
  const YAML::Node cam = root["camera"];
  if (!cam || !cam["width"] || !cam["height"]) fail(path, "no camera: width/height");
  cv::Size size;
  try {
    size = cv::Size(cam["width"].as<int>(), cam["height"].as<int>());
  } catch (const YAML::Exception&) {
    fail(path, "camera width/height are not integers");
  }
  if (size.width <= 0 || size.height <= 0 || size.width > 100000 || size.height > 100000)
    fail(path,
         "invalid image size " + std::to_string(size.width) + "x" + std::to_string(size.height));
  return size;
}

std::vector<std::string> read_classes(const std::string& path) {
  if (!std::filesystem::exists(path)) fail(path, "missing (the detectable classes, one a line)");
  std::vector<std::string> classes = load_class_names(path);
  for (size_t i = 0; i < classes.size(); ++i)
    if (std::find(classes.begin(), classes.begin() + static_cast<long>(i), classes[i]) !=
        classes.begin() + static_cast<long>(i))
      fail(path, "class '" + classes[i] + "' is listed twice");
  return classes;
}

}  // namespace

long nearest_timestamp(const std::vector<double>& stamps, double t) {
  const auto it = std::lower_bound(stamps.begin(), stamps.end(), t);
  long best = -1;
  double best_dt = kMatchTolerance;
  for (auto c : {it, it == stamps.begin() ? it : it - 1}) {
    if (c == stamps.end()) continue;
    const double dt = std::abs(*c - t);
    if (dt <= best_dt) {
      best = static_cast<long>(c - stamps.begin());
      best_dt = dt;
    }
  }
  return best;
}

DatasetBoxes read_dataset_boxes(const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) fail(dir, "not a dataset folder");
  DatasetBoxes d;
  d.image_size = read_image_size(join(dir, "calibration.yaml"));
  const std::string rgb_path = join(dir, "rgb.txt");
  for (const StampedFile& f : read_file_list(rgb_path)) {
    d.timestamps.push_back(f.timestamp);
    d.rgb_files.push_back(f.path);
  }
  if (d.timestamps.empty()) fail(rgb_path, "lists no frame");
  if (!std::is_sorted(d.timestamps.begin(), d.timestamps.end()))
    fail(rgb_path, "timestamps are not in increasing order");
  d.frames.resize(d.timestamps.size());
  d.classes = read_classes(join(dir, "classes.txt"));

  const std::string boxes_path = join(dir, "boxes.txt");
  std::ifstream in(boxes_path);
  if (!in) fail(boxes_path, "cannot open file (the ground-truth boxes)");
  const cv::Size image = d.image_size;
  for_each_record(in, boxes_path, [&](const std::string& where, const std::vector<std::string>& f) {
    if (f.size() != 9)
      fail(where,
           "expected 9 fields (timestamp id class x1 y1 x2 y2 visible_pixels moving), found " +
               std::to_string(f.size()));
    char* end = nullptr;
    const double t = std::strtod(f[0].c_str(), &end);
    if (end == f[0].c_str() || *end != '\0' || !std::isfinite(t))
      fail(where, "timestamp '" + f[0] + "' is not a number");
    const long frame = nearest_timestamp(d.timestamps, t);
    if (frame < 0) fail(where, "timestamp " + f[0] + " is not a frame of rgb.txt");
    TruthBox b;
    b.id = static_cast<int>(parse_int(where, f[1], "id"));
    b.class_name = f[2];
    const auto cls = std::find(d.classes.begin(), d.classes.end(), b.class_name);
    if (cls == d.classes.end()) fail(where, "class '" + b.class_name + "' is not in classes.txt");
    b.class_id = static_cast<int>(cls - d.classes.begin());
    b.x1 = static_cast<int>(parse_int(where, f[3], "x1"));
    b.y1 = static_cast<int>(parse_int(where, f[4], "y1"));
    b.x2 = static_cast<int>(parse_int(where, f[5], "x2"));
    b.y2 = static_cast<int>(parse_int(where, f[6], "y2"));
    b.visible_pixels = static_cast<int>(parse_int(where, f[7], "visible_pixels"));
    const long moving = parse_int(where, f[8], "moving");
    if (moving != 0 && moving != 1) fail(where, "moving '" + f[8] + "' is not 0 or 1");
    b.moving = moving == 1;
    if (b.x1 < 0 || b.y1 < 0 || b.x2 <= b.x1 || b.y2 <= b.y1 || b.x2 > image.width ||
        b.y2 > image.height)
      fail(where, "box " + f[3] + " " + f[4] + " " + f[5] + " " + f[6] +
                      " is empty or outside the " + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + " image");
    if (b.visible_pixels < 1 || b.visible_pixels > b.area())
      fail(where,
           "visible_pixels " + f[7] + " is not in [1, box area " + std::to_string(b.area()) + "]");
    d.frames[frame].push_back(std::move(b));
  });
  if (in.bad()) fail(boxes_path, "read error");
  return d;
}

}  // namespace depot::slam
