#include "sim/dataset/dataset_writer.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "common/png_codec.h"
#include "common/rng.h"
#include "common/tum_io.h"
#include "sim/dataset/boxes.h"
#include "sim/dataset/truth_files.h"
#include "sim/sensor/kinect_model.h"

namespace fs = std::filesystem;

namespace depot::sim {

std::string format_timestamp(double t) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.6f", t);
  return buf;
}

namespace {

const size_t kMaxQueued = 6;

}  // namespace

const OutputKind& simulator_output_kind() {
  static const OutputKind kind{
      "dataset",
      "info.json",
      {"rgb", "depth", "labels", "boxes_yolo", "yolo", "rgb.txt", "depth.txt", "associations.txt",
       "groundtruth.txt", "labels.txt", "object_poses.txt", "boxes.txt", "classes.txt",
       "calibration.yaml", "objects.json", "info.json", "scenario.yaml", "timestamps.txt"}};
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
  for (const char* sub : {"rgb", "depth", "labels", "boxes_yolo"})
    fs::create_directory(fs::path(dir_->path()) / sub);
  const std::string header = "# file: '" + scenario_.name + "' (depot-slam simulator)\n";
  rgb_txt_ = "# color images\n" + header + "# timestamp filename\n";
  depth_txt_ = "# depth maps\n" + header + "# timestamp filename\n";
  labels_txt_ = "# instance label images (16-bit instance ids, 0 = none)\n" + header +
                "# timestamp filename\n";
  gt_txt_ = "# ground truth trajectory (camera-to-world)\n" + header +
            "# timestamp tx ty tz qx qy qz qw\n";
  assoc_txt_.clear();
  poses_txt_ = object_poses_header() + header + "# timestamp id tx ty tz qx qy qz qw moving\n";
  boxes_txt_ = "# ground-truth boxes of visible detectable instances, pixels, x2/y2 exclusive\n" +
               header + "# timestamp id class x1 y1 x2 y2 visible_pixels moving\n";
  for (int i = 0; i < options_.writer_threads; ++i) threads_.emplace_back([this] { worker(); });
}

DatasetWriter::~DatasetWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

void DatasetWriter::rethrow_worker_error() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void DatasetWriter::add(RenderedFrame frame, const FrameTruth& truth) {
  rethrow_worker_error();
  const std::string rs = format_timestamp(truth.rgb_timestamp);
  const std::string ds = format_timestamp(truth.depth_timestamp);
  rgb_txt_ += rs + " rgb/" + rs + ".png\n";
  depth_txt_ += ds + " depth/" + ds + ".png\n";
  assoc_txt_ += rs + " rgb/" + rs + ".png " + ds + " depth/" + ds + ".png\n";
  labels_txt_ += rs + " labels/" + rs + ".png\n";
  gt_txt_ += format_tum_pose({truth.rgb_timestamp, truth.camera}) + "\n";
  std::vector<bool> moving(instances_.size() + 1, false);
  for (const ObjectState& s : truth.objects) moving[s.id] = s.moving;
  poses_txt_ += object_pose_lines(truth);
  // Boxes are cheap: compute them here, in frame order.
  std::string yolo;
  for (const InstanceBox& b : instance_boxes(frame.instance, options_.min_box_pixels)) {
    const Instance& inst = instances_[b.id - 1];
    const int cls = classes_.yolo_index(inst.class_name);
    if (cls < 0) continue;
    char buf[256];
    std::snprintf(buf, sizeof(buf), "%s %u %s %d %d %d %d %d %d\n", rs.c_str(), b.id,
                  inst.class_name.c_str(), b.x1, b.y1, b.x2, b.y2, b.pixels, moving[b.id] ? 1 : 0);
    boxes_txt_ += buf;
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

  Job job{std::move(frame), rs, ds, truth.index, truth.covered};
  std::unique_lock<std::mutex> lock(mutex_);
  cv_.wait(lock, [&] { return queue_.size() < kMaxQueued || error_; });
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
      std::unique_lock<std::mutex> lock(mutex_);
      cv_.wait(lock, [&] { return closing_ || !queue_.empty(); });
      if (queue_.empty()) break;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    cv_.notify_all();
    try {
      write_job(job, local);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
      cv_.notify_all();
    }
  }
  std::lock_guard<std::mutex> lock(mutex_);
  totals_.sensor_ms += local.sensor_ms;
  totals_.encode_write_ms += local.encode_write_ms;
  totals_.bytes += local.bytes;
}

void DatasetWriter::write_job(Job& job, WriterTimings& timings) {
  auto t0 = std::chrono::steady_clock::now();
  const SensorSpec& sensor = scenario_.sensor;
  const uint64_t seed = derive_seed(scenario_.seed, 0x5e9, static_cast<uint64_t>(job.index));
  cv::Mat depth = job.frame.depth;
  // A covered camera sees exactly nothing: black and no depth, not noise.
  if (!sensor.ideal && !job.covered) {
    depth = apply_depth_model(job.frame.depth, sensor, scenario_.camera.f, seed);
    apply_rgb_noise(job.frame.bgr, sensor.rgb_noise, derive_seed(seed, 1));
  }
  cv::Mat depth16 = depth_to_u16(depth, scenario_.camera.depth_factor);
  auto t1 = std::chrono::steady_clock::now();
  const fs::path root = dir_->path();
  const int level = options_.png_compression;
  timings.bytes += write_png((root / "rgb" / (job.stamp_rgb + ".png")).string(), job.frame.bgr,
                             PngKind::kColor, level < 0 ? 0 : level);
  timings.bytes += write_png((root / "depth" / (job.stamp_depth + ".png")).string(), depth16,
                             PngKind::kDepth, level < 0 ? 1 : level);
  timings.bytes += write_png((root / "labels" / (job.stamp_rgb + ".png")).string(),
                             job.frame.instance, PngKind::kLabels, level < 0 ? 1 : level);
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
  write("labels.txt", labels_txt_);
  write("object_poses.txt", poses_txt_);
  write("boxes.txt", boxes_txt_);
  std::string classes_txt;
  for (const auto& n : classes_.yolo_names()) classes_txt += n + "\n";
  write("classes.txt", classes_txt);
  for (const auto& [stamp, content] : yolo_files_)
    write_text_file_atomic((root / "boxes_yolo" / (stamp + ".txt")).string(), content);

  const CameraIntrinsics& c = scenario_.camera;
  const SensorSpec& s = scenario_.sensor;
  char calib[1024];
  std::snprintf(
      calib, sizeof(calib),
      "# Pinhole intrinsics of the rendered images (no distortion).\n"
      "camera:\n  model: pinhole\n  width: %d\n  height: %d\n  fx: %.6f\n  fy: %.6f\n  cx: %.6f\n"
      "  cy: %.6f\n  k1: 0.0\n  k2: 0.0\n  p1: 0.0\n  p2: 0.0\n  k3: 0.0\n"
      "depth:\n  factor: %.1f  # PNG value per metre\n  min: %.3f\n  max: %.3f\n  model: %s\n"
      "  baseline: %.4f\n",
      c.width, c.height, c.f, c.f, c.cx, c.cy, c.depth_factor, s.ideal ? 0.0 : s.min_depth,
      s.max_depth, s.ideal ? "ideal" : "kinect", s.baseline);
  write("calibration.yaml", calib);

  write("objects.json", objects_json(scenario_.name, instances_, classes_));
  nlohmann::json info = {{"generator", "depot-slam simulator"},
                         {"scenario", scenario_.name},
                         {"description", scenario_.description},
                         {"seed", scenario_.seed},
                         {"frames", frames_},
                         {"dynamic_load", scenario_.dynamic_load},
                         {"actors_style", scenario_.actors_style},
                         {"props_style", scenario_.props_style},
                         {"sensor", s.ideal ? "ideal" : "kinect"},
                         {"motion", scenario_.motion.type}};
  info["world_seed"] = scenario_.world_seed();
  if (!scenario_.camera_cover.empty()) {
    // Seconds as written, and the frames they cover (first and last index)
    // for evaluations of relocalisation after the cover.
    nlohmann::json seconds = nlohmann::json::array(), frames = nlohmann::json::array();
    for (const CoverInterval& c : scenario_.camera_cover) seconds.push_back({c.start, c.end});
    for (const auto& [first, last] : covered_frames_) frames.push_back({first, last});
    info["camera_cover"] = seconds;
    info["covered_frames"] = frames;
  }
  write("info.json", info.dump(1) + "\n");
  std::ifstream src(scenario_.source_path, std::ios::binary);
  std::string yaml((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>());
  write("scenario.yaml", yaml);

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
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  cv_.notify_all();
  for (auto& t : threads_) t.join();
  threads_.clear();
  rethrow_worker_error();
  write_text_files();
  dir_->commit();
  return totals_;
}

}  // namespace depot::sim
