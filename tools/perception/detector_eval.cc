#include "tools/perception/detector_eval.h"

#include <chrono>
#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/percentile.h"
#include "common/png_codec.h"
#include "common/progress.h"
#include "dataset/boxes.h"
#include "dataset/objects.h"
#include "slam/detect/truth_boxes.h"

namespace depot::perception {
namespace {

std::vector<eval::ScoredDetection> scored(const std::vector<slam::Detection>& detections) {
  std::vector<eval::ScoredDetection> out;
  out.reserve(detections.size());
  for (const slam::Detection& d : detections) out.push_back({d.class_name, d.confidence, d.box});
  return out;
}

// The detections of one frame, timed into `eval`.
std::vector<eval::ScoredDetection> detect(slam::Detector& detector, const cv::Mat& bgr,
                                          double timestamp, long index, DetectorEval& eval) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<slam::Detection> found = detector.detect(bgr, timestamp, index);
  eval.detect_ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  return scored(found);
}

}  // namespace

std::vector<eval::TruthObject> truth_objects(const std::vector<slam::TruthBox>& boxes,
                                             const std::map<int, std::string>& assets) {
  std::vector<eval::TruthObject> objects;
  objects.reserve(boxes.size());
  for (const slam::TruthBox& b : boxes) {
    auto it = assets.find(b.id);
    objects.push_back({b.class_name, b.rect(), static_cast<double>(b.visible_pixels),
                       it == assets.end() ? std::string() : it->second});
  }
  return objects;
}

eval::DetectionSide DetectorEval::side(const std::string& name) const {
  return {name, detector, &score, labels, percentile(detect_ms, 0.5)};
}

eval::ClassMapping class_mapping_for(const std::string& type, const std::string& path) {
  if (type == "sim" && path.empty()) return {};
  return eval::ClassMapping::load(path.empty() ? project_file("scenes/detectors/coco_to_depot.yaml")
                                               : path);
}

DetectorEval evaluate_on_dataset(slam::Detector& detector, const std::string& dataset,
                                 const eval::ClassMapping& mapping, size_t every, bool reads_pixels,
                                 bool quiet, const FrameObserver& observe) {
  if (!dataset::has_boxes(dataset))
    fail(dataset,
         "no ground-truth boxes (boxes.txt): not a simulated dataset (score real images "
         "with --images)");
  const slam::DatasetBoxes truth = slam::read_dataset_boxes(dataset);
  const std::map<int, std::string> assets = eval::instance_assets(dataset::read_objects(dataset));
  mapping.check_classes(truth.classes, dataset + "/classes.txt");
  DetectorEval eval{
      eval::DetectionScore(truth.classes, mapping), detector.name(), detector.class_names(), {}};
  const size_t n = truth.timestamps.size();
  const size_t scored_frames = (n + every - 1) / every;
  Progress progress("eval detector", scored_frames, !quiet);
  for (size_t i = 0, done = 0; i < n; i += every) {
    throw_if_interrupted(dataset);
    const cv::Mat bgr =
        reads_pixels ? read_image((std::filesystem::path(dataset) / truth.rgb_files[i]).string(),
                                  ImageRead::kColor)
                     : cv::Mat();
    const std::vector<eval::TruthObject> objects = truth_objects(truth.frames[i], assets);
    const std::vector<eval::ScoredDetection> found =
        detect(detector, bgr, truth.timestamps[i], static_cast<long>(i), eval);
    eval.score.add_frame(objects, found);
    if (observe) observe(i, truth.frames[i], found);
    progress.update(++done, "frame " + std::to_string(i));
  }
  progress.finish();
  return eval;
}

DetectorEval evaluate_on_images(slam::Detector& detector, const eval::ImageLabels& labels,
                                const eval::ClassMapping& mapping, bool quiet) {
  mapping.check_classes(labels.classes, labels.path + " (its 'classes')");
  DetectorEval eval{
      eval::DetectionScore(labels.classes, mapping), detector.name(), detector.class_names(), {}};
  for (const eval::LabelledImage& image : labels.images)
    if (!std::filesystem::is_regular_file(image.path))
      fail(image.where, "image " + image.path + " not found");
  Progress progress("eval detector", labels.images.size(), !quiet);
  for (size_t i = 0; i < labels.images.size(); ++i) {
    throw_if_interrupted(labels.path);
    const eval::LabelledImage& image = labels.images[i];
    const cv::Mat bgr = read_image(image.path, ImageRead::kColor);
    eval::check_image_size(image, bgr.cols, bgr.rows);
    eval.score.add_frame(image.boxes,
                         detect(detector, bgr, static_cast<double>(i), static_cast<long>(i), eval));
    progress.update(i + 1, std::filesystem::path(image.path).filename().string());
  }
  progress.finish();
  return eval;
}

}  // namespace depot::perception
