#include "tools/runner/rejection_overlay.h"

#include <fmt/format.h>

#include <filesystem>

#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/png_codec.h"
#include "tools/runner/frame_truth.h"

namespace depot::runner {

cv::Mat draw_rejection_overlay(const cv::Mat& bgr, const slam::RejectionFilter& filter,
                               const eval::MotionTruth::KeypointTruth* truth) {
  const slam::AprioriClasses& classes = filter.classes();
  cv::Mat out = bgr.clone();
  const cv::Scalar red(40, 40, 230), blue(230, 120, 40), green(60, 200, 60), yellow(0, 230, 255),
      magenta(230, 40, 230), cyan(230, 230, 0);
  const auto& objects = filter.last_objects();
  const auto& masks = filter.last_masks();
  for (size_t k = 0; k < objects.size() && k < masks.size(); ++k) {
    const bool dynamic =
        classes.classify(objects[k].detection.class_name) == slam::MotionClass::kDynamic;
    const cv::Scalar colour = dynamic ? red : blue;
    if (masks[k].valid()) {
      cv::Mat tint(masks[k].region.size(), CV_8UC3, colour);
      cv::Mat area = out(masks[k].region);
      cv::Mat blended;
      cv::addWeighted(area, 0.6, tint, 0.4, 0, blended);
      blended.copyTo(area, masks[k].mask);
    }
    cv::rectangle(out, objects[k].detection.box, colour, objects[k].missed ? 1 : 2);
    cv::putText(out,
                objects[k].detection.class_name +
                    (objects[k].missed ? " +" + std::to_string(objects[k].missed) : ""),
                objects[k].detection.box.tl() + cv::Point2f(2, 12), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                colour, 1);
  }
  if (objects.empty())  // modes without object masks: the detections
    for (const auto& d : filter.last_detections())
      cv::rectangle(out, d.box,
                    classes.classify(d.class_name) == slam::MotionClass::kDynamic ? red : blue, 2);
  const auto& kps = filter.last_keypoints();
  const auto& keep = filter.last_keep();
  for (size_t i = 0; i < kps.size(); ++i) {
    cv::Scalar colour = keep[i] ? green : red;
    if (truth) {
      if (truth->boundary[i])
        colour = cyan;
      else if (truth->on_moving[i])
        colour = keep[i] ? yellow : red;
      else
        colour = keep[i] ? green : magenta;
    }
    cv::circle(out, kps[i].pt, 2, colour, cv::FILLED);
  }
  return out;
}

OverlayFolder::OverlayFolder(const std::string& path, size_t every)
    : path_(path), every_(every), folder_(path, overlay_folder_kind(), false) {
  const std::filesystem::path staged(folder_.path());
  std::filesystem::create_directories(staged / "frames");
  index_.open((staged / "index.txt").string());
  index_ << "# frame timestamp picture (depot slam run --overlays; colours: "
            "tools/runner/rejection_overlay.h)\n";
}

void OverlayFolder::on_frame(const FrameRecord& frame) {
  if (frame.index % every_ != 0) return;
  const std::string name = fmt::format("frames/{:06}.png", frame.index);
  write_png((std::filesystem::path(folder_.path()) / name).string(),
            draw_rejection_overlay(frame.bgr, *frame.filter,
                                   frame.truth ? &frame.truth->labels : nullptr),
            PngKind::kColor);
  index_ << fmt::format("{} {:.6f} {}\n", frame.index, frame.timestamp, name);
}

void OverlayFolder::commit() {
  index_.close();
  if (!index_) fail(path_, "cannot write index.txt");
  folder_.commit();
}

}  // namespace depot::runner
