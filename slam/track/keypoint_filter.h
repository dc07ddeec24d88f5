#pragma once
// The seam between feature extraction and matching: a filter that decides
// which keypoints may be used for matching, pose estimation and new map
// points (the dynamic-feature rejection plugs in here). Rejected keypoints
// never reach the tracker.
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/camera/pinhole_camera.h"

namespace depot::slam {

struct FrameImages {
  const cv::Mat& bgr;    // CV_8UC3
  const cv::Mat& gray;   // CV_8UC1
  const cv::Mat& depth;  // CV_32F metres, 0 = none
  double timestamp;
  long frame_id;
  const PinholeCamera* camera = nullptr;  // the tracker's intrinsics
};

class KeypointFilter {
 public:
  virtual ~KeypointFilter() = default;
  // Called when a frame arrives, before ORB extraction: lets a filter start
  // work that runs in parallel with extraction (e.g. object detection).
  virtual void begin_frame(const FrameImages& images) { (void)images; }
  // Called with a frame before its turn, possibly while earlier frames are
  // still to be tracked (System::look_ahead): lets a filter start work early,
  // e.g. detect frame k+1 while frame k is tracked. `next.gray` is empty;
  // begin_frame() and filter() follow with the same frame_id when the frame
  // is tracked. The images are the caller's, unchanged until then.
  virtual void look_ahead(const FrameImages& next) { (void)next; }
  // Sets keep[i] = 1 for keypoints to use, 0 for rejected ones (keep has
  // keypoints.size() entries, all 1 on entry).
  virtual void filter(const FrameImages& images, const std::vector<cv::KeyPoint>& keypoints,
                      std::vector<uint8_t>& keep) = 0;
};

}  // namespace depot::slam
