#include "sim/dataset/dataset_writer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/rng.h"
#include "common/tum_io.h"
#include "dataset/boxes.h"
#include "dataset/calibration.h"
#include "dataset/class_list.h"
#include "dataset/dataset_files.h"
#include "dataset/label_images.h"
#include "sim/dataset/boxes.h"
#include "sim/dataset/truth_files.h"
#include "sim/sensor/colour_pipeline.h"
#include "sim/sensor/depth_artefacts.h"
#include "sim/sensor/kinect_model.h"
#include "sim/world/sensed_frame.h"

namespace fs = std::filesystem;

namespace depot::sim {

using dataset::format_timestamp;

namespace {

const size_t kMaxQueued = 6;

}  // namespace

const OutputKind& simulator_output_kind() {
  // Every top-level entry a render can write (--overwrite replaces only these).
  static const OutputKind kind = [] {
    OutputKind k{"dataset", dataset::kInfoFile, {"rgb", "depth", dataset::kLabelFolder, "yolo"}};
    for (const char* file :
         {"boxes_yolo", "rgb.txt", "depth.txt", "associations.txt", "groundtruth.txt",
          "groundtruth_rows.txt", "classes.txt", "calibration.yaml", "scenario.yaml", "scene.yaml",
          "timestamps.txt", dataset::kLabelListFile, dataset::kObjectPosesFile, dataset::kBoxesFile,
          dataset::kObjectsFile, dataset::kInfoFile, dataset::kExposuresFile})
      k.entries.push_back(file);
    return k;
  }();
  return kind;
}

DatasetWriter::DatasetWriter(const DatasetOptions& options, const Scenario& scenario,
                             const ClassTable& classes, const std::vector<Instance>& instances)
    : options_(options), scenario_(scenario), classes_(classes), instances_(instances) {
  if (options_.writer_threads < 1 || options_.writer_threads > 32)
    fail("--writers", "writer threads must be 1..32");
  if (options_.png_compression < -1 || options_.png_compression > 9)
    fail("--png-level", "must be 0..9");
  dir_ = std::make_unique<StagedDirectory>(options_.output, simulator_output_kind(),
                                           options_.overwrite);
  for (const char* sub : {"rgb", "depth", dataset::kLabelFolder, "boxes_yolo"})
    fs::create_directory(fs::path(dir_->path()) / sub);
  const std::string header = dataset::file_header_line(scenario_.name);
  rgb_txt_ = "# color images\n" + header + "# timestamp filename\n";
  depth_txt_ = "# depth maps\n" + header + "# timestamp filename\n";
  gt_txt_ = "# ground truth trajectory (camera-to-world)\n" + header +
            "# timestamp tx ty tz qx qy qz qw\n";
  assoc_txt_.clear();
  for (int i = 0; i < options_.writer_threads; ++i) threads_.emplace_back([this] { worker(); });
}

DatasetWriter::~DatasetWriter() {
  {
    MutexLock lock(mutex_);
    closing_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

void DatasetWriter::rethrow_worker_error() {
  MutexLock lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void DatasetWriter::add(RenderedFrame frame, const FrameTruth& truth) {
  rethrow_worker_error();
  const std::string rs = format_timestamp(truth.rgb_timestamp);
  const std::string ds = format_timestamp(truth.depth_timestamp);
  rgb_txt_ += rs + " rgb/" + rs + ".png\n";
  depth_txt_ += ds + " depth/" + ds + ".png\n";
  assoc_txt_ += rs + " rgb/" + rs + ".png " + ds + " depth/" + ds + ".png\n";
  label_timestamps_.push_back(truth.rgb_timestamp);
  gt_txt_ += format_tum_pose({truth.rgb_timestamp, truth.camera}) + "\n";
  for (const RowPose& r : truth.rows)
    rows_txt_ +=
        rs + " " + std::to_string(r.row) + " " + format_tum_pose({r.time, r.camera}) + "\n";
  std::vector<bool> moving(instances_.size() + 1, false);
  for (const ObjectState& s : truth.objects) moving[s.id] = s.moving;
  for (dataset::ObjectPoseRecord& r : object_pose_records(truth))
    object_poses_.push_back(std::move(r));
  if (scenario_.sensor.forms_colour()) {
    const std::vector<float>& rows = truth.capture.row_light;
    exposures_.push_back({truth.rgb_timestamp, truth.capture.exposure, truth.capture.gain,
                          rows.empty() ? 1.0 : rows[rows.size() / 2]});
  }
  // Boxes are cheap: compute them here, in frame order.
  std::string yolo;
  for (const InstanceBox& b : instance_boxes(frame.instance, options_.min_box_pixels)) {
    const Instance& inst = instances_[b.id - 1];
    const int cls = classes_.yolo_index(inst.class_name);
    if (cls < 0) continue;
    boxes_.push_back({truth.rgb_timestamp, b.id, inst.class_name, b.x1, b.y1, b.x2, b.y2, b.pixels,
                      static_cast<bool>(moving[b.id])});
    yolo += yolo_line(cls, b, frame.instance.cols, frame.instance.rows) + "\n";
  }
  yolo_files_.emplace_back(rs, yolo);
  ++frames_;
  if (truth.covered) {
    if (!covered_frames_.empty() && covered_frames_.back().second == truth.index - 1)
      covered_frames_.back().second = truth.index;
    else
      covered_frames_.emplace_back(truth.index, truth.index);
  }

  Job job{std::move(frame), truth.rgb_timestamp, rs, ds, truth.index, truth.covered, truth.capture};
  MutexLock lock(mutex_);
  while (queue_.size() >= kMaxQueued && !error_) mutex_.wait(cv_);
  if (error_) std::rethrow_exception(error_);
  queue_.push_back(std::move(job));
  lock.unlock();
  cv_.notify_all();
}

void DatasetWriter::worker() {
  WriterTimings local;
  while (true) {
    Job job;
    {
      MutexLock lock(mutex_);
      while (!closing_ && queue_.empty()) mutex_.wait(cv_);
      if (queue_.empty()) break;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    cv_.notify_all();
    try {
      write_job(job, local);
    } catch (...) {
      MutexLock lock(mutex_);
      if (!error_) error_ = std::current_exception();
      cv_.notify_all();
    }
  }
  MutexLock lock(mutex_);
  totals_.sensor_ms += local.sensor_ms;
  totals_.encode_write_ms += local.encode_write_ms;
  totals_.bytes += local.bytes;
}

void DatasetWriter::write_job(Job& job, WriterTimings& timings) {
  auto t0 = std::chrono::steady_clock::now();
  const cv::Mat depth = sense_frame(job.frame, scenario_, job.capture, job.covered,
                                    sensor_seed(scenario_, job.index));
  cv::Mat depth16 = depth_to_u16(depth, scenario_.camera.depth_factor);
  auto t1 = std::chrono::steady_clock::now();
  const fs::path root = dir_->path();
  const int level = options_.png_compression;
  timings.bytes += write_png((root / "rgb" / (job.stamp_rgb + ".png")).string(), job.frame.bgr,
                             PngKind::kColor, level < 0 ? 0 : level);
  timings.bytes += write_png((root / "depth" / (job.stamp_depth + ".png")).string(), depth16,
                             PngKind::kDepth, level < 0 ? 1 : level);
  timings.bytes += dataset::write_label_image(root.string(), job.rgb_timestamp, job.frame.instance,
                                              level < 0 ? 1 : level);
  auto t2 = std::chrono::steady_clock::now();
  timings.sensor_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
  timings.encode_write_ms += std::chrono::duration<double, std::milli>(t2 - t1).count();
}

void DatasetWriter::write_text_files() {
  const fs::path root = dir_->path();
  auto write = [&](const char* name, const std::string& text) {
    write_text_file_atomic((root / name).string(), text);
  };
  write("rgb.txt", rgb_txt_);
  write("depth.txt", depth_txt_);
  write("associations.txt", assoc_txt_);
  write("groundtruth.txt", gt_txt_);
  if (!rows_txt_.empty())
    write("groundtruth_rows.txt",
          "# rolling shutter ground truth (camera-to-world)\n" +
              dataset::file_header_line(scenario_.name) +
              "# the camera when each sampled row was exposed (the middle of its exposure),\n"
              "# every eighth of the height; rows between: interpolate in time (not a TUM\n"
              "# trajectory: 11 columns). Timing: calibration.yaml's shutter block.\n"
              "# frame_timestamp row row_time tx ty tz qx qy qz qw\n" +
              rows_txt_);
  dataset::write_label_list(root.string(), scenario_.name, label_timestamps_);
  dataset::write_object_poses(root.string(), scenario_.name, object_poses_);
  if (!exposures_.empty()) dataset::write_exposures(root.string(), scenario_.name, exposures_);
  dataset::write_boxes(root.string(), scenario_.name, boxes_);
  dataset::write_dataset_classes(root.string(), classes_.yolo_names());
  for (const auto& [stamp, content] : yolo_files_)
    write_text_file_atomic((root / "boxes_yolo" / (stamp + ".txt")).string(), content);

  const CameraIntrinsics& c = scenario_.camera;
  const SensorSpec& s = scenario_.sensor;
  // The lens an ideal sensor drops (sim/world/simulated_sequence.cc).
  const LensDistortion l = s.ideal ? LensDistortion{} : s.lens;
  dataset::CameraCalibration camera;
  camera.width = c.width;
  camera.height = c.height;
  camera.fx = c.f;
  camera.fy = c.focal_y();
  camera.cx = c.cx;
  camera.cy = c.cy;
  camera.lens = l;
  camera.depth_factor = c.depth_factor;
  camera.depth_min = s.ideal ? 0.0 : s.min_depth;
  camera.depth_max = s.max_depth;
  camera.depth_model = s.ideal ? "ideal" : "kinect";
  camera.depth_baseline = s.baseline;
  std::string calibration = dataset::calibration_text(camera);
  if (!s.ideal && (s.exposure > 0 || s.readout > 0)) {
    // Only where set, so datasets of an instant global shutter stay as
    // they were. Rows: sim/sensor/shutter.h.
    std::ostringstream shutter;
    shutter << "# Colour shutter: the timestamp is the middle of the middle row's exposure;\n"
            << "# row y is exposed (y / (height - 1) - 0.5) x readout later. Depth, labels and\n"
            << "# groundtruth.txt belong to the timestamp; with a readout, groundtruth_rows.txt\n"
            << "# gives the camera at sampled rows' instants.\n"
            << "shutter:\n  exposure: " << s.exposure << "  # s\n  readout: " << s.readout
            << "  # s, first row to last\n"
            << "  motion_blur: " << s.motion_blur
            << "  # subframes: rendered at each instant; field: moved from one render\n";
    calibration += shutter.str();
  }
  const bool artefacts = s.flying_pixels > 0 || s.dark_dropout > 0 ||
                         s.misregistration.squaredNorm() > 0 || s.depth_offset != 0;
  if (!s.ideal && artefacts) {
    // The truth of what the simulated rig does wrong (a real rig's user
    // would not know these): sim/sensor/depth_artefacts.h.
    std::ostringstream block;
    block << "# Depth artefacts as simulated (truth, not a calibration):\n"
          << "depth_artefacts:\n  flying_pixels: " << s.flying_pixels
          << "\n  dark_dropout: " << s.dark_dropout << "\n  misregistration: ["
          << s.misregistration.x() << ", " << s.misregistration.y()
          << "]  # px, depth against colour\n  depth_offset: " << s.depth_offset
          << "  # s, depth stamp minus colour stamp; depth rendered at its own stamp\n";
    calibration += block.str();
  }
  if (s.forms_colour()) {
    // Sim/sensor/colour_pipeline.h; per frame: exposures.txt.
    const LightSpec& l = s.light;
    const ExposureControlSpec& e = s.exposure_control;
    const ColourPipelineSpec& c = s.colour;
    std::ostringstream block;
    block << "# Colour image formation as simulated (the render is the output at the reference\n"
          << "# exposure under light 1, sRGB-encoded; per-frame exposure, gain, light in\n"
          << "# exposures.txt):\ncolour:\n  light: " << l.level << "\n  light_events: [";
    for (size_t i = 0; i < l.events.size(); ++i)
      block << (i ? ", " : "") << "[" << l.events[i].x() << ", " << l.events[i].y() << "]";
    block << "]  # [s since the first frame, level]\n  flicker: " << l.flicker
          << "\n  mains: " << l.mains_hz
          << "  # Hz\n  auto_exposure: " << (e.automatic ? "true" : "false")
          << "\n  reference_exposure: " << s.exposure << "  # s\n  ae_target: " << e.target
          << "\n  ae_time_constant: " << e.time_constant
          << "  # s\n  max_exposure: " << e.max_exposure << "  # s\n  max_gain: " << e.max_gain
          << "\n  vignetting: " << c.vignetting << "  # relative illumination at the corners\n"
          << "  lens_blur: " << c.lens_blur
          << "  # px, Gaussian PSF sigma\n  demosaic: " << c.demosaic << "\n  bayer: " << c.bayer
          << "  # the mosaic's top-left 2x2\n  full_well: " << c.full_well
          << "  # e-, at gain 1 (0: additive rgb_noise)\n  read_noise: " << c.read_noise
          << "  # e-\n  jpeg_quality: " << c.jpeg_quality << "\n";
    calibration += block.str();
  }
  write("calibration.yaml", calibration);

  dataset::write_objects(root.string(), objects_file(scenario_.name, instances_, classes_));
  dataset::DatasetInfo info = scenario_info(scenario_, "depot-slam simulator");
  info.description = scenario_.description;
  info.frames = frames_;
  info.sensor = s.ideal ? "ideal" : "kinect";
  // Seconds as written, and the frames they cover (first and last index)
  // for evaluations of relocalisation after the cover.
  for (const CoverInterval& c : scenario_.camera_cover)
    info.camera_cover.emplace_back(c.start, c.end);
  for (const auto& [first, last] : covered_frames_) info.covered_frames.emplace_back(first, last);
  dataset::write_info(root.string(), info);
  std::ifstream src(scenario_.source_path, std::ios::binary);
  std::string yaml((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>());
  write("scenario.yaml", yaml);
  // A generated hall is written out: the scenario file holds only its
  // parameters, and this is the layout the seed drew.
  if (scenario_.procedural) write("scene.yaml", scene_layout_yaml(scenario_.layout));

  if (options_.yolo_export) {
    // A ready YOLO training set: images, label files and a data file.
    fs::create_directories(root / "yolo" / "images");
    fs::create_directories(root / "yolo" / "labels");
    for (const auto& [stamp, content] : yolo_files_) {
      std::error_code ec;
      fs::create_hard_link(root / "rgb" / (stamp + ".png"),
                           root / "yolo" / "images" / (stamp + ".png"), ec);
      if (ec)
        fs::copy_file(root / "rgb" / (stamp + ".png"), root / "yolo" / "images" / (stamp + ".png"));
      write_text_file_atomic((root / "yolo" / "labels" / (stamp + ".txt")).string(), content);
    }
    std::string data = "path: .\ntrain: images\nval: images\nnames:\n";
    int i = 0;
    for (const auto& n : classes_.yolo_names())
      data += "  " + std::to_string(i++) + ": " + n + "\n";
    write_text_file_atomic((root / "yolo" / "data.yaml").string(), data);
  }
}

WriterTimings DatasetWriter::finish() {
  {
    MutexLock lock(mutex_);
    closing_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_) t.join();
  threads_.clear();
  rethrow_worker_error();
  write_text_files();
  dir_->commit();
  MutexLock lock(mutex_);
  return totals_;
}

}  // namespace depot::sim
