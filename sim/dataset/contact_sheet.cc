#include "sim/dataset/contact_sheet.h"

#include <fmt/format.h>

#include <cctype>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/staged_file.h"
#include "common/tum_io.h"
#include "dataset/label_images.h"

namespace fs = std::filesystem;

namespace depot::sim {
namespace {

cv::Scalar label_colour(uint16_t id) {
  // A fixed, well-spread colour per id.
  uint32_t h = id * 2654435761u;
  return cv::Scalar(60 + (h & 0x7f) + 60 * ((h >> 7) & 1),
                    60 + ((h >> 8) & 0x7f) + 60 * ((h >> 15) & 1),
                    60 + ((h >> 16) & 0x7f) + 60 * ((h >> 23) & 1));
}

cv::Mat colour_labels(const cv::Mat& ids) {
  cv::Mat out(ids.size(), CV_8UC3);
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      uint16_t id = ids.at<uint16_t>(y, x);
      cv::Scalar c = id == 0 ? cv::Scalar(0, 0, 0) : label_colour(id);
      out.at<cv::Vec3b>(y, x) =
          cv::Vec3b(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
    }
  return out;
}

cv::Mat colour_depth(const cv::Mat& depth16) {
  cv::Mat metres;
  depth16.convertTo(metres, CV_32F, 1.0 / 5000.0);
  cv::Mat scaled;
  metres.convertTo(scaled, CV_8U, 255.0 / 5.0);
  cv::Mat out;
  cv::applyColorMap(scaled, out, cv::COLORMAP_TURBO);
  out.setTo(cv::Scalar(0, 0, 0), depth16 == 0);
  return out;
}

}  // namespace

void write_contact_sheet(const std::string& dataset, const std::string& output,
                         const ContactSheetOptions& options) {
  // The format follows the output's extension; checked before any work.
  std::string ext = fs::path(output).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
    fail(output, "unsupported image format '" + ext + "' (use .png, .jpg or .jpeg)");
  check_output_file(output);
  const fs::path root(dataset);
  if (!fs::is_directory(root)) fail(dataset, "not a dataset folder");
  if (!fs::is_regular_file(root / "associations.txt")) fail(dataset, "associations.txt missing");
  auto assoc = read_associations((root / "associations.txt").string());
  const bool has_labels = dataset::has_label_list(dataset);
  std::vector<StampedFile> labels;
  if (has_labels) labels = dataset::read_label_list(dataset);

  const int rows = std::max(1, std::min<int>(options.rows, static_cast<int>(assoc.size())));
  std::vector<cv::Mat> lines;
  for (int r = 0; r < rows; ++r) {
    const size_t i = rows == 1 ? 0 : r * (assoc.size() - 1) / (rows - 1);
    cv::Mat rgb = read_image((root / assoc[i].rgb_path).string(), ImageRead::kColor);
    cv::Mat depth = read_image((root / assoc[i].depth_path).string(), ImageRead::kUnchanged);
    if (depth.type() != CV_16U) fail((root / assoc[i].depth_path).string(), "depth is not 16-bit");
    std::vector<cv::Mat> tiles{rgb, colour_depth(depth)};
    if (has_labels && i < labels.size()) {
      tiles.push_back(colour_labels(dataset::read_label_image(dataset, labels[i].path)));
    }
    for (auto& t : tiles) {
      double s = static_cast<double>(options.thumb_width) / t.cols;
      cv::resize(t, t, cv::Size(), s, s, cv::INTER_AREA);
    }
    const std::string caption = fmt::format("t={:.3f}  frame {}", assoc[i].rgb_timestamp, i);
    cv::putText(tiles[0], caption, cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(255, 255, 255), 2);
    cv::putText(tiles[0], caption, cv::Point(6, 18), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1);
    cv::Mat line;
    cv::hconcat(tiles, line);
    lines.push_back(line);
  }
  cv::Mat sheet;
  cv::vconcat(lines, sheet);
  cv::Mat header(28, sheet.cols, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::putText(header, dataset + "   RGB | depth (0-5 m) | instance labels", cv::Point(8, 19),
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1);
  cv::vconcat(header, sheet, sheet);
  std::vector<unsigned char> bytes;
  if (!cv::imencode(ext, sheet, bytes)) fail(output, "cannot encode the image as " + ext);
  StagedFile file(output);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace depot::sim
