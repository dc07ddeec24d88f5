#include "slam/detect/truth_boxes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/tum_io.h"
#include "dataset/boxes.h"
#include "dataset/calibration.h"
#include "dataset/class_list.h"
#include "dataset/dataset_files.h"

namespace depot::slam {
namespace {

constexpr double kMatchTolerance = 1e-4;  // s

std::string join(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
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
  const dataset::CameraCalibration camera =
      dataset::read_calibration(join(dir, "calibration.yaml"));
  d.image_size = cv::Size(camera.width, camera.height);
  const std::string rgb_path = join(dir, "rgb.txt");
  for (const StampedFile& f : read_file_list(rgb_path)) {
    d.timestamps.push_back(f.timestamp);
    d.rgb_files.push_back(f.path);
  }
  if (d.timestamps.empty()) fail(rgb_path, "lists no frame");
  if (!std::is_sorted(d.timestamps.begin(), d.timestamps.end()))
    fail(rgb_path, "timestamps are not in increasing order");
  d.frames.resize(d.timestamps.size());
  d.classes = dataset::read_dataset_classes(dir);

  // boxes.txt as the dataset library reads it; here the checks against the
  // other files: a frame of rgb.txt, a class of classes.txt, inside the image.
  const cv::Size image = d.image_size;
  for (const dataset::BoxRecord& r : dataset::read_boxes(dir)) {
    const std::string where = dataset::box_location(dir, r);
    const long frame = nearest_timestamp(d.timestamps, r.timestamp);
    if (frame < 0)
      fail(where,
           "timestamp " + dataset::format_timestamp(r.timestamp) + " is not a frame of rgb.txt");
    const auto cls = std::find(d.classes.begin(), d.classes.end(), r.class_name);
    if (cls == d.classes.end()) fail(where, "class '" + r.class_name + "' is not in classes.txt");
    if (r.x2 > image.width || r.y2 > image.height)
      fail(where, "box " + std::to_string(r.x1) + " " + std::to_string(r.y1) + " " +
                      std::to_string(r.x2) + " " + std::to_string(r.y2) + " is outside the " +
                      std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
    TruthBox b;
    b.id = r.id;
    b.class_name = r.class_name;
    b.class_id = static_cast<int>(cls - d.classes.begin());
    b.x1 = r.x1;
    b.y1 = r.y1;
    b.x2 = r.x2;
    b.y2 = r.y2;
    b.visible_pixels = r.visible_pixels;
    b.moving = r.moving;
    d.frames[static_cast<size_t>(frame)].push_back(std::move(b));
  }
  return d;
}

}  // namespace depot::slam
