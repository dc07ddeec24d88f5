#include "tools/perception/segmenter_eval.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/number_text.h"
#include "common/percentile.h"
#include "common/png_codec.h"
#include "common/progress.h"
#include "common/tum_io.h"
#include "dataset/objects.h"
#include "eval/instance_classes.h"
#include "eval/motion_truth.h"

namespace fs = std::filesystem;

namespace depot::perception {
namespace {

constexpr const char* kPerson = "person";

// The mask of one image, timed into `frame`.
cv::Mat segment(slam::PersonSegmenter& segmenter, const cv::Mat& bgr, SegmenterFrame& frame) {
  const auto start = std::chrono::steady_clock::now();
  cv::Mat mask = segmenter.mask(bgr);
  frame.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return mask;
}

}  // namespace

eval::MaskCounts SegmenterEval::total() const {
  eval::MaskCounts sum;
  for (const SegmenterFrame& f : frames) sum.add(f.counts);
  return sum;
}

double SegmenterEval::mean_iou() const {
  double sum = 0.0;
  int n = 0;
  for (const SegmenterFrame& f : frames) {
    if (f.counts.true_positive + f.counts.false_negative == 0) continue;
    sum += f.counts.iou();
    ++n;
  }
  return n > 0 ? sum / n : NAN;
}

double SegmenterEval::median_ms() const {
  std::vector<double> ms;
  for (const SegmenterFrame& f : frames) ms.push_back(f.ms);
  return percentile(ms, 0.5);
}

nlohmann::json SegmenterEval::json() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const SegmenterFrame& f : frames) {
    nlohmann::json row = {{"frame", f.name}, {"ms", f.ms}};
    if (boxes)
      row.update({{"mask_pixels", f.coverage.mask_pixels},
                  {"box_pixels", f.coverage.box_pixels},
                  {"mask_inside_boxes", f.coverage.inside()},
                  {"boxes_covered", f.coverage.covered()}});
    else
      row.update({{"true_positive", f.counts.true_positive},
                  {"false_positive", f.counts.false_positive},
                  {"false_negative", f.counts.false_negative},
                  {"iou", f.counts.iou()},
                  {"precision", f.counts.precision()},
                  {"recall", f.counts.recall()}});
    rows.push_back(row);
  }
  nlohmann::json out = {{"segmenter", segmenter}, {"frames", rows}, {"median_ms", median_ms()}};
  if (!boxes) {
    const eval::MaskCounts t = total();
    out.update(
        {{"mean_iou", mean_iou()},
         {"pooled", {{"iou", t.iou()}, {"precision", t.precision()}, {"recall", t.recall()}}}});
  }
  return out;
}

std::string SegmenterEval::text() const {
  std::string out;
  if (boxes) {
    out += "  image                          mask inside person boxes  boxes covered\n";
    for (const SegmenterFrame& f : frames)
      out += fmt::format("  {:<30} {:>24}  {:>13}\n", f.name, fixed_number(f.coverage.inside(), 3),
                         fixed_number(f.coverage.covered(), 3));
  } else {
    const eval::MaskCounts t = total();
    std::vector<double> ious;
    for (const SegmenterFrame& f : frames)
      if (f.counts.true_positive + f.counts.false_negative > 0) ious.push_back(f.counts.iou());
    // No frame with people has no IoU to take a percentile of ("-", not 0).
    auto of_ious = [&ious](double p) {
      return ious.empty() ? std::numeric_limits<double>::quiet_NaN() : percentile(ious, p);
    };
    out += fmt::format(
        "  person mask IoU: mean {} over {} frames with people (median {}, p10 {}, p90 {})\n  "
        "pooled pixels: IoU {}, precision {}, recall {}\n",
        fixed_number(mean_iou(), 3), ious.size(), fixed_number(of_ious(0.5), 3),
        fixed_number(of_ious(0.1), 3), fixed_number(of_ious(0.9), 3), fixed_number(t.iou(), 3),
        fixed_number(t.precision(), 3), fixed_number(t.recall(), 3));
  }
  return out + fmt::format("  {} frames, median {:.1f} ms per frame ({})\n", frames.size(),
                           median_ms(), segmenter);
}

SegmenterEval evaluate_segmenter(slam::PersonSegmenter& segmenter, const std::string& dataset,
                                 size_t every, bool quiet) {
  const eval::MotionTruth truth(dataset);
  const std::set<int> people =
      eval::instances_of(eval::instance_classes(dataset::read_objects(dataset)), kPerson);
  const std::vector<StampedFile> rgb = read_file_list((fs::path(dataset) / "rgb.txt").string());
  SegmenterEval eval{segmenter.name(), false, {}};
  Progress progress("eval segmenter", (rgb.size() + every - 1) / every, !quiet);
  for (size_t i = 0; i < rgb.size(); i += every) {
    throw_if_interrupted(dataset);
    SegmenterFrame frame;
    frame.name = fmt::format("{:.6f}", rgb[i].timestamp);
    const cv::Mat mask =
        segment(segmenter,
                read_image((fs::path(dataset) / rgb[i].path).string(), ImageRead::kColor), frame);
    frame.counts.add(mask, eval::instances_mask(truth.label_image(rgb[i].timestamp), people));
    eval.frames.push_back(frame);
    progress.update(eval.frames.size(), "frame " + std::to_string(i));
  }
  progress.finish();
  return eval;
}

SegmenterEval evaluate_segmenter_on_images(slam::PersonSegmenter& segmenter,
                                           const eval::ImageLabels& labels, bool quiet) {
  SegmenterEval eval{segmenter.name(), true, {}};
  Progress progress("eval segmenter", labels.images.size(), !quiet);
  for (const eval::LabelledImage& image : labels.images) {
    throw_if_interrupted(labels.path);
    std::vector<cv::Rect2f> people;
    for (const eval::TruthObject& b : image.boxes)
      if (b.class_name == kPerson) people.push_back(b.box);
    if (people.empty()) continue;
    SegmenterFrame frame;
    frame.name = fs::path(image.path).filename().string();
    const cv::Mat bgr = read_image(image.path, ImageRead::kColor);
    eval::check_image_size(image, bgr.cols, bgr.rows);
    frame.coverage = eval::box_coverage(segment(segmenter, bgr, frame), people);
    eval.frames.push_back(frame);
    progress.update(eval.frames.size(), frame.name);
  }
  progress.finish();
  return eval;
}

}  // namespace depot::perception
