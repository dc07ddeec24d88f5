#include "slam/io/tum_sequence.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/tum_association.h"

namespace fs = std::filesystem;

namespace depot::slam {

namespace {

// "<timestamp>.png" files of root/sub, in time order; none when the folder
// is missing or holds other names.
std::vector<StampedFile> list_stamped_images(const fs::path& root, const std::string& sub) {
  std::vector<StampedFile> out;
  std::error_code ec;
  if (!fs::is_directory(root / sub, ec)) return out;
  for (const auto& e : fs::directory_iterator(root / sub, ec)) {
    if (!e.is_regular_file() || e.path().extension() != ".png") continue;
    const std::string stem = e.path().stem().string();
    char* end = nullptr;
    const double t = std::strtod(stem.c_str(), &end);
    if (stem.empty() || *end != '\0' || !std::isfinite(t)) return {};
    out.push_back({t, sub + "/" + e.path().filename().string()});
  }
  std::sort(out.begin(), out.end(),
            [](const StampedFile& a, const StampedFile& b) { return a.timestamp < b.timestamp; });
  return out;
}

}  // namespace

TumSequence::TumSequence(const std::string& folder, double depth_factor)
    : folder_(folder), depth_factor_(depth_factor) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) fail(folder, "dataset folder not found");
  const fs::path root(folder);
  if (fs::is_regular_file(root / "associations.txt")) {
    frames_ = read_associations((root / "associations.txt").string());
    return;
  }
  std::vector<StampedFile> rgb, depth;
  if (fs::is_regular_file(root / "rgb.txt") && fs::is_regular_file(root / "depth.txt")) {
    rgb = read_file_list((root / "rgb.txt").string());
    depth = read_file_list((root / "depth.txt").string());
  } else {
    // A recording cut down to its image folders (e.g. one frame of a real
    // sequence): the files' names are their timestamps, as TUM names them.
    rgb = list_stamped_images(root, "rgb");
    depth = list_stamped_images(root, "depth");
    if (rgb.empty() || depth.empty())
      fail(folder,
           "not a TUM RGB-D folder (needs associations.txt, rgb.txt and depth.txt, or "
           "rgb/ and depth/ holding images named by their timestamps)");
  }
  std::vector<double> rgb_t, depth_t;
  for (const auto& r : rgb) rgb_t.push_back(r.timestamp);
  for (const auto& d : depth) depth_t.push_back(d.timestamp);
  for (const auto& m : associate(rgb_t, depth_t))
    frames_.push_back({rgb[m.reference_index].timestamp, rgb[m.reference_index].path,
                       depth[m.estimate_index].timestamp, depth[m.estimate_index].path});
  if (frames_.empty())
    fail(fs::is_regular_file(root / "rgb.txt") ? (root / "rgb.txt").string() : folder,
         fs::is_regular_file(root / "rgb.txt")
             ? "no rgb timestamp has a depth timestamp within 0.02 s in depth.txt"
             : "no image of rgb/ has one of depth/ within 0.02 s");
}

std::string TumSequence::colour_location(size_t i) const {
  return (fs::path(folder_) / frames_.at(i).rgb_path).string();
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
