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

// What a PLY file's header declares, checked against its body.
struct PlyCheck {
  std::string format;          // "ascii", "binary_little_endian" or "binary_big_endian"
  size_t vertices = 0;         // the "vertex" element's count
  bool only_vertices = false;  // no element but "vertex" (a point cloud)
  size_t header_bytes = 0;     // up to and including "end_header\n"
  size_t data_bytes = 0;       // what the elements take after it
};

// Reads a PLY file's header and walks its body: every element's rows are
// there (binary: the bytes its properties and list counts need; ASCII: one
// line of numbers per row with at least the properties' count), so a reader
// that pads what is missing (assimp does) never sees a cut file. Throws
// depot::Error "<path>: <problem>" (or "<path>:<line>: <problem>" in the
// header) for a missing or unknown header line, an unknown type, a file
// shorter than its header declares, or a row that is not numbers.
PlyCheck check_ply_file(const std::string& path);

}  // namespace depot::slam
