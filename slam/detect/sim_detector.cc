#include "slam/detect/sim_detector.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/rng.h"
#include "common/tum_io.h"
#include "common/yaml_file.h"
#include "slam/detect/class_names.h"
#include "slam/detect/text_records.h"

namespace depot::slam {
namespace {

constexpr double kMatchTolerance = 1e-4;  // s
constexpr size_t kMinBoxesForFill = 10;
// Random stream ids under (seed, frame).
constexpr uint64_t kObjectStream = 1, kFalsePositiveStream = 2;

std::string join(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}

// Nearest entry of the sorted `stamps` within the tolerance, or -1.
long nearest(const std::vector<double>& stamps, double t) {
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

// Poisson sample by multiplying uniforms (Knuth); fine for small means.
int poisson(Rng& rng, double mean) {
  if (mean <= 0) return 0;
  const double limit = std::exp(-mean);
  int k = 0;
  double p = rng.uniform();
  while (p > limit) {
    ++k;
    p *= rng.uniform();
  }
  return k;
}

double clamp01(double v) {
  return std::min(1.0, std::max(0.0, v));
}

// The box clipped to [0, W] x [0, H].
cv::Rect2f clip(const cv::Rect2f& b, cv::Size size) {
  const float x1 = std::max(0.0f, b.x), y1 = std::max(0.0f, b.y);
  const float x2 = std::min(static_cast<float>(size.width), b.x + b.width);
  const float y2 = std::min(static_cast<float>(size.height), b.y + b.height);
  return cv::Rect2f(x1, y1, std::max(0.0f, x2 - x1), std::max(0.0f, y2 - y1));
}

}  // namespace

SimDetector::SimDetector(const std::string& dataset_dir, const SimDetectorConfig& config)
    : dir_(dataset_dir), config_(config) {
  validate(config_, "simulated detector config");
  if (!std::filesystem::is_directory(dir_)) fail(dir_, "not a dataset folder");
  image_size_ = read_image_size(join(dir_, "calibration.yaml"));
  const std::string rgb_path = join(dir_, "rgb.txt");
  for (const StampedFile& f : read_file_list(rgb_path)) timestamps_.push_back(f.timestamp);
  if (timestamps_.empty()) fail(rgb_path, "lists no frame");
  if (!std::is_sorted(timestamps_.begin(), timestamps_.end()))
    fail(rgb_path, "timestamps are not in increasing order");
  truth_.resize(timestamps_.size());

  const std::string classes_path = join(dir_, "classes.txt");
  if (!std::filesystem::exists(classes_path))
    fail(classes_path, "missing (the detectable classes, one a line)");
  classes_ = load_class_names(classes_path);
  for (size_t i = 0; i < classes_.size(); ++i)
    if (std::find(classes_.begin(), classes_.begin() + static_cast<long>(i), classes_[i]) !=
        classes_.begin() + static_cast<long>(i))
      fail(classes_path, "class '" + classes_[i] + "' is listed twice");

  // boxes.txt: timestamp id class x1 y1 x2 y2 visible_pixels moving
  const std::string boxes_path = join(dir_, "boxes.txt");
  std::ifstream in(boxes_path);
  if (!in) fail(boxes_path, "cannot open file (the ground-truth boxes)");
  for_each_record(in, boxes_path, [&](const std::string& where, const std::vector<std::string>& f) {
    if (f.size() != 9)
      fail(where,
           "expected 9 fields (timestamp id class x1 y1 x2 y2 visible_pixels moving), found " +
               std::to_string(f.size()));
    char* end = nullptr;
    const double t = std::strtod(f[0].c_str(), &end);
    if (end == f[0].c_str() || *end != '\0' || !std::isfinite(t))
      fail(where, "timestamp '" + f[0] + "' is not a number");
    const long frame = nearest(timestamps_, t);
    if (frame < 0) fail(where, "timestamp " + f[0] + " is not a frame of rgb.txt");
    TruthBox b;
    b.id = static_cast<int>(parse_int(where, f[1], "id"));
    b.class_name = f[2];
    const auto cls = std::find(classes_.begin(), classes_.end(), b.class_name);
    if (cls == classes_.end()) fail(where, "class '" + b.class_name + "' is not in classes.txt");
    b.class_id = static_cast<int>(cls - classes_.begin());
    b.x1 = static_cast<int>(parse_int(where, f[3], "x1"));
    b.y1 = static_cast<int>(parse_int(where, f[4], "y1"));
    b.x2 = static_cast<int>(parse_int(where, f[5], "x2"));
    b.y2 = static_cast<int>(parse_int(where, f[6], "y2"));
    b.visible_pixels = static_cast<int>(parse_int(where, f[7], "visible_pixels"));
    const long moving = parse_int(where, f[8], "moving");
    if (moving != 0 && moving != 1) fail(where, "moving '" + f[8] + "' is not 0 or 1");
    b.moving = moving == 1;
    if (b.x1 < 0 || b.y1 < 0 || b.x2 <= b.x1 || b.y2 <= b.y1 || b.x2 > image_size_.width ||
        b.y2 > image_size_.height)
      fail(where, "box " + f[3] + " " + f[4] + " " + f[5] + " " + f[6] +
                      " is empty or outside the " + std::to_string(image_size_.width) + "x" +
                      std::to_string(image_size_.height) + " image");
    if (b.visible_pixels < 1 || b.visible_pixels > b.area())
      fail(where,
           "visible_pixels " + f[7] + " is not in [1, box area " + std::to_string(b.area()) + "]");
    truth_[frame].push_back(std::move(b));
  });
  if (in.bad()) fail(boxes_path, "read error");

  // Per class: the fill of an unoccluded object, the box sizes, the partners.
  const size_t n = classes_.size();
  std::vector<std::vector<double>> fills(n);
  class_sizes_.assign(n, {});
  for (const auto& frame : truth_) {
    for (const TruthBox& b : frame) {
      fills[b.class_id].push_back(static_cast<double>(b.visible_pixels) / b.area());
      class_sizes_[b.class_id].emplace_back(b.x2 - b.x1, b.y2 - b.y1);
    }
  }
  reference_fill_.assign(n, config_.default_fill);
  for (size_t c = 0; c < n; ++c) {
    auto& v = fills[c];
    if (v.size() < kMinBoxesForFill) continue;
    const size_t k = static_cast<size_t>(0.9 * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    reference_fill_[c] = v[k];
  }
  confusions_.assign(n, {});
  for (const auto& [name, partners] : config_.confusions) {
    const auto from = std::find(classes_.begin(), classes_.end(), name);
    if (from == classes_.end()) continue;
    for (const std::string& p : partners) {
      const auto to = std::find(classes_.begin(), classes_.end(), p);
      if (to != classes_.end() && to != from)
        confusions_[from - classes_.begin()].push_back(static_cast<int>(to - classes_.begin()));
    }
  }
}

long SimDetector::find_frame(double timestamp) const {
  return nearest(timestamps_, timestamp);
}

double SimDetector::reference_fill(const std::string& class_name) const {
  const auto it = std::find(classes_.begin(), classes_.end(), class_name);
  return it == classes_.end() ? config_.default_fill : reference_fill_[it - classes_.begin()];
}

double SimDetector::smallness(const TruthBox& box) const {
  const double image_area = static_cast<double>(image_size_.area());
  return clamp01(1.0 - std::sqrt(box.area() / (config_.small_area * image_area)));
}

double SimDetector::occlusion(const TruthBox& box) const {
  const double fill = static_cast<double>(box.visible_pixels) / std::max(1, box.area());
  const double ref = box.class_id >= 0 && box.class_id < static_cast<int>(reference_fill_.size())
                         ? reference_fill_[box.class_id]
                         : config_.default_fill;
  return clamp01(1.0 - fill / ref);
}

double SimDetector::difficulty(const TruthBox& box) const {
  return 1.0 - (1.0 - smallness(box)) * (1.0 - occlusion(box));
}

double SimDetector::miss_probability(const TruthBox& box) const {
  return 1.0 - (1.0 - config_.miss_rate) * (1.0 - config_.small_miss_boost * smallness(box)) *
                   (1.0 - config_.occlusion_miss * occlusion(box));
}

bool SimDetector::detect_box(const TruthBox& box, size_t frame, Detection& out) const {
  out.class_name = box.class_name;
  out.class_id = box.class_id;
  if (config_.perfect) {
    out.confidence = 1.0f;
    out.box = box.rect();
    return true;
  }
  // A fixed sequence of draws, whatever the branches: settings only change
  // what a draw means, never which draw another decision gets.
  Rng rng(derive_seed(config_.seed, frame, kObjectStream, static_cast<uint64_t>(box.id)));
  const double u_miss = rng.uniform();
  const double u_confuse = rng.uniform();
  const uint64_t pick = rng.next_u64();
  const double n_cx = rng.normal(), n_cy = rng.normal();
  const double n_w = rng.normal(), n_h = rng.normal();
  const double n_conf = rng.normal();

  if (u_miss < miss_probability(box)) return false;
  double d = difficulty(box);
  const auto& partners = confusions_[box.class_id];
  if (!partners.empty() && u_confuse < config_.class_confusion) {
    out.class_id = partners[pick % partners.size()];
    out.class_name = classes_[out.class_id];
    d = std::max(d, 0.5);
  }
  const double gain = 1.0 + config_.hard_jitter_gain * d;
  const double w = box.x2 - box.x1, h = box.y2 - box.y1;
  const double cx = 0.5 * (box.x1 + box.x2) + n_cx * config_.jitter * gain * w;
  const double cy = 0.5 * (box.y1 + box.y2) + n_cy * config_.jitter * gain * h;
  const double w2 = w * std::exp(n_w * config_.scale_error * gain);
  const double h2 = h * std::exp(n_h * config_.scale_error * gain);
  out.box = clip(cv::Rect2f(static_cast<float>(cx - 0.5 * w2), static_cast<float>(cy - 0.5 * h2),
                            static_cast<float>(w2), static_cast<float>(h2)),
                 image_size_);
  if (out.box.width <= 0 || out.box.height <= 0) return false;
  const double mean =
      config_.max_confidence - (config_.max_confidence - config_.min_confidence) * d;
  out.confidence = static_cast<float>(
      std::min(1.0, std::max(config_.min_confidence, mean + config_.confidence_noise * n_conf)));
  return true;
}

void SimDetector::add_false_positives(size_t frame, std::vector<Detection>& out) const {
  Rng rng(derive_seed(config_.seed, frame, kFalsePositiveStream));
  const int count = poisson(rng, config_.false_positive_rate);
  const double W = image_size_.width, H = image_size_.height;
  for (int i = 0; i < count; ++i) {
    Detection d;
    d.class_id = static_cast<int>(rng.below(classes_.size()));
    d.class_name = classes_[d.class_id];
    const auto& sizes = class_sizes_[d.class_id];
    double w, h;
    if (!sizes.empty()) {
      // The size of a real object of the class, give or take 35 %.
      const cv::Size s = sizes[rng.below(sizes.size())];
      const double scale = std::exp(rng.uniform(-0.3, 0.3));
      w = s.width * scale;
      h = s.height * scale;
    } else {
      // A generic object: 0.2 % to 5 % of the image, aspect 1:2 to 2:1.
      const double area = std::exp(rng.uniform(std::log(0.002), std::log(0.05))) * W * H;
      const double aspect = std::exp(rng.uniform(std::log(0.5), std::log(2.0)));
      w = std::sqrt(area * aspect);
      h = area / w;
    }
    w = std::min(std::max(w, 1.0), W);
    h = std::min(std::max(h, 1.0), H);
    const double x = rng.uniform(0.0, W - w), y = rng.uniform(0.0, H - h);
    d.box = clip(cv::Rect2f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(w),
                            static_cast<float>(h)),
                 image_size_);
    d.confidence = static_cast<float>(
        rng.uniform(config_.min_confidence, config_.false_positive_max_confidence));
    out.push_back(std::move(d));
  }
}

std::vector<Detection> SimDetector::detect_frame(size_t index) const {
  const std::vector<TruthBox>& boxes = truth_.at(index);
  std::vector<Detection> out;
  out.reserve(boxes.size() + 1);
  for (const TruthBox& b : boxes) {
    Detection d;
    if (detect_box(b, index, d)) out.push_back(std::move(d));
  }
  if (!config_.perfect) add_false_positives(index, out);
  return out;
}

std::vector<Detection> SimDetector::detect(const cv::Mat& bgr, double timestamp, long) {
  if (!bgr.empty() && bgr.size() != image_size_)
    fail(dir_, "image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                   " but the dataset's frames are " + std::to_string(image_size_.width) + "x" +
                   std::to_string(image_size_.height));
  const long frame = find_frame(timestamp);
  if (frame < 0) {
    char stamp[64];
    std::snprintf(stamp, sizeof(stamp), "%.6f", timestamp);
    fail(join(dir_, "rgb.txt"), std::string("no frame at timestamp ") + stamp);
  }
  const long lagged = frame - config_.latency_frames;
  if (lagged < 0) return {};
  return detect_frame(static_cast<size_t>(lagged));
}

}  // namespace depot::slam
