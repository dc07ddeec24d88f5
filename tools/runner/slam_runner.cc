#include "tools/runner/slam_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "common/config_path.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/percentile.h"
#include "common/png_codec.h"
#include "common/progress.h"
#include "common/staged_directory.h"
#include "common/staged_file.h"
#include "common/yaml_overrides.h"
#include "eval/keypoint_file.h"
#include "eval/keypoint_score.h"
#include "slam/detect/detection_file.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/sim_detector.h"
#include "slam/detect/sim_detector_config.h"
#include "slam/io/frame_states_file.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "slam/system/system.h"
#include "tools/runner/dense_map.h"
#include "tools/runner/rejection_overlay.h"

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

slam::SimDetectorConfig sim_detector_config(const RunOptions& o) {
  slam::SimDetectorConfig config = slam::load_sim_detector_config_file(
      o.detector_config.empty() ? default_detector_config("sim") : o.detector_config);
  if (!o.detector_overrides.empty())
    config = slam::load_sim_detector_config(
        overrides_to_node(o.detector_overrides, "--detector-set"), "--detector-set", config);
  config.seed = o.detector_seed;
  return config;
}

std::unique_ptr<slam::Detector> make_detector(const RunOptions& o, const std::string& type) {
  if (type == "sim") return std::make_unique<slam::SimDetector>(o.dataset, sim_detector_config(o));
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

char set_letter(slam::PointSet set) {
  return set == slam::PointSet::kZ ? 'Z' : set == slam::PointSet::kQ ? 'Q' : 'P';
}

// One row per keypoint of the frame (eval/keypoint_file.h): where it is, its
// set and decision, its depth, and (simulated data) whether it lies on a
// moving object or on its boundary (MotionTruth's rule) and the instance id
// there (objects.json); empty truth columns on real data.
void write_keypoint_rows(std::ostream& out, size_t frame, double timestamp,
                         const slam::RejectionFilter& filter, const std::vector<float>& depths,
                         const eval::MotionTruth::KeypointTruth* truth) {
  const auto& kps = filter.last_keypoints();
  eval::WrittenKeypoint row;
  row.frame = frame;
  row.timestamp = timestamp;
  for (size_t k = 0; k < kps.size(); ++k) {
    row.keypoint = kps[k];
    row.set = set_letter(filter.last_sets()[k]);
    row.kept = filter.last_keep()[k] != 0;
    row.depth_m = depths[k];
    if (truth)
      row.truth = eval::WrittenKeypoint::Truth{truth->on_moving[k] != 0, truth->boundary[k] != 0,
                                               truth->instance[k]};
    eval::write_keypoint_row(out, row);
  }
}

// The images must have the camera's size: say which file, which sizes, and
// where the camera came from, before any work.
void check_image_size(const slam::TumSequence& sequence, const slam::SlamSettings& settings,
                      const std::string& settings_source) {
  cv::Mat bgr, depth;
  sequence.load(0, bgr, depth);
  const int w = settings.camera.width, h = settings.camera.height;
  if (bgr.cols == w && bgr.rows == h) return;
  fail((fs::path(sequence.folder()) / sequence.entry(0).rgb_path).string(),
       "image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
           " but the camera of " + settings_source + " is " + std::to_string(w) + "x" +
           std::to_string(h) + " (give --settings with the dataset's intrinsics)");
}

}  // namespace

RejectionSetup make_rejection(const RunOptions& o, float scale_factor) {
  RejectionSetup setup;
  const slam::RejectionMode mode = slam::parse_rejection_mode(o.mode);
  if (mode == slam::RejectionMode::kOrb) return setup;
  const std::string type = !o.detector.empty()
                               ? o.detector
                               : (eval::MotionTruth::available(o.dataset) ? "sim" : "darknet");
  if (slam::mode_uses_detector(mode)) setup.detector = make_detector(o, type);
  const std::string table_path =
      !o.classes.empty()
          ? o.classes
          : project_file(type == "sim" ? "scenes/apriori/depot.yaml" : "scenes/apriori/coco.yaml");
  slam::AprioriClasses classes = slam::AprioriClasses::load(table_path);
  if (setup.detector && !setup.detector->class_names().empty())
    classes.check_against(setup.detector->class_names(), table_path, setup.detector->name());
  slam::RejectionParams params = o.rejection;
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

RunSummary run_sequence(const RunOptions& o) {
  RunSummary summary;
  slam::TumSequence sequence(o.dataset);
  slam::SlamSettings settings;
  summary.settings_source = "the TUM fr3 Kinect defaults (no calibration.yaml)";
  if (!sequence.calibration_path().empty()) {
    settings = slam::load_settings(sequence.calibration_path(), settings);
    summary.settings_source = sequence.calibration_path();
  }
  if (!o.settings.empty()) {
    settings = slam::load_settings(o.settings, settings);
    summary.settings_source = o.settings;
  }
  if (o.sync) settings.threaded_mapping = false;
  if (!o.vocabulary.empty()) settings.vocabulary = o.vocabulary;
  if (o.localise_only && o.load_map.empty())
    fail("--localise-only", "needs a map to localise in (--load-map M)");
  if (!o.save_map.empty()) check_output_file(o.save_map);
  if (!o.loop_closing) settings.loop_closing = false;
  sequence.set_depth_factor(settings.camera.depth_factor);
  if (o.frames && *o.frames > sequence.size())
    fail(o.dataset, "has " + std::to_string(sequence.size()) + " frames; --frames asks for " +
                        std::to_string(*o.frames));
  const size_t n = o.frames ? *o.frames : sequence.size();
  check_image_size(sequence, settings, summary.settings_source);
  if (sequence.calibration_path().empty() && o.settings.empty())
    std::fprintf(stderr,
                 "depot: warning: %s: no calibration.yaml; using the TUM fr3 Kinect intrinsics "
                 "(%dx%d, fx %.1f fy %.1f cx %.1f cy %.1f; give --settings to choose others)\n",
                 o.dataset.c_str(), settings.camera.width, settings.camera.height,
                 settings.camera.fx, settings.camera.fy, settings.camera.cx, settings.camera.cy);

  // Rejection: mode, detector and class table, all checked before any work.
  const bool simulated = eval::MotionTruth::available(o.dataset);
  RejectionSetup rejection = make_rejection(o, settings.orb.scale_factor);
  slam::RejectionFilter* filter = rejection.filter.get();
  if (rejection.detector) summary.detector_name = rejection.detector->name();
  std::unique_ptr<eval::MotionTruth> truth;
  if (simulated) truth = std::make_unique<eval::MotionTruth>(o.dataset);
  summary.scored = truth != nullptr;
  // The dense map's masks: checked before any work.
  const DenseMask dense_mask = parse_dense_mask(o.dense_mask);
  const bool dense = !o.dense_map.empty();
  if (dense) {
    check_output_file(o.dense_map);
    slam::DenseCloud check_params(settings.camera, o.dense);
    if (dense_mask == DenseMask::kLabels && !truth)
      fail(o.dataset, "has no labels: --dense-mask labels needs a simulated dataset");
    if (dense_mask == DenseMask::kRejection &&
        (!filter || filter->mode() == slam::RejectionMode::kOrbLk))
      fail("--dense-mask rejection",
           "mode " + o.mode +
               " leaves no moving mask (orb+yolo, full and masked do); give --dense-mask labels "
               "or none");
  }
  std::map<double, cv::Mat> keyframe_masks;  // rejection masks of the frames made keyframes

  std::optional<StagedFile> stats, keypoint_rows;
  if (!o.stats_csv.empty()) {
    stats.emplace(o.stats_csv);
    stats->stream()
        << "frame,timestamp,state,keypoints,kept,Z,Q,Q_to_P,P,detections,flow_u,flow_v,z,wait_ms,"
           "detect_ms,flow_ms,"
           "filter_ms,total_ms,true_positive,false_positive,false_negative,false_positive_z,"
           "false_positive_q,method,matches,inliers,local_points,new_keyframe,motion_objects,"
           "motion_rejected\n";
  }
  std::optional<StagedDirectory> overlays;
  std::optional<std::ofstream> overlay_index;
  if (!o.overlays.empty()) {
    if (!filter)
      fail(o.overlays,
           "rejection pictures need a rejection mode (orb+yolo, orb+lk, full or masked)");
    overlays.emplace(o.overlays, overlay_folder_kind(), false);
    fs::create_directories(fs::path(overlays->path()) / "frames");
    overlay_index.emplace((fs::path(overlays->path()) / "index.txt").string());
    *overlay_index << "# frame timestamp picture (depot slam run --overlays; colours: "
                      "tools/runner/rejection_overlay.h)\n";
  }
  if (!o.keypoints_csv.empty()) {
    if (!filter)
      fail(o.keypoints_csv,
           "per-keypoint rows need a rejection mode (orb+yolo, orb+lk, full or masked)");
    keypoint_rows.emplace(o.keypoints_csv);
    eval::write_keypoint_header(keypoint_rows->stream());
  }

  slam::System system(settings, filter);
  if (!o.load_map.empty()) system.load_map(o.load_map);
  if (o.localise_only) system.start_localisation();
  std::vector<double> total, extract, track, filter_ms, wait_ms, detect_ms, flow_ms;
  Progress progress("slam " + o.mode, n, !o.quiet);
  // Two frames' images, frame k in slot k % 2: a frame handed over ahead
  // keeps its pixels until it is tracked (loading overwrites depth in place).
  cv::Mat bgr_slots[2], depth_slots[2];
  using Clock = std::chrono::steady_clock;
  sequence.load(0, bgr_slots[0], depth_slots[0]);
  const Clock::time_point start = Clock::now();  // frame 0 arrives
  // Sleeps until frame k of the emulated camera has arrived.
  auto await_arrival = [&](size_t k) {
    if (o.rate_hz <= 0) return;
    const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>(k / o.rate_hz));
    if (Clock::now() < due)
      std::this_thread::sleep_until(due);
    else if (k > 0)
      ++summary.late_frames;
  };
  if (o.run_ahead) system.look_ahead(bgr_slots[0], depth_slots[0], sequence.entry(0).rgb_timestamp);
  slam::TrackingState previous_state = slam::TrackingState::kNotInitialized;
  std::vector<double> relocalising;
  for (size_t i = 0; i < n; ++i) {
    throw_if_interrupted(o.dataset);
    const cv::Mat& bgr = bgr_slots[i % 2];
    const cv::Mat& depth = depth_slots[i % 2];
    if (!o.run_ahead) {
      if (i > 0) sequence.load(i, bgr_slots[i % 2], depth_slots[i % 2]);
      await_arrival(i);
    } else if (i + 1 < n) {
      // Frame i is tracked once frame i+1 is there; hand i+1 over first.
      const size_t next = (i + 1) % 2;
      sequence.load(i + 1, bgr_slots[next], depth_slots[next]);
      await_arrival(i + 1);
      system.look_ahead(bgr_slots[next], depth_slots[next], sequence.entry(i + 1).rgb_timestamp);
    }
    const double t = sequence.entry(i).rgb_timestamp;
    slam::TrackResult r = system.track(bgr, depth, t);
    // A frame that follows a lost one is where relocalisation is tried.
    if (previous_state == slam::TrackingState::kLost) relocalising.push_back(r.timing.track_ms);
    previous_state = r.state;
    summary.lost += r.state == slam::TrackingState::kLost;
    summary.relocalized += r.state == slam::TrackingState::kRelocalized;
    if (dense && dense_mask == DenseMask::kRejection && r.stats.new_keyframe)
      keyframe_masks[t] = filter->moving_mask(bgr.size());
    total.push_back(r.timing.total_ms);
    extract.push_back(r.timing.extract_ms);
    track.push_back(r.timing.track_ms);
    slam::RejectionStats rs;
    if (filter) {
      rs = filter->last_stats();
      filter_ms.push_back(rs.filter_ms);
      wait_ms.push_back(rs.wait_ms);
      detect_ms.push_back(rs.detect_ms);
      flow_ms.push_back(rs.flow_ms);
    } else {
      rs.total = rs.kept = rs.p = r.keypoints;
    }
    // The keypoints' depths, for the score over keypoints with depth and
    // the keypoint rows.
    std::vector<float> kp_depth;
    if (filter && (truth || keypoint_rows))
      kp_depth = slam::keypoint_depths(depth, filter->last_keypoints());
    eval::RejectionScore frame_score;
    long fp_z = 0, fp_q = 0;
    eval::MotionTruth::KeypointTruth labels;
    if (truth && filter) {
      frame_score = eval::score_frame(*truth, t, filter->last_keypoints(), filter->last_keep(),
                                      settings.orb.scale_factor, &labels);
      const std::vector<uint8_t>& moving = labels.on_moving;
      // Where the false rejections come from: Z (boxes) or Q (flow test).
      for (size_t k = 0; k < moving.size(); ++k) {
        if (filter->last_keep()[k] || moving[k]) continue;
        (filter->last_sets()[k] == slam::PointSet::kZ ? fp_z : fp_q)++;
      }
      summary.score.add(frame_score);
      // Keypoints with depth on their own: only they start map points.
      std::vector<uint8_t> keep_d, moving_d, boundary_d;
      for (size_t k = 0; k < kp_depth.size(); ++k) {
        if (!(kp_depth[k] > 0)) continue;
        keep_d.push_back(filter->last_keep()[k]);
        moving_d.push_back(labels.on_moving[k]);
        boundary_d.push_back(labels.boundary[k]);
      }
      summary.score_with_depth.add(keep_d, moving_d, boundary_d);
    }
    if (overlays && i % o.overlays_every == 0) {
      char name[32];
      std::snprintf(name, sizeof(name), "frames/%06zu.png", i);
      write_png((fs::path(overlays->path()) / name).string(),
                draw_rejection_overlay(bgr, *filter, truth ? &labels : nullptr), PngKind::kColor);
      char row[96];
      std::snprintf(row, sizeof(row), "%zu %.6f %s\n", i, t, name);
      *overlay_index << row;
    }
    if (keypoint_rows)
      write_keypoint_rows(keypoint_rows->stream(), i, t, *filter, kp_depth,
                          truth ? &labels : nullptr);
    if (stats) {
      char line[640];
      std::snprintf(line, sizeof(line),
                    "%zu,%.6f,%s,%d,%d,%d,%d,%d,%d,%d,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f,%.2f,%.2f,%ld,%"
                    "ld,%ld,%ld,%ld,%s,%d,%d,%d,%d,%d,%d\n",
                    i, t, slam::tracking_state_name(r.state), rs.total, rs.kept, rs.z, rs.q,
                    rs.q_to_p, rs.p, rs.detections, rs.mean_flow.x, rs.mean_flow.y, rs.z_threshold,
                    rs.wait_ms, rs.detect_ms, rs.flow_ms, rs.filter_ms, r.timing.total_ms,
                    frame_score.true_positive, frame_score.false_positive,
                    frame_score.false_negative, fp_z, fp_q,
                    slam::tracking_method_name(r.stats.method), r.stats.matches, r.stats.inliers,
                    r.stats.local_points, r.stats.new_keyframe ? 1 : 0, rs.motion_objects,
                    rs.motion_rejected);
      stats->stream() << line;
    }
    if (o.on_frame) o.on_frame(i, r, filter, system);
    char detail[160];
    std::snprintf(detail, sizeof(detail), "frame %zu %s features %d/%d inliers %d %.1f ms", i,
                  slam::tracking_state_name(r.state), r.kept, r.keypoints, r.stats.inliers,
                  r.timing.total_ms);
    progress.update(i + 1, detail);
  }
  progress.finish();
  system.finish();
  if (o.after_run) o.after_run(system, sequence);
  if (!o.save_map.empty()) system.save_map(o.save_map);
  if (dense) {
    const DenseMapResult cloud =
        write_dense_map(o.dense_map, sequence, settings.camera, system.keyframe_trajectory(),
                        dense_mask, keyframe_masks, truth.get(), o.dense);
    summary.dense_points = cloud.points;
    summary.dense_keyframes = cloud.keyframes;
    summary.dense_left_out = cloud.without_frame + cloud.without_mask;
  }
  summary.frames = n;
  summary.trajectory = system.trajectory();
  summary.frame_states = system.frame_states();
  for (const slam::AtlasPose& p : system.atlas_trajectory())
    summary.atlas_trajectory.push_back(p.pose);
  summary.tracked = slam::tracked_share(summary.frame_states).tracked;
  summary.keyframes_trajectory = system.keyframe_trajectory();
  if (summary.trajectory.empty()) {
    const bool abandoned =
        std::any_of(summary.frame_states.begin(), summary.frame_states.end(),
                    [](const auto& f) { return f.state == slam::FrameState::kAbandoned; });
    // With a loaded map no frame initialises a map of its own: each must
    // relocalise in the loaded one (its place, vocabulary and camera).
    const std::string why =
        !o.load_map.empty() ? "no frame relocalised in the loaded map " + o.load_map +
                                  " (is it a map of this place, seen from these views?)"
        : abandoned ? "every map started was abandoned (lost within its first keyframes)"
                    : "tracking never initialised (too few keypoints with depth?)";
    fail(o.dataset, std::string(kNoFrameTracked) + ": " + why);
  }
  summary.keyframes = system.n_keyframes();
  summary.map_points = system.n_map_points();
  summary.median_ms = percentile(total, 0.5);
  summary.p95_ms = percentile(total, 0.95);
  summary.extract_ms = percentile(extract, 0.5);
  summary.track_ms = percentile(track, 0.5);
  summary.filter_ms = percentile(filter_ms, 0.5);
  summary.wait_ms = percentile(wait_ms, 0.5);
  summary.wait_p95_ms = percentile(wait_ms, 0.95);
  summary.detect_ms = percentile(detect_ms, 0.5);
  summary.flow_ms = percentile(flow_ms, 0.5);
  summary.ba_ms_total = system.mapping_stats().ba_ms;
  summary.lost_ms = relocalising.empty() ? 0 : percentile(relocalising, 0.5);
  summary.loops = system.loop_closures();
  summary.loops_refused = system.loops_refused();
  summary.global_adjustments = system.global_adjustments();
  summary.maps = system.maps();
  summary.merges_unconfirmed = system.merges_unconfirmed();
  summary.maps_rejoined = system.maps_rejoined();
  if (stats) stats->commit();
  if (keypoint_rows) keypoint_rows->commit();
  if (overlays) {
    overlay_index->close();
    if (!*overlay_index) fail(o.overlays, "cannot write index.txt");
    overlays->commit();
  }
  return summary;
}

}  // namespace depot::runner
