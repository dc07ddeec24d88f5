#include "eval/motion_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/fast_circle.h"
#include "common/png_codec.h"
#include "common/tum_io.h"

namespace fs = std::filesystem;

namespace depot::eval {
namespace {

std::string stamp_key(double t) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6f", t);
  return buf;
}

}  // namespace

bool MotionTruth::available(const std::string& dataset) {
  return fs::is_regular_file(fs::path(dataset) / "labels.txt") &&
         fs::is_regular_file(fs::path(dataset) / "object_poses.txt");
}

MotionTruth::MotionTruth(const std::string& dataset) : root_(dataset) {
  if (!available(dataset))
    fail(dataset, "no ground-truth labels (labels.txt, object_poses.txt): not a simulated dataset");
  for (const auto& f : read_file_list((fs::path(dataset) / "labels.txt").string()))
    label_files_[stamp_key(f.timestamp)] = f.path;
  const std::string poses = (fs::path(dataset) / "object_poses.txt").string();
  std::ifstream in(poses);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string stamp;
    int id = 0, moving = 0;
    double v[7];
    if (!(s >> stamp >> id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> moving))
      fail(poses + ":" + std::to_string(line_no),
           "expected 'timestamp id tx ty tz qx qy qz qw moving'");
    if (moving) moving_ids_[stamp].insert(id);
  }
}

cv::Mat MotionTruth::load_labels(const std::string& key) const {
  auto it = label_files_.find(key);
  if (it == label_files_.end()) fail(root_, "no label image for timestamp " + key);
  const std::string path = (fs::path(root_) / it->second).string();
  cv::Mat labels = read_image(path, ImageRead::kUnchanged);
  if (labels.type() != CV_16UC1) fail(path, "label image is not 16-bit single-channel");
  return labels;
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
