#include "slam/io/tum_sequence.h"

#include <filesystem>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/tum_association.h"

namespace fs = std::filesystem;

namespace depot::slam {

TumSequence::TumSequence(const std::string& folder, double depth_factor)
    : folder_(folder), depth_factor_(depth_factor) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) fail(folder, "dataset folder not found");
  const fs::path root(folder);
  if (fs::is_regular_file(root / "associations.txt")) {
    frames_ = read_associations((root / "associations.txt").string());
    return;
  }
  if (!fs::is_regular_file(root / "rgb.txt") || !fs::is_regular_file(root / "depth.txt"))
    fail(folder, "not a TUM RGB-D folder (needs associations.txt, or rgb.txt and depth.txt)");
  auto rgb = read_file_list((root / "rgb.txt").string());
  auto depth = read_file_list((root / "depth.txt").string());
  std::vector<double> rgb_t, depth_t;
  for (const auto& r : rgb) rgb_t.push_back(r.timestamp);
  for (const auto& d : depth) depth_t.push_back(d.timestamp);
  for (const auto& m : associate(rgb_t, depth_t))
    frames_.push_back({rgb[m.reference_index].timestamp, rgb[m.reference_index].path,
                       depth[m.estimate_index].timestamp, depth[m.estimate_index].path});
  if (frames_.empty())
    fail((root / "rgb.txt").string(),
         "no rgb timestamp has a depth timestamp within 0.02 s in depth.txt");
}

std::string TumSequence::calibration_path() const {
  fs::path p = fs::path(folder_) / "calibration.yaml";
  return fs::is_regular_file(p) ? p.string() : "";
}

void TumSequence::load(size_t i, cv::Mat& bgr, cv::Mat& depth_metres) const {
  const Association& a = frames_.at(i);
  const fs::path rgb_path = fs::path(folder_) / a.rgb_path;
  const fs::path depth_path = fs::path(folder_) / a.depth_path;
  if (!fs::is_regular_file(depth_path)) fail(depth_path.string(), "depth image missing");
  bgr = read_image(rgb_path.string(), ImageRead::kColor);
  cv::Mat raw = read_image(depth_path.string(), ImageRead::kUnchanged);
  if (raw.type() != CV_16UC1)
    fail(depth_path.string(), "depth must be a 16-bit single-channel PNG");
  if (raw.size() != bgr.size()) fail(depth_path.string(), "depth and colour sizes differ");
  raw.convertTo(depth_metres, CV_32F, 1.0 / depth_factor_);
}

}  // namespace depot::slam
