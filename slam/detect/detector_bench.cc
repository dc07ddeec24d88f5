// depot_detector_bench: milliseconds per frame of each real OpenCV-dnn
// detector on the real TUM fr3/walking_xyz frame (median of N runs after one
// warm-up), and each as a ratio to baselines measured in the same run: the
// input preprocessing alone (cv::resize + blobFromImage at 320x320) and
// Yolo-Fastest 1.1 itself. Also the person segmenter
// (scenes/segmenters/selfie.yaml) with its pre- and post-processing at the
// frame's size.
//
//   depot_detector_bench [--runs N] [extra_detector.yaml ...]
//
// Extra YAML files (e.g. scenes/detectors/yolov5s.yaml once its model is in
// place) are benchmarked too. The thread count is OpenCV's default.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/person_segmenter.h"

namespace {

using depot::slam::Detection;

double median_ms(int runs, const std::function<void()>& f) {
  f();  // warm-up
  std::vector<double> ms;
  ms.reserve(static_cast<size_t>(runs));
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
  return ms[ms.size() / 2];
}

struct Row {
  std::string name;
  double ms;
  std::string found;
  bool baseline;  // Yolo-Fastest: the second baseline
};

}  // namespace

int main(int argc, char** argv) {
  int runs = 30;
  std::vector<std::string> yamls{
      std::string(DEPOT_SOURCE_DIR) + "/scenes/detectors/yolo_fastest.yaml",
      std::string(DEPOT_SOURCE_DIR) + "/scenes/detectors/yolo_fastest_xl.yaml",
      std::string(DEPOT_SOURCE_DIR) + "/scenes/detectors/fastestdet.yaml"};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "-h" || a == "--help") {
      std::printf("usage: %s [--runs N] [extra_detector.yaml ...]\n", argv[0]);
      return 0;
    } else {
      yamls.push_back(a);
    }
  }
  const std::string frame_path =
      std::string(DEPOT_SHARED_DATA) + "/tum/fr3_walking_xyz_frame/rgb/1341846313.592026.png";
  const cv::Mat frame = cv::imread(frame_path, cv::IMREAD_COLOR);
  if (frame.empty()) {
    std::fprintf(stderr, "%s: cannot read the TUM frame (shared data missing?)\n",
                 frame_path.c_str());
    return 1;
  }
  std::printf("frame %s (%dx%d), %d runs each, median; OpenCV %s, %d threads\n",
              std::filesystem::path(frame_path).filename().c_str(), frame.cols, frame.rows, runs,
              CV_VERSION, cv::getNumThreads());

  const double prep_ms = median_ms(runs, [&] {
    cv::Mat small;
    cv::resize(frame, small, {320, 320});
    const cv::Mat blob = cv::dnn::blobFromImage(small, 1 / 255.0, {320, 320}, {}, true, false);
    (void)blob;
  });

  std::vector<Row> rows;
  int status = 0;
  for (const std::string& yaml : yamls) {
    try {
      const depot::slam::DetectorConfig config = depot::slam::load_detector_config(yaml);
      const auto detector = depot::slam::make_dnn_detector(config);
      std::vector<Detection> dets;
      const double ms = median_ms(runs, [&] { dets = detector->detect(frame, 0.0, 0); });
      std::string found;
      for (const Detection& d : dets)
        if (d.class_name == "person")
          found += fmt::format("{}person {:.2f}", found.empty() ? "" : ", ",
                               static_cast<double>(d.confidence));
      rows.push_back({std::filesystem::path(yaml).stem().string() + " (" + config.type + ")", ms,
                      found.empty() ? "no person" : found, &yaml == &yamls.front()});
    } catch (const depot::Error& e) {
      std::fprintf(stderr, "skipping %s: %s\n", yaml.c_str(), e.what());
      status = 1;
    }
  }

  try {
    depot::slam::PersonSegmenter segmenter(depot::slam::load_segmenter_config(
        std::string(DEPOT_SOURCE_DIR) + "/scenes/segmenters/selfie.yaml"));
    double share = 0.0;
    const double ms = median_ms(
        runs, [&] { share = cv::countNonZero(segmenter.mask(frame)) / double(frame.total()); });
    rows.push_back({"selfie segmentation (mask)", ms,
                    cv::format("person mask %.0f %% of the frame", 100 * share), false});
  } catch (const depot::Error& e) {
    std::fprintf(stderr, "skipping the segmenter: %s\n", e.what());
    status = 1;
  }

  double yolo_fastest_ms = 0.0;
  for (const Row& r : rows)
    if (r.baseline) yolo_fastest_ms = r.ms;
  std::printf("%-28s %9s %10s %14s  %s\n", "detector / segmenter", "ms/frame", "x preproc",
              "x yolo_fastest", "persons found");
  std::printf("%-28s %9.2f %10.2f %14s  %s\n", "preprocess (resize+blob 320)", prep_ms, 1.0, "-",
              "-");
  for (const Row& r : rows)
    std::printf("%-28s %9.2f %10.1f %14s  %s\n", r.name.c_str(), r.ms, r.ms / prep_ms,
                yolo_fastest_ms > 0 ? cv::format("%.2f", r.ms / yolo_fastest_ms).c_str() : "-",
                r.found.c_str());
  return status;
}
