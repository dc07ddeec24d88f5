#include "slam/reject/box_tracker.h"

#include <algorithm>
#include <tuple>

#include "slam/detect/nms.h"

namespace depot::slam {

namespace {

cv::Point2f centre(const cv::Rect2f& r) {
  return {r.x + r.width / 2, r.y + r.height / 2};
}

}  // namespace

std::vector<TrackedBox> BoxTracker::update(const std::vector<Detection>& detections) {
  // Predict: every track moves by its measured motion, else its velocity.
  for (Track& t : tracks_) {
    cv::Rect2f& b = t.detection.box;
    const cv::Point2f c = centre(b) + (t.measured ? t.shift : t.velocity);
    t.measured = false;
    const float w = std::max(1.0f, b.width + t.size_velocity.width);
    const float h = std::max(1.0f, b.height + t.size_velocity.height);
    b = cv::Rect2f(c.x - w / 2, c.y - h / 2, w, h);
  }
  // Match greedily by IoU (highest first), same class only.
  std::vector<std::tuple<float, size_t, size_t>> pairs;
  for (size_t d = 0; d < detections.size(); ++d)
    for (size_t t = 0; t < tracks_.size(); ++t) {
      if (detections[d].class_name != tracks_[t].detection.class_name) continue;
      const float overlap = iou(detections[d].box, tracks_[t].detection.box);
      if (overlap >= params_.min_iou) pairs.emplace_back(overlap, d, t);
    }
  std::sort(pairs.begin(), pairs.end(),
            [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<int> track_of(detections.size(), -1);
  std::vector<uint8_t> track_used(tracks_.size(), 0);
  for (const auto& [iou, d, t] : pairs) {
    if (track_of[d] >= 0 || track_used[t]) continue;
    track_of[d] = static_cast<int>(t);
    track_used[t] = 1;
  }
  std::vector<TrackedBox> out;
  const size_t old_tracks = tracks_.size();
  const float a = params_.velocity_smoothing;
  for (size_t d = 0; d < detections.size(); ++d) {
    if (track_of[d] < 0) {
      Track t{next_id_++, detections[d], detections[d].box};
      t.detected = 1;
      tracks_.push_back(t);
      out.push_back({detections[d], t.id, 0});
      continue;
    }
    Track& t = tracks_[track_of[d]];
    // The motion per frame since the last detection.
    const float frames = static_cast<float>(t.missed + 1);
    const cv::Rect2f& now = detections[d].box;
    const cv::Point2f motion = (centre(now) - centre(t.last_detected)) / frames;
    const cv::Size2f growth((now.width - t.last_detected.width) / frames,
                            (now.height - t.last_detected.height) / frames);
    const float w = t.detected == 1 ? 1.0f : a;  // the first motion seen is taken whole
    t.velocity = w * motion + (1 - w) * t.velocity;
    t.size_velocity = cv::Size2f(w * growth.width + (1 - w) * t.size_velocity.width,
                                 w * growth.height + (1 - w) * t.size_velocity.height);
    t.detection = detections[d];
    t.last_detected = now;
    t.missed = 0;
    t.detected++;
    out.push_back({detections[d], t.id, 0, t.depth});
  }
  // Tracks without a detection this frame: carried, or dropped after max_missed.
  std::vector<Track> kept;
  for (size_t t = 0; t < tracks_.size(); ++t) {
    Track& track = tracks_[t];
    if (t < old_tracks && !track_used[t]) {
      const int limit =
          track.seen ? std::max(params_.max_missed, params_.max_missed_seen) : params_.max_missed;
      track.seen = false;
      if (++track.missed > limit) continue;
      // A box seen once may be a false detection: kept to match, not carried.
      if (track.detected >= params_.min_hits)
        out.push_back({track.detection, track.id, track.missed, track.depth});
    }
    kept.push_back(track);
  }
  tracks_ = std::move(kept);
  return out;
}

void BoxTracker::correct(int track_id, const cv::Rect2f& box) {
  for (Track& t : tracks_)
    if (t.id == track_id && t.missed > 0) {
      // Found where it was carried: most of the measured box overlaps the
      // prediction (what is found far off may be something else).
      t.seen = iou(box, t.detection.box) >= params_.seen_min_iou;
      t.detection.box = box;
    }
}

void BoxTracker::set_motion(int track_id, const cv::Point2f& shift) {
  for (Track& t : tracks_)
    if (t.id == track_id) {
      t.measured = true;
      t.shift = shift;
    }
}

void BoxTracker::set_depth(int track_id, float depth) {
  for (Track& t : tracks_)
    if (t.id == track_id) t.depth = depth;
}

}  // namespace depot::slam
