#pragma once
// Movers without a detection: keypoints that fail the camera-motion flow
// test (ego_motion_flow.h) are grouped into objects, so an animal no
// detector names is rejected as a whole. A single failing keypoint is too
// weak a sign (LK slips at depth edges and on repeated texture); several
// failing keypoints close together in the image and in depth, where most of
// the tested keypoints around them fail too, are one moving object. Its box
// is then segmented from depth like a detector's (object_mask.h) and joins
// the detector's boxes from the next frame on (box_tracker.h carries it).
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

// The class name a motion-found object carries among the detector's boxes
// (dynamic; not a detector class).
inline constexpr const char* kMotionClass = "(moving)";

struct MotionObjectParams {
  bool enabled = false;  // masked mode with the camera-motion flow test only
  // Two failing keypoints belong to one object when they are this close in
  // the image (px at 640 px width) and in depth (m, plus a share of depth).
  float link_px = 25.0f;
  float link_depth_m = 0.25f;
  float link_depth_per_m = 0.1f;
  int min_seeds = 6;  // failing keypoints an object needs
  // Of the tested keypoints inside the group's box and within its depth
  // range (link tolerance), at least this share fail: a group on a static
  // surface next to few slips does not pass.
  float min_moving_share = 0.6f;
  // When more than this share of all tested keypoints fail, the camera's
  // motion was not found (a blurred or fast frame): no objects this frame.
  float max_frame_moving_share = 0.25f;
  // The box searched for the object's depth mask: the group's keypoints'
  // bounds grown by this share of their size per side (at least link_px).
  float grow = 0.5f;
  // Reject an object's keypoints in the frame it is first found (else from
  // the next frame on, when it is found again).
  bool reject_on_first_sight = false;
};

// A keypoint the camera-motion test decided, with its depth (m, > 0).
struct TestedKeypoint {
  cv::Point2f pixel;
  float depth = 0;
  bool moving = false;
};

struct MotionObject {
  cv::Rect2f box;   // where to look for it (grown, clipped to the image)
  float depth = 0;  // median depth of its failing keypoints (m)
  int seeds = 0;    // its failing keypoints
  int tested = 0;   // tested keypoints inside its box at its depth
};

// Groups the failing keypoints (single linkage by image distance and depth)
// and returns the groups that pass min_seeds and min_moving_share, largest
// first. `image` is the frame's size (link_px scales with its width).
std::vector<MotionObject> find_motion_objects(const std::vector<TestedKeypoint>& tested,
                                              cv::Size image, const MotionObjectParams& params);

}  // namespace depot::slam
