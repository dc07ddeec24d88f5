#include "slam/reject/optical_flow.h"

#include <algorithm>

#include <opencv2/video/tracking.hpp>

namespace depot::slam {

void SparseFlow::next_frame(const cv::Mat& gray) {
  previous_ = std::move(current_);
  current_.clear();
  cv::buildOpticalFlowPyramid(gray, current_, cv::Size(params_.window, params_.window),
                              params_.levels);
}

void SparseFlow::flow(const std::vector<cv::Point2f>& points, std::vector<cv::Point2f>& flow,
                      std::vector<uint8_t>& ok) const {
  flow.assign(points.size(), cv::Point2f(0, 0));
  ok.assign(points.size(), 0);
  if (previous_.empty() || points.empty()) return;
  // Track current keypoints back into the previous frame, then forward again
  // to reject inconsistent tracks; flow = current - previous.
  const cv::TermCriteria term(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, params_.iterations,
                              0.01);
  const cv::Size win(params_.window, params_.window);
  std::vector<cv::Point2f> back;
  std::vector<uint8_t> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(current_, previous_, points, back, status, error, win, params_.levels,
                           term);
  std::vector<cv::Point2f> forth;
  std::vector<uint8_t> status2;
  std::vector<float> error2;
  if (params_.max_forward_backward > 0)
    cv::calcOpticalFlowPyrLK(previous_, current_, back, forth, status2, error2, win, params_.levels,
                             term);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!status[i] || error[i] > params_.max_error) continue;
    if (params_.max_forward_backward > 0) {
      if (!status2[i]) continue;
      const cv::Point2f d = forth[i] - points[i];
      if (d.dot(d) > params_.max_forward_backward * params_.max_forward_backward) continue;
    }
    flow[i] = points[i] - back[i];
    ok[i] = 1;
  }
}

void SparseFlow::follow(const std::vector<cv::Point2f>& previous_points,
                        std::vector<cv::Point2f>& current, std::vector<uint8_t>& ok) const {
  current.clear();
  ok.assign(previous_points.size(), 0);
  if (previous_.empty() || current_.empty() || previous_points.empty()) return;
  const cv::TermCriteria term(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, params_.iterations,
                              0.01);
  std::vector<uint8_t> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(previous_, current_, previous_points, current, status, error,
                           cv::Size(params_.window, params_.window), params_.levels, term);
  for (size_t i = 0; i < previous_points.size(); ++i)
    ok[i] = status[i] && error[i] <= params_.max_error;
}

void SparseFlow::refine(const std::vector<cv::Point2f>& points, std::vector<cv::Point2f>& previous,
                        std::vector<uint8_t>& ok, int window, int levels, float max_error) const {
  ok.assign(points.size(), 0);
  if (previous_.empty() || points.empty()) return;
  const cv::TermCriteria term(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, params_.iterations,
                              0.01);
  std::vector<uint8_t> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(current_, previous_, points, previous, status, error,
                           cv::Size(window, window), std::min(levels, params_.levels), term,
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  for (size_t i = 0; i < points.size(); ++i) ok[i] = status[i] && error[i] <= max_error;
}

}  // namespace depot::slam
