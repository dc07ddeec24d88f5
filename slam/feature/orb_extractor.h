#pragma once
// ORB feature extraction the way ORB-SLAM2 does it: a scale pyramid, FAST on
// ~30 px cells with a fallback threshold, a quadtree that spreads the keypoints
// over each level, intensity-centroid orientation and steered BRIEF (rBRIEF)
// descriptors on the Gaussian-smoothed level image.
#include <vector>

#include <opencv2/core.hpp>

namespace depot::slam {

struct OrbParams {
  int n_features = 1000;      // total over all levels (an upper bound)
  float scale_factor = 1.2f;  // between consecutive pyramid levels, in (1, 2]
  int n_levels = 8;           // 1..16
  int ini_fast = 20;          // FAST threshold tried first in every cell
  int min_fast = 7;           // FAST threshold for cells where ini_fast finds nothing
};

// Not thread-safe: extract() reuses per-instance buffers (one extractor per thread,
// as in ORB-SLAM2). Parameters are fixed at construction.
class OrbExtractor {
 public:
  static constexpr int kPatchSize = 31;      // keypoint diameter at level 0
  static constexpr int kHalfPatchSize = 15;  // radius of the orientation patch
  static constexpr int kEdgeThreshold = 19;  // keypoints keep this far from level borders
  static constexpr int kCellSize = 30;       // FAST cell edge, level pixels

  // Throws depot::Error when a parameter is out of range.
  explicit OrbExtractor(const OrbParams& params);

  // gray: non-empty CV_8UC1. mask: empty, or CV_8UC1 of gray's size where 0 marks
  // pixels whose keypoints are dropped (before the spreading, so the budget goes to
  // the allowed area). Outputs at most n_features keypoints in level-0 pixel
  // coordinates, level by level (octave = level, size = kPatchSize * scale,
  // angle in degrees [0, 360), response = FAST score), and one 32-byte descriptor
  // row per keypoint (N x 32 CV_8U; released when N = 0). Throws depot::Error on
  // a bad image or mask.
  void extract(const cv::Mat& gray, const cv::Mat& mask, std::vector<cv::KeyPoint>& kps,
               cv::Mat& descriptors);

  const OrbParams& params() const { return params_; }
  int n_levels() const { return params_.n_levels; }
  float scale_factor() const { return params_.scale_factor; }
  // Per level: scale_factor^level, its inverse, its square (ORB-SLAM2's sigma^2,
  // the variance of a keypoint's position in level-0 pixels) and that inverse.
  const std::vector<float>& scale_factors() const { return scale_; }
  const std::vector<float>& inv_scale_factors() const { return inv_scale_; }
  const std::vector<float>& level_sigma2() const { return sigma2_; }
  const std::vector<float>& inv_level_sigma2() const { return inv_sigma2_; }
  // Keypoint budget per level (a geometric series, sums to n_features).
  const std::vector<int>& features_per_level() const { return per_level_; }
  // Level images of the last extract() (unsmoothed); valid until the next call.
  const std::vector<cv::Mat>& pyramid() const { return levels_; }

 private:
  void build_pyramid(const cv::Mat& gray);
  void detect_level(int level, const cv::Mat& mask);
  void distribute(int level, std::vector<cv::KeyPoint>& out);

  OrbParams params_;
  std::vector<float> scale_, inv_scale_, sigma2_, inv_sigma2_;
  std::vector<int> per_level_;
  std::vector<int> umax_;  // half-width of each row of the circular patch

  // Buffers reused across calls.
  std::vector<cv::Mat> levels_;
  cv::Mat blurred_;
  std::vector<cv::KeyPoint> candidates_, cell_kps_;
  std::vector<int> cell_count_, index_;
  std::vector<std::vector<cv::KeyPoint>> level_kps_;
};

}  // namespace depot::slam
