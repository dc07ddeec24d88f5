#pragma once
// Scale-pyramid constants shared by frames, keyframes and map points.
#include <cmath>
#include <vector>

namespace depot::slam {

struct ScaleLevels {
  int n_levels = 8;
  float scale_factor = 1.2f;
  float log_scale_factor = std::log(1.2f);
  std::vector<float> scale;   // scale_factor^level
  std::vector<float> sigma2;  // scale^2: variance of a keypoint position
  std::vector<float> inv_sigma2;

  static ScaleLevels make(int n_levels, float scale_factor) {
    ScaleLevels s;
    s.n_levels = n_levels;
    s.scale_factor = scale_factor;
    s.log_scale_factor = std::log(scale_factor);
    float f = 1.0f;
    for (int i = 0; i < n_levels; ++i, f *= scale_factor) {
      s.scale.push_back(f);
      s.sigma2.push_back(f * f);
      s.inv_sigma2.push_back(1.0f / (f * f));
    }
    return s;
  }
};

}  // namespace depot::slam
