#include "slam/detect/detection_file.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <type_traits>

#include "common/error.h"
#include "common/text_records.h"
#include "common/tum_io.h"

namespace depot::slam {
namespace {

constexpr double kMatchTolerance = 1e-4;  // s

// The shortest text that reads back as the same float.
std::string shortest(float v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

bool has_space(const std::string& s) {
  return std::any_of(s.begin(), s.end(),
                     [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

template <typename T>
T parse(const std::string& where, const std::string& field, const char* what) {
  const char* s = field.c_str();
  char* end = nullptr;
  T v;
  if constexpr (std::is_same_v<T, float>) {
    v = std::strtof(s, &end);
  } else {
    v = std::strtod(s, &end);
  }
  if (end == s || *end != '\0') fail(where, std::string(what) + " '" + field + "' is not a number");
  if (!std::isfinite(v)) fail(where, std::string(what) + " '" + field + "' is not finite");
  return v;
}

}  // namespace

void write_detections_file(const std::string& path, const std::vector<DetectionFrame>& frames) {
  std::string text =
      "# detections: timestamp class_name confidence x1 y1 x2 y2 (pixels, x2 = x + width)\n";
  for (const DetectionFrame& f : frames) {
    if (!std::isfinite(f.timestamp) || f.timestamp < 0)
      fail(path, "frame timestamp " + std::to_string(f.timestamp) + " is not a valid time");
    const std::string stamp = fmt::format("{:.6f}", f.timestamp);
    for (const Detection& d : f.detections) {
      const std::string at = path + ": frame " + stamp;
      if (d.class_name.empty() || has_space(d.class_name))
        fail(at, "class name '" + d.class_name + "' is empty or contains white space");
      const cv::Rect2f& b = d.box;
      const float x2 = b.x + b.width, y2 = b.y + b.height;
      for (float v : {d.confidence, b.x, b.y, x2, y2})
        if (!std::isfinite(v))
          fail(at, "detection of '" + d.class_name + "' has a non-finite value");
      if (b.width < 0 || b.height < 0)
        fail(at, "box of '" + d.class_name + "' has a negative size");
      if (d.confidence < 0 || d.confidence > 1)
        fail(at, "confidence of '" + d.class_name + "' is outside [0, 1]");
      text += stamp + " " + d.class_name + " " + shortest(d.confidence) + " " + shortest(b.x) +
              " " + shortest(b.y) + " " + shortest(x2) + " " + shortest(y2) + "\n";
    }
  }
  write_text_file_atomic(path, text);
}

std::vector<DetectionFrame> read_detections_file(const std::string& path,
                                                 const std::vector<std::string>& class_names) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file");
  // Frames keyed by the timestamp in microseconds, so equal stamps group.
  std::map<long long, DetectionFrame> frames;
  for_each_record(in, path, [&](const std::string& where, const std::vector<std::string>& f) {
    if (f.size() != 7)
      fail(where, "expected 7 fields (timestamp class_name confidence x1 y1 x2 y2), found " +
                      std::to_string(f.size()));
    const double t = parse<double>(where, f[0], "timestamp");
    if (t < 0) fail(where, "timestamp '" + f[0] + "' is negative");
    Detection d;
    d.class_name = f[1];
    if (!class_names.empty()) {
      const auto it = std::find(class_names.begin(), class_names.end(), d.class_name);
      if (it == class_names.end()) fail(where, "unknown class '" + d.class_name + "'");
      d.class_id = static_cast<int>(it - class_names.begin());
    }
    d.confidence = parse<float>(where, f[2], "confidence");
    if (d.confidence < 0 || d.confidence > 1)
      fail(where, "confidence '" + f[2] + "' is outside [0, 1]");
    const float x1 = parse<float>(where, f[3], "x1"), y1 = parse<float>(where, f[4], "y1");
    const float x2 = parse<float>(where, f[5], "x2"), y2 = parse<float>(where, f[6], "y2");
    if (x2 < x1) fail(where, "x2 " + f[5] + " is left of x1 " + f[3]);
    if (y2 < y1) fail(where, "y2 " + f[6] + " is above y1 " + f[4]);
    d.box = cv::Rect2f(x1, y1, x2 - x1, y2 - y1);
    DetectionFrame& frame = frames[std::llround(t * 1e6)];
    frame.timestamp = t;
    frame.detections.push_back(std::move(d));
  });
  if (in.bad()) fail(path, "read error");
  std::vector<DetectionFrame> out;
  out.reserve(frames.size());
  for (auto& [key, frame] : frames) out.push_back(std::move(frame));
  return out;
}

FileDetector::FileDetector(const std::string& path, const std::vector<std::string>& class_names)
    : frames_(read_detections_file(path, class_names)), label_(path), class_names_(class_names) {}

FileDetector::FileDetector(std::vector<DetectionFrame> frames, std::string label)
    : frames_(std::move(frames)), label_(std::move(label)) {
  std::stable_sort(
      frames_.begin(), frames_.end(),
      [](const DetectionFrame& a, const DetectionFrame& b) { return a.timestamp < b.timestamp; });
}

const DetectionFrame* FileDetector::find(double timestamp) const {
  const auto it =
      std::lower_bound(frames_.begin(), frames_.end(), timestamp,
                       [](const DetectionFrame& f, double t) { return f.timestamp < t; });
  const DetectionFrame* best = nullptr;
  double best_dt = kMatchTolerance;
  for (auto c : {it, it == frames_.begin() ? it : it - 1}) {
    if (c == frames_.end()) continue;
    const double dt = std::abs(c->timestamp - timestamp);
    if (dt <= best_dt) {
      best = &*c;
      best_dt = dt;
    }
  }
  return best;
}

std::vector<std::string> FileDetector::class_names() const {
  if (!class_names_.empty()) return class_names_;
  std::vector<std::string> names;
  for (const DetectionFrame& f : frames_)
    for (const Detection& d : f.detections)
      if (std::find(names.begin(), names.end(), d.class_name) == names.end())
        names.push_back(d.class_name);
  return names;
}

std::vector<Detection> FileDetector::detect(const cv::Mat&, double timestamp, long) {
  const DetectionFrame* f = find(timestamp);
  return f ? f->detections : std::vector<Detection>{};
}

}  // namespace depot::slam
