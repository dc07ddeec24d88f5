// `depot eval detector|segmenter`: a detector or a person segmenter scored
// against a simulated dataset's ground truth and/or hand-labelled real
// images. The work is in tools/perception (running) and eval/ (scoring, report).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "common/config_path.h"
#include "common/error.h"
#include "common/staged_directory.h"
#include "common/staged_file.h"
#include "common/yaml_overrides.h"
#include "eval/detection_report.h"
#include "eval/image_labels.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/person_segmenter.h"
#include "tools/depot/cli_errors.h"
#include "tools/depot/commands.h"
#include "tools/depot/detector_options.h"
#include "tools/depot/output_paths.h"
#include "tools/perception/detector_calibration.h"
#include "tools/perception/detector_eval.h"
#include "tools/perception/segmenter_eval.h"
#include "tools/runner/slam_runner.h"

namespace fs = std::filesystem;

namespace depot::cli {
namespace {

// A report folder is always new (or empty); its marker names it as ours.
const OutputKind kReportKind{"detector report", "report.html", {"report.html", "report.md"}};

struct DetectorArgs {
  std::string dataset;                // a simulated dataset
  runner::PerceptionChoice detector;  // detector type, its config and settings
  std::string images;                 // hand labels YAML
  std::string class_map;
  size_t every = 1;
  std::string json, report;
  bool quiet = false;
};

struct CalibrateArgs {
  std::vector<std::string> datasets;
  runner::PerceptionChoice detector;  // detector type, its config and settings
  std::string class_map;
  size_t every = 1;
  std::string output;
  bool quiet = false;
};

struct SegmenterArgs {
  std::string dataset, images;
  std::string config = project_file("scenes/segmenters/selfie.yaml");
  size_t every = 1;
  std::string json;
  bool quiet = false;
};

void require_input(const std::string& dataset, const std::string& images) {
  if (dataset.empty() && images.empty())
    fail_usage("", "give a DATASET, --images LABELS.yaml, or both");
  if (!dataset.empty() && !fs::is_directory(dataset)) fail(dataset, "dataset folder not found");
}

std::string every_text(size_t every, size_t frames) {
  return every == 1 ? std::to_string(frames) + " frames"
                    : std::to_string(frames) + " frames (every " + std::to_string(every) + ")";
}

void run_detector_eval(DetectorArgs& a) {
  const std::string& type = a.detector.detector;
  const std::string& dataset = a.dataset;
  require_input(dataset, a.images);
  if (type == "sim" && dataset.empty())
    fail_usage("--detector sim",
               "needs a simulated DATASET (it reads its boxes.txt), not only --images");
  if (type == "file")
    fail_usage("--detector file", "is not scored here (score the detector itself)");
  // Everything that can be refused is refused before the first frame.
  const eval::ClassMapping mapping = perception::class_mapping_for(type, a.class_map);
  std::optional<eval::ImageLabels> labels;
  if (!a.images.empty()) labels = eval::read_image_labels(a.images);
  OutputPaths outputs;
  outputs.add_input("--images", a.images);
  outputs.add_input_folder("DATASET", dataset);
  outputs.add_file("--json", a.json);
  outputs.add_folder("--report", a.report);
  outputs.check();
  std::unique_ptr<slam::Detector> detector = runner::make_detector(a.detector, dataset, type);
  std::optional<StagedFile> json;
  if (!a.json.empty()) json.emplace(a.json);
  std::optional<StagedDirectory> report;
  if (!a.report.empty()) {
    std::error_code ec;
    if (fs::exists(a.report, ec) && !(fs::is_directory(a.report, ec) && fs::is_empty(a.report, ec)))
      fail(a.report, "exists and is not empty (the report goes to a new or empty folder)");
    report.emplace(a.report, kReportKind, false);
  }

  std::vector<perception::DetectorEval> evals;
  std::vector<std::string> names;
  if (!dataset.empty()) {
    evals.push_back(perception::evaluate_on_dataset(*detector, dataset, mapping, a.every,
                                                    type != "sim", a.quiet));
    names.push_back("sim: " + fs::path(dataset).filename().string() + ", " +
                    every_text(a.every, evals.back().score.frames()));
  }
  if (labels) {
    evals.push_back(perception::evaluate_on_images(*detector, *labels, mapping, a.quiet));
    names.push_back("real: " + fs::path(a.images).filename().string() + ", " +
                    std::to_string(labels->images.size()) + " images");
  }
  std::vector<eval::DetectionSide> sides;
  for (size_t i = 0; i < evals.size(); ++i) sides.push_back(evals[i].side(names[i]));

  for (const eval::DetectionSide& side : sides)
    std::printf("%s\n", eval::detection_text(side).c_str());
  if (sides.size() > 1) std::printf("%s", eval::detection_gap_text(sides).c_str());
  if (json) {
    nlohmann::json doc = {{"detector", type}, {"sides", nlohmann::json::array()}};
    for (const eval::DetectionSide& side : sides)
      doc["sides"].push_back(eval::detection_side_json(side));
    json->stream() << doc.dump(2) << "\n";
    json->commit();
    std::printf("wrote %s\n", a.json.c_str());
  }
  if (report) {
    eval::write_detection_report(report->path(), "Detector " + type + ": " + sides.front().detector,
                                 sides);
    report->commit();
    std::printf("wrote %s/report.html\n", a.report.c_str());
  }
}

std::string rate_text(const eval::Tally& t) {
  if (t.total == 0) return "-";
  return fmt::format("{:.2f}", t.rate());
}

void run_calibrate(CalibrateArgs& a) {
  const std::string& type = a.detector.detector;
  // Everything that can be refused is refused before the first frame.
  const eval::ClassMapping mapping = perception::class_mapping_for(type, a.class_map);
  perception::CalibrationRequest request;
  request.datasets = a.datasets;
  request.every = a.every;
  request.mapping = mapping;
  request.quiet = a.quiet;
  std::string detector_config = a.detector.detector_config;
  std::string sim_dataset;  // the one the simulated detector reads
  if (type == "sim") {
    // The simulated detector fitted to itself: a check of the fit.
    if (a.datasets.size() != 1)
      fail_usage("--detector sim", "calibrates against one DATASET (the one it reads)");
    perception::check_calibration_dataset(a.datasets.front());
    sim_dataset = a.datasets.front();
    request.base = runner::sim_detector_config(a.detector);
    request.min_confidence = request.base.min_confidence;
    request.reads_pixels = false;
    if (detector_config.empty()) detector_config = runner::default_detector_config("sim");
  } else {
    if (detector_config.empty()) detector_config = runner::default_detector_config(type);
    request.min_confidence = slam::load_detector_config(detector_config).confidence;
  }
  check_output_file(a.output);
  for (const std::string& d : a.datasets) perception::check_calibration_dataset(d);
  std::unique_ptr<slam::Detector> detector = runner::make_detector(a.detector, sim_dataset, type);
  StagedFile out(a.output);

  std::string config_text;
  const perception::DetectorCalibration cal =
      perception::calibrate_sim_detector(*detector, request, config_text);
  perception::CalibrationMeta meta;
  meta.detector_type = type;
  meta.detector_config = detector_config;
  meta.class_map = mapping.path();
  meta.every = a.every;
  meta.command = "depot eval calibrate";
  for (const std::string& d : a.datasets) meta.command += " " + d;
  meta.command += " --detector " + type;
  if (!a.detector.detector_config.empty())
    meta.command += " --detector-config " + perception::portable_path(a.detector.detector_config);
  for (const YamlOverride& o : a.detector.detector_overrides)
    meta.command += " --detector-set " + o.key + "=" + o.value;
  if (!a.class_map.empty())
    meta.command += " --class-map " + perception::portable_path(a.class_map);
  if (a.every != 1) meta.command += " --every " + std::to_string(a.every);
  meta.command += " -o " + perception::portable_path(a.output);
  out.stream() << perception::calibration_file_text(cal, config_text, meta);
  out.commit();

  std::printf(
      "%s fitted on %ld boxes in %ld frames (%ld matched, %ld confused, %ld unmatched "
      "detections):\n%s",
      cal.detector_name.c_str(), cal.fit.boxes, cal.fit.frames, cal.fit.matched, cal.fit.confused,
      cal.fit.false_positives, config_text.c_str());
  std::printf("Recall per class, real detector / fitted simulated detector (%d seeds)\n",
              cal.sim_seeds);
  std::printf("  %-8s %6s %10s %10s %10s %10s\n", "class", "boxes", "all real", "all sim",
              "clear real", "clear sim");
  for (const std::string& c : cal.classes) {
    const auto it = cal.per_class.find(c);
    if (it == cal.per_class.end() || it->second.truth_boxes == 0) continue;
    const perception::ClassCalibration& pc = it->second;
    std::printf("  %-8s %6ld %10s %10s %10s %10s\n", c.c_str(), pc.truth_boxes,
                rate_text(pc.real_all).c_str(), rate_text(pc.sim_all).c_str(),
                rate_text(pc.real_clear).c_str(), rate_text(pc.sim_clear).c_str());
  }
  std::printf("wrote %s\n", a.output.c_str());
}

void run_segmenter_eval(const SegmenterArgs& a) {
  require_input(a.dataset, a.images);
  std::optional<eval::ImageLabels> labels;
  if (!a.images.empty()) labels = eval::read_image_labels(a.images);
  slam::PersonSegmenter segmenter(slam::load_segmenter_config(a.config));
  std::optional<StagedFile> json;
  if (!a.json.empty()) json.emplace(a.json);

  nlohmann::json doc = {{"segmenter", segmenter.name()}};
  if (!a.dataset.empty()) {
    const perception::SegmenterEval e =
        perception::evaluate_segmenter(segmenter, a.dataset, a.every, a.quiet);
    std::printf("sim: %s, %s: person mask (probability >= %.2f) against the label masks\n%s",
                fs::path(a.dataset).filename().c_str(),
                every_text(a.every, e.frames.size()).c_str(), segmenter.config().threshold,
                e.text().c_str());
    doc["dataset"] = e.json();
  }
  if (labels) {
    const perception::SegmenterEval e =
        perception::evaluate_segmenter_on_images(segmenter, *labels, a.quiet);
    std::printf("real: %s: person mask against the hand-labelled person boxes\n%s",
                fs::path(a.images).filename().c_str(), e.text().c_str());
    doc["images"] = e.json();
  }
  if (json) {
    json->stream() << doc.dump(2) << "\n";
    json->commit();
    std::printf("wrote %s\n", a.json.c_str());
  }
}

}  // namespace

void register_perception_eval_commands(CLI::App* group) {
  auto d = std::make_shared<DetectorArgs>();
  d->detector.detector = "darknet";
  CLI::App* det = group->add_subcommand(
      "detector",
      "Score a detector against a simulated dataset's boxes.txt and/or hand-labelled images: "
      "recall and precision per class at IoU 0.5, by box height and visible fraction, confusion");
  det->add_option("DATASET", d->dataset, "Simulated dataset folder (boxes.txt)");
  det->add_option("--images", d->images,
                  "Hand-labelled images YAML (e.g. eval/data/real_labels.yaml): the real side");
  det->add_option("--detector", d->detector.detector,
                  "sim (the simulated detector), darknet (Yolo-Fastest 1.1), xl (Yolo-Fastest 1.1 "
                  "XL), fastestdet, yolov5")
      ->check(CLI::IsMember({"sim", "darknet", "xl", "fastestdet", "yolov5"}))
      ->capture_default_str();
  det->add_option("--detector-config", d->detector.detector_config,
                  "Detector YAML (default: scenes/detectors/ for the type)");
  add_detector_set_option(
      det, d->detector.detector_overrides,
      "Change a simulated-detector key, e.g. --detector-set perfect=true (repeatable)");
  det->add_option("--detector-seed", d->detector.detector_seed,
                  "Seed of the simulated detector's errors")
      ->capture_default_str();
  det->add_option("--class-map", d->class_map,
                  "Detector label -> class YAML (default: identity for sim, else "
                  "scenes/detectors/coco_to_depot.yaml)");
  det->add_option("--every", d->every, "Score every N-th frame of the dataset")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  det->add_option("--json", d->json, "Also write every figure as JSON");
  det->add_option("--report", d->report,
                  "Also write a report folder (report.html, report.md, recall-vs-height SVGs)");
  det->add_flag("-q,--quiet", d->quiet, "No progress line");
  det->callback([d] { run_detector_eval(*d); });

  auto c = std::make_shared<CalibrateArgs>();
  c->detector.detector = "darknet";
  CLI::App* cal = group->add_subcommand(
      "calibrate",
      "Fit the simulated detector's error model to what a real detector does on simulated "
      "datasets; write it with the measurement (e.g. -o scenes/detectors/sim.yaml)");
  cal->add_option("DATASET", c->datasets, "Simulated dataset folders (boxes.txt)")->required();
  cal->add_option("--detector", c->detector.detector,
                  "darknet (Yolo-Fastest 1.1), xl (Yolo-Fastest 1.1 XL), fastestdet, yolov5, or "
                  "sim (the simulated detector fitted to itself: a check)")
      ->check(CLI::IsMember({"darknet", "xl", "fastestdet", "yolov5", "sim"}))
      ->capture_default_str();
  cal->add_option("--detector-config", c->detector.detector_config,
                  "Detector YAML (default: scenes/detectors/ for the type)");
  add_detector_set_option(
      cal, c->detector.detector_overrides,
      "With --detector sim: change a key of the detector being fitted (repeatable)");
  cal->add_option("--class-map", c->class_map,
                  "Detector label -> class YAML (default: scenes/detectors/coco_to_depot.yaml)");
  cal->add_option("--every", c->every, "Use every N-th frame of each dataset")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cal->add_option("-o,--output", c->output, "The fitted configuration (YAML)")->required();
  cal->add_flag("-q,--quiet", c->quiet, "No progress line");
  cal->callback([c] { run_calibrate(*c); });

  auto s = std::make_shared<SegmenterArgs>();
  CLI::App* seg = group->add_subcommand(
      "segmenter",
      "Score a person segmenter: mask IoU against a simulated dataset's person label masks, and "
      "the mask's share inside hand-labelled person boxes");
  seg->add_option("DATASET", s->dataset, "Simulated dataset folder (labels/, objects.json)");
  seg->add_option("--images", s->images, "Hand-labelled images YAML (their person boxes)");
  seg->add_option("--segmenter-config", s->config, "Segmenter YAML")->capture_default_str();
  seg->add_option("--every", s->every, "Score every N-th frame of the dataset")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  seg->add_option("--json", s->json, "Also write every figure as JSON");
  seg->add_flag("-q,--quiet", s->quiet, "No progress line");
  seg->callback([s] { run_segmenter_eval(*s); });
}

}  // namespace depot::cli
