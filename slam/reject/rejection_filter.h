#pragma once
// Dynamic feature rejection (PAPER.md), the KeypointFilter between ORB
// extraction and matching. Modes of the paper's ablation:
//   orb      nothing rejected (plain ORB-SLAM2)
//   orb+yolo every point inside a dynamic box
//   orb+lk   points whose LK flow deviates from the mean flow (all points)
//   full     Z rejected, Q kept only if its flow agrees with P's mean flow
// and our mode beyond boxes:
//   masked   boxes of dynamic and potentially dynamic classes are tracked
//            across frames (box_tracker.h: a missed detection is bridged for
//            a few frames) and each is segmented from depth (object_mask.h;
//            person boxes optionally with a person segmenter). A keypoint
//            whose centre is on a dynamic object's mask, or whose FAST
//            circle (radius scaled by mask_reach) touches it, goes to Z; on
//            a potentially dynamic one's, to Q; every other keypoint (the
//            background seen in the box, pixels without depth) to P. A box
//            whose object has no depth at all falls back to the paper's rule
//            (Z or Q whole). Q then as in full. A dynamic object seen still
//            (a seated person: few of its keypoints fail the flow test) has
//            its keypoints decided one by one like Q's; a moving one loses
//            them all (still_object_max_moving). With motion.enabled (and
//            the camera-motion flow test), keypoints failing that test are
//            grouped into objects no detector named (motion_objects.h):
//            each is segmented from depth, its keypoints rejected, and it
//            joins the next frame's boxes as a dynamic object.
#include <memory>
#include <string>
#include <vector>

#include "slam/detect/detection.h"
#include "slam/detect/detection_thread.h"
#include "slam/detect/person_segmenter.h"
#include "slam/reject/apriori_classes.h"
#include "slam/reject/box_tracker.h"
#include "slam/reject/ego_motion_flow.h"
#include "slam/reject/flow_test.h"
#include "slam/reject/motion_objects.h"
#include "slam/reject/object_mask.h"
#include "slam/reject/optical_flow.h"
#include "slam/reject/point_sets.h"
#include "slam/track/keypoint_filter.h"

namespace depot::slam {

enum class RejectionMode { kOrb, kOrbYolo, kOrbLk, kFull, kMasked };
// orb | orb+yolo | orb+lk | full | masked
RejectionMode parse_rejection_mode(const std::string& name);
const char* rejection_mode_name(RejectionMode mode);
bool mode_uses_detector(RejectionMode mode);
bool mode_uses_flow(RejectionMode mode);

struct RejectionParams {
  FlowParams flow;
  FlowTestParams test;
  int max_reference_points = 100;  // P points sampled for the mean flow
  // Our extension, off by default (0 = the paper exactly): in `full`, boxed
  // points that are not at their object's depth go to P, the object's
  // background being this far (m) behind it (split_boxes_by_depth).
  float background_depth_margin = 0.0f;
  // Our extension, off by default: test flow against the camera's own
  // motion fitted to P (ego_motion_flow.h) instead of P's mean flow, for
  // points with depth (others keep the paper's test).
  bool ego_motion_flow = false;
  EgoMotionParams ego;
  // Our extension, off by default: test P's points too, so moving points the
  // detector missed (or that a jittered box left out) are rejected as well.
  bool test_static_points = false;
  // masked mode:
  ObjectMaskParams mask;
  BoxTrackerParams tracking;
  float scale_factor = 1.2f;  // the ORB pyramid's, for the FAST circle at a keypoint's level
  // A keypoint goes with an object when its centre pixel is on the object's
  // mask, or (reach > 0) its FAST circle, radius scaled by `mask_reach`,
  // touches it (1 = the boundary rule of eval/motion_truth.h). 0.5 (half
  // the circle's radius) measured best on the walking scenarios: 0 leaves
  // moving points at the mask's edge (recall 0.86-0.92), 1 takes background
  // a few pixels off the true outline (precision 0.80-0.93).
  float mask_reach = 0.5f;
  // Person boxes with a segmenter (set_segmenter): its mask alone, or its
  // mask and the depth mask together (a pixel on either is on the person).
  enum class PersonMask { kDepth, kSegmentation, kBoth };
  PersonMask person_mask = PersonMask::kDepth;
  // masked: a dynamic object (a-priori class) whose tracked keypoints fail
  // the flow test in less than this share, at a still camera's threshold
  // (test.z_floor, or the camera-motion test's), is still this frame: each of its
  // keypoints is kept when its own flow agrees with the static scene, as a
  // Q point. Otherwise (or with fewer than still_object_min_points tracked,
  // or no previous frame) all of them go to Z. A seated person's torso then
  // keeps constraining the pose while its moving hands are rejected; a
  // walking person fails the test in ~90 % of its points. 0 = the a-priori
  // rule alone (every keypoint on a dynamic object goes to Z).
  float still_object_max_moving = 0.3f;
  // masked: a tracked box is moved from frame to frame by the median
  // optical flow of the keypoints on its object (at least 4 followed), not
  // by the velocity of its past detections: a carried box then stays on
  // its object while the camera turns (walking_rpy).
  bool carry_by_flow = true;
  int still_object_min_points = 5;
  // masked, with ego_motion_flow: movers found without a detection.
  MotionObjectParams motion;
};
// depth | segmentation | both; Error("<where>: ...") otherwise.
RejectionParams::PersonMask parse_person_mask(const std::string& name,
                                              const std::string& where = "--person-mask");

// Per-frame statistics.
struct RejectionStats {
  long frame = 0;
  int total = 0, z = 0, q = 0, q_to_p = 0, p = 0, kept = 0;
  int p_rejected = 0;       // P points failing the flow test (test_static_points)
  bool ego_motion = false;  // the flow test used a fitted camera motion
  int detections = 0;
  cv::Point2f mean_flow{0, 0};
  float z_threshold = 0;
  double wait_ms = 0;    // how long tracking waited for the detector
  double detect_ms = 0;  // the detector's own time (hidden by the thread when it runs ahead)
  double flow_ms = 0;
  double filter_ms = 0;     // the whole rejection stage after detection
  int carried = 0;          // masked: boxes carried by the box tracker (missed detections)
  int masks = 0;            // masked: objects segmented from depth
  double mask_ms = 0;       // masked: box tracking and depth segmentation
  double segment_ms = 0;    // masked: the person segmenter (in the detection thread)
  int still_objects = 0;    // masked: dynamic objects seen still (keypoints decided by flow)
  int motion_objects = 0;   // masked: objects found by their motion alone this frame
  int motion_rejected = 0;  // masked: keypoints rejected on them (not on a detector's object)
};

class RejectionFilter : public KeypointFilter {
 public:
  // `detector` (not owned) is required by orb+yolo and full.
  RejectionFilter(RejectionMode mode, AprioriClasses classes, Detector* detector,
                  const RejectionParams& params = {});

  void begin_frame(const FrameImages& images) override;
  void look_ahead(const FrameImages& next) override;  // starts the detector on `next`
  void filter(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
              std::vector<uint8_t>& keep) override;

  // masked mode: person masks from this segmenter (not owned; null = none),
  // run in the detection thread after the detector. Call before the first
  // frame.
  void set_segmenter(PersonSegmenter* segmenter);

  RejectionMode mode() const { return mode_; }
  const AprioriClasses& classes() const { return classes_; }
  const RejectionStats& last_stats() const { return stats_; }
  const std::vector<Detection>& last_detections() const { return detections_; }
  // The last frame's keypoints (all, before rejection) and decisions.
  const std::vector<cv::KeyPoint>& last_keypoints() const { return keypoints_; }
  const std::vector<uint8_t>& last_keep() const { return keep_; }
  // The set of each keypoint (full and masked; Z = rejected by orb+yolo).
  const std::vector<PointSet>& last_sets() const { return sets_; }
  // masked: the frame's tracked boxes and their objects' masks.
  const std::vector<TrackedBox>& last_objects() const { return objects_; }
  const std::vector<ObjectMask>& last_masks() const { return masks_; }

  // The pixels the last frame's rejection took for moving (CV_8U of `image`
  // size, 255 = moving), to leave out of a dense map: in orb+yolo and full
  // every dynamic box, and a potentially dynamic box where the flow test
  // rejected most of its keypoints (at least one); in masked the objects'
  // masks by the same rule (a box whose object had no depth, whole). orb and
  // orb+lk decide per keypoint, not per pixel: depot::Error.
  cv::Mat moving_mask(cv::Size image) const;

 private:
  void filter_full(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                   std::vector<uint8_t>& keep);
  std::vector<PointSet> masked_sets(const FrameImages& images,
                                    const std::vector<cv::KeyPoint>& keypoints);
  // A tracked object's motion class: a motion-found one is dynamic.
  MotionClass object_class(const TrackedBox& object) const;
  // masked with motion.enabled: groups the keypoints that failed the
  // camera-motion test (`moving`, -1 = not tested) into objects, rejects the
  // keypoints on them and keeps them for the next frame. Returns how many
  // of those were P points.
  int reject_motion_objects(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                            const std::vector<float>& depth, const std::vector<int8_t>& moving,
                            std::vector<uint8_t>& keep);
  // Z rejected, Q (and P with test_static_points) decided by the flow test.
  void decide_sets(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                   const std::vector<float>& depth, std::vector<uint8_t>& keep);

  RejectionMode mode_;
  AprioriClasses classes_;
  Detector* detector_;
  RejectionParams params_;
  BoxTracker box_tracker_;
  cv::Mat person_mask_;  // this frame's, from the detection thread
  std::vector<TrackedBox> objects_;
  std::vector<ObjectMask> masks_;
  std::unique_ptr<DetectionThread> thread_;
  SparseFlow flow_;
  RejectionStats stats_;
  std::vector<Detection> detections_;
  std::vector<cv::KeyPoint> keypoints_;
  std::vector<uint8_t> keep_;
  std::vector<PointSet> sets_;
  // masked, with the still-object test: the dynamic object (index into
  // objects_) each keypoint lies on, -1 for none; empty when not tested.
  std::vector<int> dynamic_object_;
  // masked: keypoints on an object a detector found (not motion-found).
  std::vector<uint8_t> on_detected_object_;
  // masked, carry_by_flow: moves each track's box by the median flow of
  // the keypoints its object held in the last frame (object_points_).
  void move_tracks_by_flow();
  // masked, carry_by_flow: the keypoints (positions) on each track's object
  // this frame, by track id, for the next frame's move_tracks_by_flow.
  std::vector<std::pair<int, std::vector<cv::Point2f>>> object_points_;
  // masked: the objects found by motion in the last frame, handed to the
  // box tracker with the next frame's detections.
  std::vector<Detection> motion_detections_;
};

}  // namespace depot::slam
