#include "tools/perception/detector_calibration.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "common/config_path.h"
#include "common/error.h"
#include "dataset/boxes.h"
#include "slam/detect/sim_detector.h"
#include "tools/perception/detector_eval.h"

namespace fs = std::filesystem;

namespace depot::perception {
namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// What the detector did with each box of a frame, and its false positives.
void collect_frame(const std::vector<slam::TruthBox>& truth,
                   const std::vector<eval::ScoredDetection>& detections,
                   const eval::ClassMapping& mapping, const slam::SimDetector& model, FitData& data,
                   std::map<std::string, ClassCalibration>& per_class) {
  const std::vector<std::string>& classes = model.class_names();
  const double image_area = static_cast<double>(model.image_size().area());
  const eval::FrameMatch m =
      eval::match_frame(truth_objects(truth), detections, mapping, eval::DetectionRules{}.min_iou);
  std::vector<bool> used(detections.size(), false);
  for (size_t t = 0; t < truth.size(); ++t) {
    const slam::TruthBox& box = truth[t];
    FitBox b;
    b.truth_class = box.class_name;
    b.area = box.area();
    b.image_area = image_area;
    b.occlusion = model.occlusion(box);
    int d = m.by_class[t];
    if (d >= 0) {
      b.detected_class = box.class_name;
    } else if ((d = m.any.detection_of_truth[t]) >= 0) {
      // Another class of the simulator (confused), or a label it has no
      // class for (a "bench": as good as missed).
      const std::string called = mapping.class_of(detections[d].label);
      if (contains(classes, called))
        b.detected_class = called;
      else
        d = -1;
    }
    if (d >= 0) {
      used[d] = true;
      const cv::Rect2f& tb = box.rect();
      const cv::Rect2f& db = detections[d].box;
      b.dx = (db.x + 0.5 * db.width - (tb.x + 0.5 * tb.width)) / tb.width;
      b.dy = (db.y + 0.5 * db.height - (tb.y + 0.5 * tb.height)) / tb.height;
      b.log_w = std::log(static_cast<double>(db.width) / tb.width);
      b.log_h = std::log(static_cast<double>(db.height) / tb.height);
      b.confidence = detections[d].confidence;
    }
    ++per_class[box.class_name].truth_boxes;
    data.boxes.push_back(std::move(b));
  }
  for (size_t d = 0; d < detections.size(); ++d) {
    if (!mapping.relevant(detections[d].label, classes)) continue;
    const std::string called = mapping.class_of(detections[d].label);
    if (contains(classes, called)) ++per_class[called].detections;
    if (!used[d]) data.false_positive_confidences.push_back(detections[d].confidence);
  }
  ++data.frames;
}

void add_tallies(const eval::DetectionScore& score, const std::vector<std::string>& classes,
                 bool sim, std::map<std::string, ClassCalibration>& per_class) {
  for (const std::string& c : classes) {
    const eval::ClassTally& t = score.tally(c);
    ClassCalibration& out = per_class[c];
    eval::Tally& all = sim ? out.sim_all : out.real_all;
    eval::Tally& clear = sim ? out.sim_clear : out.real_clear;
    all.found += t.all.found;
    all.total += t.all.total;
    clear.found += t.clear.found;
    clear.total += t.clear.total;
  }
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// The fitted keys, in the order of sim_detector_config.h.
std::string config_yaml(const slam::SimDetectorConfig& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(4);
  out << YAML::BeginMap;
  auto key = [&](const char* k, double v) { out << YAML::Key << k << YAML::Value << v; };
  key("miss_rate", c.miss_rate);
  out << YAML::Key << "class_miss_rate" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [cls, rate] : c.class_miss_rate) out << YAML::Key << cls << YAML::Value << rate;
  out << YAML::EndMap;
  key("small_miss_boost", c.small_miss_boost);
  key("small_area", c.small_area);
  key("occlusion_miss", c.occlusion_miss);
  key("default_fill", c.default_fill);
  key("jitter", c.jitter);
  key("scale_error", c.scale_error);
  key("hard_jitter_gain", c.hard_jitter_gain);
  key("min_confidence", c.min_confidence);
  key("max_confidence", c.max_confidence);
  key("confidence_drop", c.confidence_drop);
  key("confidence_noise", c.confidence_noise);
  key("false_positive_rate", c.false_positive_rate);
  key("false_positive_max_confidence", c.false_positive_max_confidence);
  key("class_confusion", c.class_confusion);
  out << YAML::Key << "class_confusion_rate" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [cls, rate] : c.class_confusion_rate)
    out << YAML::Key << cls << YAML::Value << rate;
  out << YAML::EndMap;
  out << YAML::Key << "confusions" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [cls, partners] : c.confusions)
    out << YAML::Key << cls << YAML::Value << YAML::Flow << partners;
  out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The command that renders the dataset again, from its info.json.
std::string render_command(const CalibrationDataset& d) {
  if (!d.info || d.info->scenario.empty() || !d.info->seed || !d.info->frames) return "";
  const dataset::DatasetInfo& i = *d.info;
  std::string cmd = "depot sim render " + i.scenario + " -o " + d.path + " --frames " +
                    std::to_string(*i.frames) + " --seed " + std::to_string(*i.seed);
  if (d.image_size.width != 640) cmd += " --width " + std::to_string(d.image_size.width);
  if (i.sensor == "ideal") cmd += " --ideal";
  if (i.dynamic_load && *i.dynamic_load != 1.0) cmd += " --load " + number_text(*i.dynamic_load);
  // Styles other than the default (mesh).
  if (!i.actors_style.empty() && i.actors_style != "mesh")
    cmd += " --set actors_style=" + i.actors_style;
  if (!i.props_style.empty() && i.props_style != "mesh")
    cmd += " --set props_style=" + i.props_style;
  if (i.world_seed && i.world_seed != i.seed)
    cmd += " --set seed_world=" + std::to_string(*i.world_seed);
  return cmd;
}

void emit_rate(YAML::Emitter& out, const char* key, const eval::Tally& t) {
  out << YAML::Key << key << YAML::Value;
  if (t.total > 0)
    out << t.rate();
  else
    out << YAML::Null;
}

}  // namespace

std::string portable_path(const std::string& path) {
  if (path.empty()) return path;
  const std::string p = fs::absolute(path).lexically_normal().string();
  auto under = [&](const std::string& root) -> std::string {
    const std::string r = fs::absolute(root).lexically_normal().string();
    if (r.empty() || p.size() <= r.size() + 1 || p.compare(0, r.size(), r) != 0) return "";
    if (r.back() == '/') return p.substr(r.size());
    return p[r.size()] == '/' ? p.substr(r.size() + 1) : "";
  };
  const std::string shared = under(shared_data_dir());
  if (!shared.empty()) return "${" + std::string(kSharedDataVariable) + "}/" + shared;
  const std::string project = under(project_file(""));
  if (!project.empty()) return project;
  return path;
}

void check_calibration_dataset(const std::string& path) {
  if (!fs::is_directory(path)) fail(path, "dataset folder not found");
  if (!dataset::has_boxes(path))
    fail(path,
         "no ground-truth boxes (boxes.txt): the calibration needs a simulated dataset (depot sim "
         "render)");
}

DetectorCalibration calibrate_sim_detector(slam::Detector& detector,
                                           const CalibrationRequest& request,
                                           std::string& config_text) {
  if (request.datasets.empty()) fail("depot eval calibrate", "give at least one DATASET");
  // Everything that can be refused is refused before the first frame.
  DetectorCalibration out;
  std::vector<std::unique_ptr<slam::SimDetector>> models;  // boxes, occlusion, the re-run
  for (const std::string& path : request.datasets) {
    check_calibration_dataset(path);
    models.push_back(std::make_unique<slam::SimDetector>(path, request.base));
    request.mapping.check_classes(models.back()->class_names(), path + "/classes.txt");
    for (const std::string& c : models.back()->class_names())
      if (!contains(out.classes, c)) out.classes.push_back(c);
  }

  FitData data;
  data.min_confidence = request.min_confidence;
  for (size_t k = 0; k < request.datasets.size(); ++k) {
    const std::string& path = request.datasets[k];
    const slam::SimDetector& model = *models[k];
    const DetectorEval real = evaluate_on_dataset(
        detector, path, request.mapping, request.every, request.reads_pixels, request.quiet,
        [&](size_t, const std::vector<slam::TruthBox>& truth,
            const std::vector<eval::ScoredDetection>& detections) {
          collect_frame(truth, detections, request.mapping, model, data, out.per_class);
        });
    add_tallies(real.score, model.class_names(), false, out.per_class);
    out.real_false_positives += real.score.false_positives();
    out.detector_name = real.detector;
    CalibrationDataset d;
    d.path = path;
    d.info = dataset::read_info(path);
    d.image_size = model.image_size();
    d.frames = model.frame_count();
    d.scored_frames = static_cast<size_t>(real.score.frames());
    out.datasets.push_back(std::move(d));
  }

  out.fit = fit_sim_detector(data, request.base, join(request.datasets, ", "));
  // The re-run uses the values exactly as the file states them.
  config_text = config_yaml(out.fit.config);
  slam::SimDetectorConfig fitted =
      slam::load_sim_detector_config(YAML::Load(config_text), "the fitted config");
  out.sim_seeds = request.sim_seeds;
  for (int seed = 1; seed <= request.sim_seeds; ++seed) {
    fitted.seed = static_cast<uint64_t>(seed);
    for (const std::string& path : request.datasets) {
      slam::SimDetector sim(path, fitted);
      const DetectorEval e =
          evaluate_on_dataset(sim, path, eval::ClassMapping{}, request.every, false, true);
      add_tallies(e.score, sim.class_names(), true, out.per_class);
      out.sim_false_positives += e.score.false_positives();
      out.sim_frames += e.score.frames();
    }
  }
  return out;
}

std::string calibration_file_text(const DetectorCalibration& cal, const std::string& config_text,
                                  const CalibrationMeta& meta) {
  YAML::Emitter out;
  out.SetDoublePrecision(4);
  out << YAML::BeginMap << YAML::Key << "calibration" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "detector" << YAML::Value << meta.detector_type;
  out << YAML::Key << "detector_config" << YAML::Value << portable_path(meta.detector_config);
  out << YAML::Key << "class_map" << YAML::Value
      << (meta.class_map.empty() ? std::string("identity") : portable_path(meta.class_map));
  out << YAML::Key << "command" << YAML::Value << meta.command;
  out << YAML::Key << "rules" << YAML::Value
      << "a box is matched at IoU >= 0.5 (greedy by confidence; the class map's rule first, then "
         "any class: confused); clearly visible boxes are >= 100 px tall with >= 4000 visible "
         "pixels";
  out << YAML::Key << "every" << YAML::Value << meta.every;
  out << YAML::Key << "datasets" << YAML::Value << YAML::BeginSeq;
  for (const CalibrationDataset& d : cal.datasets) {
    out << YAML::BeginMap;
    out << YAML::Key << "path" << YAML::Value << d.path;
    if (d.info) {
      const dataset::DatasetInfo& i = *d.info;
      auto text = [&](const char* key, const std::string& value) {
        if (!value.empty()) out << YAML::Key << key << YAML::Value << value;
      };
      text("scenario", i.scenario);
      text("actors_style", i.actors_style);
      text("props_style", i.props_style);
      text("sensor", i.sensor.value_or(""));
      if (i.seed) out << YAML::Key << "seed" << YAML::Value << *i.seed;
      if (i.world_seed) out << YAML::Key << "world_seed" << YAML::Value << *i.world_seed;
      if (i.dynamic_load) out << YAML::Key << "dynamic_load" << YAML::Value << *i.dynamic_load;
    }
    out << YAML::Key << "size" << YAML::Value
        << std::to_string(d.image_size.width) + "x" + std::to_string(d.image_size.height);
    out << YAML::Key << "frames" << YAML::Value << d.frames;
    out << YAML::Key << "scored_frames" << YAML::Value << d.scored_frames;
    const std::string render = render_command(d);
    if (!render.empty()) out << YAML::Key << "render" << YAML::Value << render;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  const SimDetectorFit& f = cal.fit;
  out << YAML::Key << "scored_frames" << YAML::Value << f.frames;
  out << YAML::Key << "truth_boxes" << YAML::Value << f.boxes;
  out << YAML::Key << "matched" << YAML::Value << f.matched;
  out << YAML::Key << "confused" << YAML::Value << f.confused;
  out << YAML::Key << "unmatched_detections" << YAML::Value << f.false_positives;
  out << YAML::Key << "of_them_off_target" << YAML::Value << f.off_target;
  out << YAML::Key << "miss_log_likelihood" << YAML::Value << f.miss_log_likelihood;
  out << YAML::Key << "sim_seeds" << YAML::Value << cal.sim_seeds;
  out << YAML::Key << "false_positives_per_frame" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "real" << YAML::Value
      << static_cast<double>(cal.real_false_positives) / std::max(1L, f.frames);
  out << YAML::Key << "sim" << YAML::Value
      << static_cast<double>(cal.sim_false_positives) / std::max(1L, cal.sim_frames);
  out << YAML::EndMap;
  out << YAML::Key << "classes" << YAML::Value << YAML::BeginMap;
  for (const std::string& c : cal.classes) {
    const auto it = cal.per_class.find(c);
    if (it == cal.per_class.end() || it->second.truth_boxes == 0) continue;
    const ClassCalibration& pc = it->second;
    const auto fc = f.classes.find(c);
    out << YAML::Key << c << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "boxes" << YAML::Value << pc.truth_boxes;
    out << YAML::Key << "clear_boxes" << YAML::Value << pc.real_clear.total;
    out << YAML::Key << "detections" << YAML::Value << pc.detections;
    out << YAML::Key << "found" << YAML::Value << pc.real_all.found;
    out << YAML::Key << "confused" << YAML::Value
        << (fc == f.classes.end() ? 0L : fc->second.confused);
    emit_rate(out, "recall_real", pc.real_all);
    emit_rate(out, "recall_sim", pc.sim_all);
    emit_rate(out, "recall_clear_real", pc.real_clear);
    emit_rate(out, "recall_clear_sim", pc.sim_clear);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::EndMap << YAML::EndMap;

  std::string header =
      "# The simulated detector's error model (slam/detect/sim_detector.h) fitted by\n"
      "# `depot eval calibrate` to what the real detector '" +
      meta.detector_type +
      "' did on simulated frames.\n"
      "# The fitted keys come first; `calibration` records the measurement they came\n"
      "# from (datasets and how to render them, the command that regenerates this\n"
      "# file) and the recall per class of the real detector and of the simulated\n"
      "# detector with these values, re-run on the same frames (recall_sim, over\n"
      "# `sim_seeds` seeds).\n";
  return header + config_text + out.c_str() + "\n";
}

}  // namespace depot::perception
