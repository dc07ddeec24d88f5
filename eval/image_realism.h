#pragma once
// Image statistics that tell a simulated camera from a real one, measured
// the same way on both (`depot eval realism`): sharpness, noise by
// brightness, ORB keypoints, depth holes by depth and at depth edges, and
// image motion between frames. Plain functions of images; reading the
// folders is the caller's (slam/io/tum_sequence.h).
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::eval {

// Brightness bins of the noise measure (grey levels [0, 256) in 8 bins) and
// depth bins of the hole measure (metres; the last is open).
constexpr int kNoiseBins = 8;
inline const std::vector<double> kHoleDepthEdges = {0.0, 1.0, 2.0, 3.0, 4.0};

// "1-2 m", "4+ m": the name of a depth bin.
std::string depth_bin_name(size_t bin);

// What one frame adds to the statistics (sums, so frames combine).
struct FrameRealism {
  double sharpness = 0;  // variance of the grey image's Laplacian
  // Noise: sum and count of |I * N| (Immerkaer's operator) over smooth
  // pixels, per brightness bin of the 3x3 mean.
  std::vector<double> noise_sum = std::vector<double>(kNoiseBins, 0.0);
  std::vector<double> noise_count = std::vector<double>(kNoiseBins, 0.0);
  int keypoints = 0;           // ORB (OpenCV, FAST threshold 20, 8 levels): texture there
  double response_median = 0;  // median FAST response of those keypoints
  bool has_depth = false;
  double pixels = 0, holes = 0;                         // depth: all pixels, 0 = no data
  double edge_pixels = 0, edge_holes = 0;               // within 2 px of a depth edge
  std::vector<double> holes_by_depth, pixels_by_depth;  // per kHoleDepthEdges bin
  double motion_px = -1;  // median feature motion from the previous frame; -1 = none
};

// Statistics of one frame; `previous_grey` (CV_8U, may be empty) gives the
// image motion. `depth` is metres (CV_32F, 0 = none) or empty.
FrameRealism measure_frame(const cv::Mat& bgr, const cv::Mat& depth, const cv::Mat& previous_grey);

// A whole recording's figures.
struct Realism {
  std::string name;
  int frames = 0;
  double sharpness_p10 = 0, sharpness_median = 0, sharpness_p90 = 0;
  std::vector<double> noise_sigma;  // grey levels per brightness bin; NaN = too few pixels
  double keypoints_median = 0, response_median = 0;
  double hole_share = NAN, edge_hole_share = NAN;  // NaN = no depth
  std::vector<double> hole_share_by_depth;         // per bin; NaN = no pixels there
  double motion_median = NAN;                      // px a frame; NaN = a single frame
};

Realism summarise_realism(const std::string& name, const std::vector<FrameRealism>& frames);

// A readable side-by-side table (text) and a self-contained HTML page with
// the table and plots (noise by brightness, holes by depth).
std::string format_realism_table(const Realism& simulated, const Realism& reference);
std::string realism_page(const Realism& simulated, const Realism& reference);

}  // namespace depot::eval
