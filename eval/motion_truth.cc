#include "eval/motion_truth.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error.h"
#include "common/fast_circle.h"
#include "dataset/dataset_files.h"
#include "dataset/label_images.h"
#include "dataset/object_poses.h"

namespace fs = std::filesystem;

namespace depot::eval {
namespace {

// Frames are joined across files by their written timestamp.
std::string stamp_key(double t) {
  return dataset::format_timestamp(t);
}

}  // namespace

bool MotionTruth::available(const std::string& dataset) {
  return dataset::has_label_list(dataset) &&
         fs::is_regular_file(dataset::dataset_file(dataset, dataset::kObjectPosesFile));
}

MotionTruth::MotionTruth(const std::string& dataset) : root_(dataset) {
  if (!available(dataset))
    fail(dataset, "no ground-truth labels (labels.txt, object_poses.txt): not a simulated dataset");
  for (const StampedFile& f : dataset::read_label_list(dataset))
    label_files_[stamp_key(f.timestamp)] = f.path;
  for (const dataset::ObjectPoseRecord& r : dataset::read_object_poses(dataset))
    if (r.moving) moving_ids_[stamp_key(r.timestamp)].insert(r.id);
}

cv::Mat MotionTruth::load_labels(const std::string& key) const {
  auto it = label_files_.find(key);
  if (it == label_files_.end()) fail(root_, "no label image for timestamp " + key);
  return dataset::read_label_image(root_, it->second);
}

cv::Mat MotionTruth::label_image(double timestamp) const {
  return load_labels(stamp_key(timestamp));
}

std::vector<double> MotionTruth::timestamps() const {
  std::vector<double> stamps;
  for (const auto& [key, file] : label_files_) stamps.push_back(std::stod(key));
  return stamps;
}

MotionTruth::KeypointTruth MotionTruth::classify_keypoints(
    double timestamp, const std::vector<cv::KeyPoint>& keypoints, float scale_factor) const {
  const std::string key = stamp_key(timestamp);
  const cv::Mat labels = load_labels(key);
  KeypointTruth out{std::vector<uint8_t>(keypoints.size(), 0),
                    std::vector<uint8_t>(keypoints.size(), 0),
                    std::vector<uint16_t>(keypoints.size(), 0)};
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int x = static_cast<int>(std::lround(keypoints[i].pt.x));
    const int y = static_cast<int>(std::lround(keypoints[i].pt.y));
    if (x >= 0 && y >= 0 && x < labels.cols && y < labels.rows)
      out.instance[i] = labels.at<uint16_t>(y, x);
  }
  auto moving = moving_ids_.find(key);
  if (moving == moving_ids_.end()) return out;
  auto moving_at = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < labels.cols && y < labels.rows &&
           moving->second.count(labels.at<uint16_t>(y, x));
  };
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& kp = keypoints[i];
    const int cx = static_cast<int>(std::lround(kp.pt.x));
    const int cy = static_cast<int>(std::lround(kp.pt.y));
    out.on_moving[i] = moving_at(cx, cy);
    if (out.on_moving[i]) continue;
    out.boundary[i] = fast_circle_touches(kp, fast_circle_scale(kp, scale_factor), moving_at);
  }
  return out;
}

cv::Mat MotionTruth::moving_mask(double timestamp, cv::Mat* labels_out) const {
  const std::string key = stamp_key(timestamp);
  const cv::Mat labels = load_labels(key);
  if (labels_out) *labels_out = labels;
  cv::Mat mask = cv::Mat::zeros(labels.size(), CV_8U);
  auto moving = moving_ids_.find(key);
  if (moving == moving_ids_.end()) return mask;
  for (int y = 0; y < labels.rows; ++y) {
    const uint16_t* row = labels.ptr<uint16_t>(y);
    uint8_t* out = mask.ptr<uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x) out[x] = moving->second.count(row[x]) ? 255 : 0;
  }
  return mask;
}

double MotionTruth::moving_fraction(double timestamp) const {
  const cv::Mat mask = moving_mask(timestamp);
  return static_cast<double>(cv::countNonZero(mask)) / mask.total();
}

std::vector<uint8_t> MotionTruth::on_moving_object(
    double timestamp, const std::vector<cv::KeyPoint>& keypoints) const {
  return classify_keypoints(timestamp, keypoints, 1.0f).on_moving;
}

void RejectionScore::add(const std::vector<uint8_t>& keep, const std::vector<uint8_t>& moving,
                         const std::vector<uint8_t>& boundary) {
  for (size_t i = 0; i < keep.size() && i < moving.size(); ++i) {
    const bool rejected = !keep[i];
    const bool on_boundary = i < boundary.size() && boundary[i];
    if (rejected && moving[i]) {
      ++true_positive;
    } else if (rejected) {
      ++false_positive;
      boundary_false_positive += on_boundary;
    } else if (moving[i]) {
      ++false_negative;
    } else {
      ++true_negative;
      boundary_true_negative += on_boundary;
    }
  }
}

void RejectionScore::add(const RejectionScore& o) {
  true_positive += o.true_positive;
  false_positive += o.false_positive;
  false_negative += o.false_negative;
  true_negative += o.true_negative;
  boundary_false_positive += o.boundary_false_positive;
  boundary_true_negative += o.boundary_true_negative;
}

double RejectionScore::precision_without_boundary() const {
  const long n = true_positive + false_positive - boundary_false_positive;
  return n ? static_cast<double>(true_positive) / n : NAN;
}

double RejectionScore::precision() const {
  const long n = true_positive + false_positive;
  return n ? static_cast<double>(true_positive) / n : NAN;
}

double RejectionScore::recall() const {
  const long n = true_positive + false_negative;
  return n ? static_cast<double>(true_positive) / n : NAN;
}

}  // namespace depot::eval
