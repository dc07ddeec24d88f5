#pragma once
// Point clouds as PLY (binary little-endian, the format Open3D, CloudCompare,
// MeshLab and assimp read): position, colour and an optional per-point
// count (map points: how many keyframes observe each). Written through a
// staged file: a failure leaves no half file.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace depot::slam {

struct PlyPoint {
  Eigen::Vector3f position;
  cv::Vec3b bgr;
  int count = 0;
};

// `count_name` names the per-point count property ("" = none).
void write_ply(const std::string& path, const std::vector<PlyPoint>& points,
               const std::string& count_name);

}  // namespace depot::slam
