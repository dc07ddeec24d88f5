#pragma once
// Sparse pyramidal Lucas-Kanade flow of keypoints between the previous and
// the current frame (PAPER.md Eq. 1-5), computed only where asked.
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

struct FlowParams {
  int window = 11;  // px: 15 gave the same rejection at twice the cost
  int levels = 3;
  int iterations = 10;
  float max_error = 30.0f;  // LK residual above which a track fails
  // Forward-backward consistency check in px (0 = off). It doubles the cost
  // and the threshold test already rejects wild tracks, so it is off.
  float max_forward_backward = 0.0f;
};

class SparseFlow {
 public:
  explicit SparseFlow(const FlowParams& params = {}) : params_(params) {}
  // Sets the current frame; the previous one is kept for flow.
  void next_frame(const cv::Mat& gray);
  bool has_previous() const { return !previous_.empty(); }
  // Flow (u, v) of each point from the previous frame to the current one;
  // ok[i] = false where the track failed.
  void flow(const std::vector<cv::Point2f>& current_points, std::vector<cv::Point2f>& flow,
            std::vector<uint8_t>& ok) const;
  // Where points of the previous frame are in the current one (forward LK);
  // ok[i] = false where the track failed or its residual exceeds max_error.
  void follow(const std::vector<cv::Point2f>& previous_points, std::vector<cv::Point2f>& current,
              std::vector<uint8_t>& ok) const;
  // Refines where each point was in the previous frame, starting from a
  // guess and searching only `levels` pyramid levels with a small window:
  // a predicted position lets LK avoid being dragged by a nearby moving
  // occluder. `previous` holds the guesses on entry and the result on exit;
  // ok[i] = false where the track failed or its residual exceeds max_error.
  void refine(const std::vector<cv::Point2f>& current_points, std::vector<cv::Point2f>& previous,
              std::vector<uint8_t>& ok, int window, int levels, float max_error) const;

 private:
  FlowParams params_;
  std::vector<cv::Mat> previous_, current_;  // image pyramids
};

}  // namespace depot::slam
