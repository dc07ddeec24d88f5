#include "tools/runner/slam_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "common/config_path.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "common/staged_file.h"
#include "common/yaml_overrides.h"
#include "slam/detect/detection_file.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/sim_detector.h"
#include "slam/io/frame_states_file.h"
#include "slam/io/rgbd_sequence.h"
#include "slam/io/settings.h"
#include "slam/reject/point_sets.h"
#include "slam/system/system.h"
#include "tools/runner/dense_map.h"
#include "tools/runner/frame_observer.h"
#include "tools/runner/frame_timings.h"
#include "tools/runner/frame_truth.h"
#include "tools/runner/keypoint_rows.h"
#include "tools/runner/rejection_overlay.h"
#include "tools/runner/stats_table.h"

namespace fs = std::filesystem;

namespace depot::runner {

std::string default_detector_config(const std::string& type) {
  if (type == "sim") return project_file("scenes/detectors/sim.yaml");
  if (type == "darknet") return project_file("scenes/detectors/yolo_fastest.yaml");
  if (type == "xl") return project_file("scenes/detectors/yolo_fastest_xl.yaml");
  if (type == "fastestdet") return project_file("scenes/detectors/fastestdet.yaml");
  if (type == "yolov5") return project_file("scenes/detectors/yolov5s.yaml");
  fail("--detector",
       "unknown detector '" + type + "' (expected sim, file, darknet, xl, fastestdet, yolov5)");
}

slam::SimDetectorConfig sim_detector_config(const PerceptionChoice& o) {
  slam::SimDetectorConfig config = slam::load_sim_detector_config_file(
      o.detector_config.empty() ? default_detector_config("sim") : o.detector_config);
  if (!o.detector_overrides.empty())
    config = slam::load_sim_detector_config(
        overrides_to_node(o.detector_overrides, "--detector-set"), "--detector-set", config);
  config.seed = o.detector_seed;
  return config;
}

std::unique_ptr<slam::Detector> make_detector(const PerceptionChoice& o, const std::string& dataset,
                                              const std::string& type) {
  if (type == "sim") return std::make_unique<slam::SimDetector>(dataset, sim_detector_config(o));
  if (type == "file") {
    if (o.detections.empty()) fail("--detector file", "needs --detections FILE");
    return std::make_unique<slam::FileDetector>(o.detections);
  }
  if (!o.detector_overrides.empty())
    fail("--detector-set",
         "applies to the simulated detector only (edit the " + type + " detector's YAML instead)");
  const auto& dnn = slam::dnn_detector_types();
  if (type != "xl" && std::find(dnn.begin(), dnn.end(), type) == dnn.end())
    fail("--detector",
         "unknown detector '" + type + "' (expected sim, file, darknet, xl, fastestdet, yolov5)");
  const std::string config =
      o.detector_config.empty() ? default_detector_config(type) : o.detector_config;
  const slam::DetectorConfig loaded = slam::load_detector_config(config);
  const std::string expected = type == "xl" ? "darknet" : type;  // XL is a Darknet model
  if (loaded.type != expected)
    fail(config,
         "configures a '" + loaded.type + "' detector, but --detector " + type + " was asked for");
  return slam::make_dnn_detector(loaded);
}

namespace {

// The images must have the camera's size: say which file, which sizes, and
// where the camera came from, before any work.
void check_image_size(const slam::RgbdSequence& sequence, const slam::SlamSettings& settings,
                      const std::string& settings_source) {
  cv::Mat bgr, depth;
  sequence.load(0, bgr, depth);
  const int w = settings.camera.width, h = settings.camera.height;
  if (bgr.cols == w && bgr.rows == h) return;
  fail(sequence.colour_location(0),
       "image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
           " but the camera of " + settings_source + " is " + std::to_string(w) + "x" +
           std::to_string(h) + " (give --settings with the dataset's intrinsics)");
}

}  // namespace

RejectionSetup make_rejection(const RunOptions& options, float scale_factor) {
  RejectionSetup setup;
  const slam::RejectionMode mode = slam::parse_rejection_mode(options.rejection.mode);
  if (mode == slam::RejectionMode::kOrb) return setup;
  const PerceptionChoice& o = options.perception;
  const std::string& dataset = options.input.dataset;
  const std::string type = !o.detector.empty()
                               ? o.detector
                               : (eval::MotionTruth::available(dataset) ? "sim" : "darknet");
  if (slam::mode_uses_detector(mode)) setup.detector = make_detector(o, dataset, type);
  const std::string table_path =
      !o.classes.empty()
          ? o.classes
          : project_file(type == "sim" ? "scenes/apriori/depot.yaml" : "scenes/apriori/coco.yaml");
  slam::AprioriClasses classes = slam::AprioriClasses::load(table_path);
  if (setup.detector && !setup.detector->class_names().empty())
    classes.check_against(setup.detector->class_names(), table_path, setup.detector->name());
  slam::RejectionParams params = options.rejection.params;
  params.scale_factor = scale_factor;
  setup.filter =
      std::make_unique<slam::RejectionFilter>(mode, classes, setup.detector.get(), params);
  if (mode == slam::RejectionMode::kMasked &&
      params.person_mask != slam::RejectionParams::PersonMask::kDepth) {
    const std::string config =
        o.segmenter.empty() ? project_file("scenes/segmenters/selfie.yaml") : o.segmenter;
    setup.segmenter = std::make_unique<slam::PersonSegmenter>(slam::load_segmenter_config(config));
    setup.filter->set_segmenter(setup.segmenter.get());
  }
  return setup;
}

namespace {

// Where a run's camera came from when neither the recording nor --settings
// states one.
constexpr const char* kDefaultCameraSource = "the TUM fr3 Kinect defaults (no calibration.yaml)";

// The settings of a run: the dataset's calibration.yaml (else the TUM fr3
// Kinect defaults), then --settings, then the run's own switches; `source`
// says where the camera came from, for errors and the summary.
slam::SlamSettings load_run_settings(const RunInput& in, const slam::RgbdSequence& sequence,
                                     std::string& source) {
  slam::SlamSettings settings;
  source = kDefaultCameraSource;
  if (!sequence.calibration_path().empty()) {
    settings = slam::load_settings(sequence.calibration_path(), settings);
    source = sequence.calibration_path();
  } else if (const auto camera = sequence.recorded_camera(slam::camera_calibration_of(settings))) {
    source = sequence.source() + " (its camera_info)";
    slam::set_camera(settings, *camera, source);
  }
  if (!in.settings.empty()) {
    settings = slam::load_settings(in.settings, settings);
    source = in.settings;
  }
  if (in.sync) settings.threaded_mapping = false;
  if (!in.vocabulary.empty()) settings.vocabulary = in.vocabulary;
  if (!in.loop_closing) settings.loop_closing = false;
  return settings;
}

// The input's checks, before any work; returns the number of frames to run.
size_t check_input(const RunOptions& o, slam::RgbdSequence& sequence,
                   const slam::SlamSettings& settings, const std::string& settings_source) {
  if (o.map.localise_only && o.map.load_map.empty())
    fail("--localise-only", "needs a map to localise in (--load-map M)");
  if (!o.map.save_map.empty()) check_output_file(o.map.save_map);
  sequence.set_depth_factor(settings.camera.depth_factor);
  const std::optional<size_t>& frames = o.input.frames;
  if (frames && *frames > sequence.size())
    fail(o.input.dataset, "has " + std::to_string(sequence.size()) + " frames; --frames asks for " +
                              std::to_string(*frames));
  check_image_size(sequence, settings, settings_source);
  if (settings_source == kDefaultCameraSource)
    std::fprintf(stderr,
                 "depot: warning: %s: no calibration.yaml; using the TUM fr3 Kinect intrinsics "
                 "(%dx%d, fx %.1f fy %.1f cx %.1f cy %.1f; give --settings to choose others)\n",
                 o.input.dataset.c_str(), settings.camera.width, settings.camera.height,
                 settings.camera.fx, settings.camera.fy, settings.camera.cx, settings.camera.cy);
  return frames ? *frames : sequence.size();
}

// The observers of the run, each checking its output before any work.
std::vector<std::unique_ptr<FrameObserver>> make_observers(const RunOptions& o,
                                                           const slam::SlamSettings& settings,
                                                           const slam::RejectionFilter* filter,
                                                           const eval::MotionTruth* truth) {
  std::vector<std::unique_ptr<FrameObserver>> observers;
  observers.push_back(std::make_unique<FrameTimings>());
  observers.push_back(std::make_unique<RejectionScoring>());
  const RunOutputs& out = o.outputs;
  if (!out.dense_map.empty())
    observers.push_back(std::make_unique<DenseMapBuilder>(
        out.dense_map, parse_dense_mask(out.dense_mask), out.dense, settings.camera, filter, truth,
        o.input.dataset, o.rejection.mode));
  if (!out.stats_csv.empty()) observers.push_back(std::make_unique<StatsTable>(out.stats_csv));
  if (!out.overlays.empty()) {
    if (!filter)
      fail(out.overlays,
           "rejection pictures need a rejection mode (orb+yolo, orb+lk, full or masked)");
    observers.push_back(std::make_unique<OverlayFolder>(out.overlays, out.overlays_every));
  }
  if (!out.keypoints_csv.empty()) {
    if (!filter)
      fail(out.keypoints_csv,
           "per-keypoint rows need a rejection mode (orb+yolo, orb+lk, full or masked)");
    observers.push_back(std::make_unique<KeypointRows>(out.keypoints_csv));
  }
  return observers;
}

// The dataset's frames as a camera delivers them: frame k's images in slot
// k % 2 (a frame handed over ahead keeps its pixels until it is tracked:
// loading overwrites depth in place), each frame arriving at k / rate_hz
// after frame 0 when the camera is paced.
class FrameFeed {
 public:
  FrameFeed(const slam::RgbdSequence& sequence, double rate_hz)
      : sequence_(sequence), rate_hz_(rate_hz) {
    sequence_.load(0, bgr_[0], depth_[0]);
    start_ = Clock::now();  // frame 0 arrives
  }
  const cv::Mat& bgr(size_t k) const { return bgr_[k % 2]; }
  const cv::Mat& depth(size_t k) const { return depth_[k % 2]; }
  double timestamp(size_t k) const { return sequence_.timestamp(k); }
  // Loads frame k (frame 0 is loaded already) and waits for its arrival.
  void receive(size_t k) {
    if (k > 0) sequence_.load(k, bgr_[k % 2], depth_[k % 2]);
    if (rate_hz_ <= 0) return;
    const auto due = start_ + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(k / rate_hz_));
    if (Clock::now() < due)
      std::this_thread::sleep_until(due);
    else if (k > 0)
      ++late_;
  }
  size_t late_frames() const { return late_; }

 private:
  using Clock = std::chrono::steady_clock;
  const slam::RgbdSequence& sequence_;
  double rate_hz_;
  cv::Mat bgr_[2], depth_[2];
  Clock::time_point start_;
  size_t late_ = 0;
};

// What the frame just tracked gave, for the observers; `judged` holds the
// truth's judgement the record points to (simulated data with a filter).
FrameRecord record_frame(size_t i, const FrameFeed& feed, const slam::TrackResult& r,
                         const slam::RejectionFilter* filter, const eval::MotionTruth* truth,
                         float scale_factor, std::optional<FrameTruth>& judged) {
  FrameRecord record{i, feed.timestamp(i), feed.bgr(i), feed.depth(i), r, filter, {}, {}, nullptr};
  judged.reset();
  if (!filter) {
    record.rejection.total = record.rejection.kept = record.rejection.p = r.keypoints;
    return record;
  }
  record.rejection = filter->last_stats();
  record.keypoint_depths = slam::keypoint_depths(feed.depth(i), filter->last_keypoints());
  if (truth) {
    judged = judge_frame(*truth, record.timestamp, *filter, scale_factor);
    record.truth = &*judged;
  }
  return record;
}

// The system's side of the summary, once it has finished.
void summarise_system(const slam::System& system, RunSummary& summary) {
  summary.trajectory = system.trajectory();
  summary.frame_states = system.frame_states();
  for (const slam::AtlasPose& p : system.atlas_trajectory())
    summary.atlas_trajectory.push_back(p.pose);
  summary.tracked = slam::tracked_share(summary.frame_states).tracked;
  summary.keyframes_trajectory = system.keyframe_trajectory();
  summary.keyframes = system.n_keyframes();
  summary.map_points = system.n_map_points();
  summary.ba_ms_total = system.mapping_stats().ba_ms;
  summary.loops = system.loop_closures();
  summary.loops_refused = system.loops_refused();
  summary.global_adjustments = system.global_adjustments();
  summary.maps = system.maps();
  summary.merges_unconfirmed = system.merges_unconfirmed();
  summary.maps_rejoined = system.maps_rejoined();
}

// Why no frame got a pose.
std::string no_frame_tracked(const RunSummary& summary, const std::string& load_map) {
  const bool abandoned =
      std::any_of(summary.frame_states.begin(), summary.frame_states.end(),
                  [](const auto& f) { return f.state == slam::FrameState::kAbandoned; });
  // With a loaded map no frame initialises a map of its own: each must
  // relocalise in the loaded one (its place, vocabulary and camera).
  const std::string why =
      !load_map.empty() ? "no frame relocalised in the loaded map " + load_map +
                              " (is it a map of this place, seen from these views?)"
      : abandoned ? "every map started was abandoned (lost within its first keyframes)"
                  : "tracking never initialised (too few keypoints with depth?)";
  return std::string(kNoFrameTracked) + ": " + why;
}

}  // namespace

PreparedRun prepare_run(const RunOptions& o, const slam::RgbdSequence& sequence) {
  PreparedRun run;
  run.settings = load_run_settings(o.input, sequence, run.settings_source);
  run.rejection = make_rejection(o, run.settings.orb.scale_factor);
  run.system = std::make_unique<slam::System>(run.settings, run.rejection.filter.get());
  return run;
}

RunSummary run_sequence(const RunOptions& o) {
  RunSummary summary;
  const std::unique_ptr<slam::RgbdSequence> opened =
      slam::open_sequence(o.input.dataset, o.input.topics);
  slam::RgbdSequence& sequence = *opened;
  const slam::SlamSettings settings = load_run_settings(o.input, sequence, summary.settings_source);
  const size_t n = check_input(o, sequence, settings, summary.settings_source);
  // Rejection, truth and outputs: all checked before any work.
  RejectionSetup rejection = make_rejection(o, settings.orb.scale_factor);
  const slam::RejectionFilter* filter = rejection.filter.get();
  if (rejection.detector) summary.detector_name = rejection.detector->name();
  std::unique_ptr<eval::MotionTruth> truth;
  if (eval::MotionTruth::available(o.input.dataset))
    truth = std::make_unique<eval::MotionTruth>(o.input.dataset);
  summary.scored = truth != nullptr;
  const auto observers = make_observers(o, settings, filter, truth.get());

  slam::System system(settings, rejection.filter.get());
  if (!o.map.load_map.empty()) system.load_map(o.map.load_map);
  if (o.map.localise_only) system.start_localisation();
  Progress progress("slam " + o.rejection.mode, n, !o.quiet);
  FrameFeed feed(sequence, o.pacing.rate_hz);
  const bool ahead = o.pacing.run_ahead;
  if (ahead) system.look_ahead(feed.bgr(0), feed.depth(0), feed.timestamp(0));
  std::optional<FrameTruth> judged;
  for (size_t i = 0; i < n; ++i) {
    throw_if_interrupted(o.input.dataset);
    if (!ahead) {
      feed.receive(i);
    } else if (i + 1 < n) {  // frame i is tracked once frame i+1 is there: hand it over first
      feed.receive(i + 1);
      system.look_ahead(feed.bgr(i + 1), feed.depth(i + 1), feed.timestamp(i + 1));
    }
    const slam::TrackResult r = system.track(feed.bgr(i), feed.depth(i), feed.timestamp(i));
    const FrameRecord record =
        record_frame(i, feed, r, filter, truth.get(), settings.orb.scale_factor, judged);
    for (const auto& observer : observers) observer->on_frame(record);
    if (o.hooks.on_frame) o.hooks.on_frame(i, r, filter, system);
    progress.update(i + 1, fmt::format("frame {} {} features {}/{} inliers {} {:.1f} ms", i,
                                       slam::tracking_state_name(r.state), r.kept, r.keypoints,
                                       r.stats.inliers, r.timing.total_ms));
  }
  progress.finish();
  system.finish();
  if (o.hooks.after_run) o.hooks.after_run(system, sequence);
  summary.frames = n;
  summary.late_frames = feed.late_frames();
  summarise_system(system, summary);
  // A run that posed no frame writes nothing: no map, no cloud, no tables.
  if (summary.trajectory.empty()) fail(o.input.dataset, no_frame_tracked(summary, o.map.load_map));
  if (!o.map.save_map.empty()) system.save_map(o.map.save_map);
  for (const auto& observer : observers) observer->on_finish(system, sequence, summary);
  for (const auto& observer : observers) observer->commit();
  return summary;
}

}  // namespace depot::runner
