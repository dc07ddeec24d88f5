#pragma once
// Dynamic feature rejection (PAPER.md), the KeypointFilter between ORB
// extraction and matching. Modes of the paper's ablation:
//   orb      nothing rejected (plain ORB-SLAM2)
//   orb+yolo every point inside a dynamic box
//   orb+lk   points whose LK flow deviates from the mean flow (all points)
//   full     Z rejected, Q kept only if its flow agrees with P's mean flow
#include <memory>
#include <string>
#include <vector>

#include "slam/detect/detection.h"
#include "slam/detect/detection_thread.h"
#include "slam/reject/apriori_classes.h"
#include "slam/reject/ego_motion_flow.h"
#include "slam/reject/flow_test.h"
#include "slam/reject/optical_flow.h"
#include "slam/reject/point_sets.h"
#include "slam/track/keypoint_filter.h"

namespace depot::slam {

enum class RejectionMode { kOrb, kOrbYolo, kOrbLk, kFull };
RejectionMode parse_rejection_mode(const std::string& name);  // orb | orb+yolo | orb+lk | full
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
};

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
  double detect_ms = 0;  // the detector's own time (hidden by the thread when < extraction)
  double flow_ms = 0;
  double filter_ms = 0;  // the whole rejection stage after detection
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

  RejectionMode mode() const { return mode_; }
  const RejectionStats& last_stats() const { return stats_; }
  const std::vector<Detection>& last_detections() const { return detections_; }
  // The last frame's keypoints (all, before rejection) and decisions.
  const std::vector<cv::KeyPoint>& last_keypoints() const { return keypoints_; }
  const std::vector<uint8_t>& last_keep() const { return keep_; }
  // The set of each keypoint (full mode; P for the other modes).
  const std::vector<PointSet>& last_sets() const { return sets_; }

 private:
  void filter_full(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                   std::vector<uint8_t>& keep);

  RejectionMode mode_;
  AprioriClasses classes_;
  Detector* detector_;
  RejectionParams params_;
  std::unique_ptr<DetectionThread> thread_;
  SparseFlow flow_;
  RejectionStats stats_;
  std::vector<Detection> detections_;
  std::vector<cv::KeyPoint> keypoints_;
  std::vector<uint8_t> keep_;
  std::vector<PointSet> sets_;
};

}  // namespace depot::slam
