#include "slam/detect/sim_detector.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/rng.h"

namespace depot::slam {
namespace {

constexpr size_t kMinBoxesForFill = 10;
// Random stream ids under (seed, frame).
constexpr uint64_t kObjectStream = 1, kFalsePositiveStream = 2;

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

double model_smallness(double area, double image_area, double small_area) {
  return clamp01(1.0 - std::sqrt(area / (small_area * image_area)));
}

double model_difficulty(double smallness, double occlusion) {
  return 1.0 - (1.0 - smallness) * (1.0 - occlusion);
}

SimDetector::SimDetector(const std::string& dataset_dir, const SimDetectorConfig& config)
    : dir_(dataset_dir), config_(config) {
  validate(config_, "simulated detector config");
  data_ = read_dataset_boxes(dataset_dir);

  // Per class: the fill of an unoccluded object, the box sizes, the partners.
  const size_t n = data_.classes.size();
  std::vector<std::vector<double>> fills(n);
  class_sizes_.assign(n, {});
  for (const auto& frame : data_.frames) {
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
  miss_rate_.assign(n, config_.miss_rate);
  confusion_rate_.assign(n, config_.class_confusion);
  for (size_t c = 0; c < n; ++c) {
    const auto miss = config_.class_miss_rate.find(data_.classes[c]);
    if (miss != config_.class_miss_rate.end()) miss_rate_[c] = miss->second;
    const auto confusion = config_.class_confusion_rate.find(data_.classes[c]);
    if (confusion != config_.class_confusion_rate.end()) confusion_rate_[c] = confusion->second;
  }
  confusions_.assign(n, {});
  for (const auto& [name, partners] : config_.confusions) {
    const auto from = std::find(data_.classes.begin(), data_.classes.end(), name);
    if (from == data_.classes.end()) continue;
    for (const std::string& p : partners) {
      const auto to = std::find(data_.classes.begin(), data_.classes.end(), p);
      if (to != data_.classes.end() && to != from)
        confusions_[from - data_.classes.begin()].push_back(
            static_cast<int>(to - data_.classes.begin()));
    }
  }
}

long SimDetector::find_frame(double timestamp) const {
  return nearest_timestamp(data_.timestamps, timestamp);
}

double SimDetector::reference_fill(const std::string& class_name) const {
  const auto it = std::find(data_.classes.begin(), data_.classes.end(), class_name);
  return it == data_.classes.end() ? config_.default_fill
                                   : reference_fill_[it - data_.classes.begin()];
}

double SimDetector::class_miss_rate(const std::string& class_name) const {
  const auto it = std::find(data_.classes.begin(), data_.classes.end(), class_name);
  return it == data_.classes.end() ? config_.miss_rate : miss_rate_[it - data_.classes.begin()];
}

double SimDetector::smallness(const TruthBox& box) const {
  const double image_area = static_cast<double>(data_.image_size.area());
  return model_smallness(box.area(), image_area, config_.small_area);
}

double SimDetector::occlusion(const TruthBox& box) const {
  const double fill = static_cast<double>(box.visible_pixels) / std::max(1, box.area());
  const double ref = box.class_id >= 0 && box.class_id < static_cast<int>(reference_fill_.size())
                         ? reference_fill_[box.class_id]
                         : config_.default_fill;
  return clamp01(1.0 - fill / ref);
}

double SimDetector::difficulty(const TruthBox& box) const {
  return model_difficulty(smallness(box), occlusion(box));
}

double SimDetector::miss_probability(const TruthBox& box) const {
  const double base = box.class_id >= 0 && box.class_id < static_cast<int>(miss_rate_.size())
                          ? miss_rate_[box.class_id]
                          : config_.miss_rate;
  return 1.0 - (1.0 - base) * (1.0 - config_.small_miss_boost * smallness(box)) *
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
  if (!partners.empty() && u_confuse < confusion_rate_[box.class_id]) {
    out.class_id = partners[pick % partners.size()];
    out.class_name = data_.classes[out.class_id];
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
                 data_.image_size);
  if (out.box.width <= 0 || out.box.height <= 0) return false;
  const double mean = config_.max_confidence - (config_.max_confidence - config_.min_confidence) *
                                                   config_.confidence_drop * d;
  out.confidence = static_cast<float>(
      std::min(1.0, std::max(config_.min_confidence, mean + config_.confidence_noise * n_conf)));
  return true;
}

void SimDetector::add_false_positives(size_t frame, std::vector<Detection>& out) const {
  Rng rng(derive_seed(config_.seed, frame, kFalsePositiveStream));
  const int count = poisson(rng, config_.false_positive_rate);
  const double W = data_.image_size.width, H = data_.image_size.height;
  for (int i = 0; i < count; ++i) {
    Detection d;
    d.class_id = static_cast<int>(rng.below(data_.classes.size()));
    d.class_name = data_.classes[d.class_id];
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
                 data_.image_size);
    d.confidence = static_cast<float>(
        rng.uniform(config_.min_confidence, config_.false_positive_max_confidence));
    out.push_back(std::move(d));
  }
}

std::vector<Detection> SimDetector::detect_frame(size_t index) const {
  const std::vector<TruthBox>& boxes = data_.frames.at(index);
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
  if (!bgr.empty() && bgr.size() != data_.image_size)
    fail(dir_, "image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
                   " but the dataset's frames are " + std::to_string(data_.image_size.width) + "x" +
                   std::to_string(data_.image_size.height));
  const long frame = find_frame(timestamp);
  if (frame < 0)
    fail((std::filesystem::path(dir_) / "rgb.txt").string(),
         "no frame at timestamp " + fmt::format("{:.6f}", timestamp));
  const long lagged = frame - config_.latency_frames;
  if (lagged < 0) return {};
  return detect_frame(static_cast<size_t>(lagged));
}

}  // namespace depot::slam
