#pragma once
// Missed-detection recovery: boxes tracked from frame to frame, so that an
// object the detector misses for a few frames is still rejected. Each track
// keeps its box and the box's velocity (image px per frame, smoothed over
// detections: the object's and the camera's motion together), or is moved
// by its object's measured motion where the caller has it; a detection
// updates the track it overlaps most (greedy by IoU, same class), a track
// without one is carried on by its velocity for at most `max_missed` frames
// and then dropped. The caller may re-centre a carried box on what it finds
// there (correct(): e.g. the object's depth mask).
//
// Owned by one thread (the tracking thread's rejection filter).
#include <vector>

#include "slam/detect/detection.h"

namespace depot::slam {

struct BoxTrackerParams {
  int max_missed = 5;  // frames a track lives without a detection
  // ... and while the caller finds its object where the track carries it
  // (correct() on every carried frame), up to this many (a person the
  // detector misses for longer, still found at its depth).
  int max_missed_seen = 5;
  float seen_min_iou = 0.5f;        // correct()'s box overlaps the carried one this much
  int min_hits = 2;                 // detections before a missed track's box is carried
  float min_iou = 0.2f;             // a detection continues a track from this overlap
  float velocity_smoothing = 0.5f;  // weight of the newest box motion in the velocity
};

struct TrackedBox {
  Detection detection;  // the detection, or the track's prediction when missed > 0
  int track_id = 0;
  int missed = 0;   // frames since the track's last detection (0 = detected now)
  float depth = 0;  // the object's depth last recorded for the track (0 = none)
};

class BoxTracker {
 public:
  explicit BoxTracker(const BoxTrackerParams& params = {}) : params_(params) {}

  // Advances every track one frame and matches this frame's detections to
  // them. Returns each detection (missed = 0) followed by the predicted box
  // of each track the detector missed (missed = 1..max_missed).
  std::vector<TrackedBox> update(const std::vector<Detection>& detections);
  // Replaces a carried track's box (the one update() just returned, same
  // track_id) by a measured one; its velocity is kept, and the track counts
  // as seen this frame (max_missed_seen) when the two overlap by
  // seen_min_iou.
  void correct(int track_id, const cv::Rect2f& box);
  // Records the object's depth (m) for the track, returned with it from the
  // next update() (a carried box's object is looked for at that depth).
  void set_depth(int track_id, float depth);
  // The object's image motion from the last frame to the one the next
  // update() gets, measured (e.g. the median optical flow of its
  // keypoints): that update() moves the track's box by it instead of by
  // the velocity of past detections, which a turning camera makes stale.
  void set_motion(int track_id, const cv::Point2f& shift);

  size_t tracks() const { return tracks_.size(); }

 private:
  struct Track {
    int id;
    Detection detection;         // the current box (detected or carried)
    cv::Rect2f last_detected;    // the box of the last detection
    cv::Point2f velocity{0, 0};  // of the box centre, px per frame
    cv::Size2f size_velocity{0, 0};
    int missed = 0;
    int detected = 0;  // detections so far
    float depth = 0;
    bool seen = false;      // correct() was called on its last carried frame
    bool measured = false;  // set_motion() gave the next update's shift
    cv::Point2f shift{0, 0};
  };
  BoxTrackerParams params_;
  std::vector<Track> tracks_;
  int next_id_ = 1;
};

}  // namespace depot::slam
