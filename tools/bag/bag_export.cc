#include "tools/bag/bag_export.h"

#include <filesystem>
#include <map>

#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/progress.h"
#include "common/tum_io.h"
#include "dataset/boxes.h"
#include "dataset/dataset_files.h"
#include "dataset/label_images.h"
#include "dataset/object_poses.h"
#include "dataset/ros2/bag_layout.h"
#include "dataset/ros2/messages.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"

namespace fs = std::filesystem;

namespace depot::bag {

namespace {

ros2::Header header_at(double seconds, const std::string& frame) {
  return {ros2::time_of(mcap::nanoseconds_of(seconds)), frame};
}

ros2::Image image_message(const cv::Mat& m, const std::string& encoding, double t,
                          const std::string& frame) {
  ros2::Image im;
  im.header = header_at(t, frame);
  im.height = static_cast<uint32_t>(m.rows);
  im.width = static_cast<uint32_t>(m.cols);
  im.encoding = encoding;
  im.step = static_cast<uint32_t>(m.cols * m.elemSize());
  const cv::Mat dense = m.isContinuous() ? m : m.clone();
  im.data.assign(reinterpret_cast<const char*>(dense.data), dense.total() * dense.elemSize());
  return im;
}

ros2::CameraInfo camera_info(const slam::PinholeCamera& c, double t, const std::string& frame) {
  ros2::CameraInfo info;
  info.header = header_at(t, frame);
  info.width = static_cast<uint32_t>(c.width);
  info.height = static_cast<uint32_t>(c.height);
  info.d = {c.lens.k1, c.lens.k2, c.lens.p1, c.lens.p2, c.lens.k3};
  info.k = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  info.r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.p = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  return info;
}

ros2::TransformStamped transform(double t, const std::string& parent, const std::string& child,
                                 const Pose& pose) {
  ros2::TransformStamped tf;
  tf.header = header_at(t, parent);
  tf.child_frame_id = child;
  tf.translation = pose.translation();
  tf.rotation = Eigen::Quaterniond(pose.rotation());
  return tf;
}

uint64_t folder_bytes(const std::string& folder) {
  uint64_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(folder, ec))
    if (e.is_regular_file(ec)) n += e.file_size(ec);
  return n;
}

// One channel per topic, its schema added once.
class Channels {
 public:
  explicit Channels(mcap::Writer& w) : w_(w) {}
  uint16_t operator()(const std::string& topic, const ros2::MessageType& type) {
    auto s = schemas_.find(type.name);
    if (s == schemas_.end())
      s = schemas_.emplace(type.name, w_.add_schema(type.name, "ros2msg", type.definition)).first;
    topics_.push_back(topic);
    return w_.add_channel(s->second, topic, "cdr");
  }
  const std::vector<std::string>& topics() const { return topics_; }

 private:
  mcap::Writer& w_;
  std::map<std::string, uint16_t> schemas_;
  std::vector<std::string> topics_;
};

}  // namespace

BagExportReport export_bag(const std::string& dataset, const std::string& bag_path,
                           const BagExportOptions& options) {
  BagExportReport report;
  slam::TumSequence sequence(dataset);
  slam::SlamSettings settings;
  if (!sequence.calibration_path().empty())
    settings = slam::load_settings(sequence.calibration_path(), settings);
  sequence.set_depth_factor(settings.camera.depth_factor);
  const slam::PinholeCamera& camera = settings.camera;

  // The truth the folder has, read (and checked) before the bag is begun.
  const std::string truth_path = (fs::path(dataset) / "groundtruth.txt").string();
  const std::vector<StampedPose> truth = fs::is_regular_file(truth_path)
                                             ? read_tum_trajectory(truth_path)
                                             : std::vector<StampedPose>{};
  std::map<std::string, std::string> labels;  // timestamp text -> image
  if (dataset::has_label_list(dataset))
    for (const StampedFile& f : dataset::read_label_list(dataset))
      labels[dataset::format_timestamp(f.timestamp)] = f.path;
  std::map<std::string, std::vector<dataset::BoxRecord>> boxes;
  const bool has_boxes = dataset::has_boxes(dataset);
  if (has_boxes)
    for (dataset::BoxRecord& b : dataset::read_boxes(dataset))
      boxes[dataset::format_timestamp(b.timestamp)].push_back(std::move(b));
  std::map<std::string, std::vector<dataset::ObjectPoseRecord>> objects;
  const std::string objects_path = dataset::dataset_file(dataset, dataset::kObjectPosesFile);
  if (fs::is_regular_file(objects_path))
    for (dataset::ObjectPoseRecord& o : dataset::read_object_poses(dataset))
      objects[dataset::format_timestamp(o.timestamp)].push_back(o);

  mcap::Writer writer(bag_path, {options.compression});
  Channels channel(writer);
  const uint16_t colour = channel(ros2::kColourTopic, ros2::image_type());
  const uint16_t colour_info = channel(ros2::kColourInfoTopic, ros2::camera_info_type());
  const uint16_t depth = channel(ros2::kDepthTopic, ros2::image_type());
  const uint16_t depth_info = channel(ros2::kDepthInfoTopic, ros2::camera_info_type());
  const uint16_t tf_static = channel(ros2::kTfStaticTopic, ros2::tf_message_type());
  const uint16_t tf = truth.empty() ? 0 : channel(ros2::kTfTopic, ros2::tf_message_type());
  const uint16_t truth_pose =
      truth.empty() ? 0 : channel(ros2::kTruthPoseTopic, ros2::pose_stamped_type());
  const uint16_t truth_path_channel =
      truth.empty() ? 0 : channel(ros2::kTruthPathTopic, ros2::path_type());
  const uint16_t label_channel =
      labels.empty() ? 0 : channel(ros2::kLabelsTopic, ros2::image_type());
  const uint16_t box_channel =
      has_boxes ? channel(ros2::kBoxesTopic, ros2::detection_array_type()) : 0;
  const uint16_t object_channel =
      objects.empty() ? 0 : channel(ros2::kObjectsTopic, ros2::tf_message_type());
  const auto put = [&writer](uint16_t ch, double t, const std::string& cdr) {
    const uint64_t ns = mcap::nanoseconds_of(t);
    writer.write(ch, ns, ns, cdr);
  };

  const double t0 = sequence.size() ? sequence.timestamp(0) : 0.0;
  ros2::TFMessage statics;
  statics.transforms = {
      transform(t0, ros2::kTruthCameraFrame, ros2::kColourFrame, Pose::Identity()),
      transform(t0, ros2::kTruthCameraFrame, ros2::kDepthFrame, Pose::Identity())};
  put(tf_static, t0, ros2::encode(statics));

  Progress progress("export mcap", sequence.size(), options.progress);
  size_t next_truth = 0;
  ros2::Path path;
  path.header = header_at(truth.empty() ? t0 : truth.back().timestamp, ros2::kWorldFrame);
  const auto put_truth_until = [&](double t) {
    for (; next_truth < truth.size() && truth[next_truth].timestamp <= t; ++next_truth) {
      const StampedPose& p = truth[next_truth];
      ros2::TFMessage m;
      m.transforms = {transform(p.timestamp, ros2::kWorldFrame, ros2::kTruthCameraFrame, p.pose)};
      put(tf, p.timestamp, ros2::encode(m));
      ros2::PoseStamped pose;
      pose.header = header_at(p.timestamp, ros2::kWorldFrame);
      pose.position = p.pose.translation();
      pose.orientation = Eigen::Quaterniond(p.pose.rotation());
      put(truth_pose, p.timestamp, ros2::encode(pose));
      path.poses.push_back(pose);
    }
  };
  cv::Mat bgr, depth_m, rgb;
  for (size_t i = 0; i < sequence.size(); ++i) {
    const Association& a = sequence.entry(i);
    put_truth_until(a.rgb_timestamp);
    sequence.load(i, bgr, depth_m);
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    put(colour, a.rgb_timestamp,
        ros2::encode(image_message(rgb, "rgb8", a.rgb_timestamp, ros2::kColourFrame)));
    put(colour_info, a.rgb_timestamp,
        ros2::encode(camera_info(camera, a.rgb_timestamp, ros2::kColourFrame)));
    put(depth, a.depth_timestamp,
        ros2::encode(image_message(depth_m, "32FC1", a.depth_timestamp, ros2::kDepthFrame)));
    put(depth_info, a.depth_timestamp,
        ros2::encode(camera_info(camera, a.depth_timestamp, ros2::kDepthFrame)));
    const std::string key = dataset::format_timestamp(a.rgb_timestamp);
    if (const auto l = labels.find(key); l != labels.end())
      put(label_channel, a.rgb_timestamp,
          ros2::encode(image_message(dataset::read_label_image(dataset, l->second), "16UC1",
                                     a.rgb_timestamp, ros2::kColourFrame)));
    if (box_channel) {
      ros2::Detection2DArray m;
      m.header = header_at(a.rgb_timestamp, ros2::kColourFrame);
      if (const auto b = boxes.find(key); b != boxes.end())
        for (const dataset::BoxRecord& r : b->second)
          m.detections.push_back(
              {m.header, r.class_name, static_cast<double>(r.visible_pixels) / r.area(),
               0.5 * (r.x1 + r.x2), 0.5 * (r.y1 + r.y2), static_cast<double>(r.x2 - r.x1),
               static_cast<double>(r.y2 - r.y1),
               std::to_string(r.id) + (r.moving ? " moving" : "")});
      put(box_channel, a.rgb_timestamp, ros2::encode(m));
    }
    if (const auto o = objects.find(key); o != objects.end()) {
      ros2::TFMessage m;
      for (const dataset::ObjectPoseRecord& r : o->second)
        m.transforms.push_back(transform(a.rgb_timestamp, ros2::kWorldFrame,
                                         "depot_object_" + std::to_string(r.id), r.pose));
      put(object_channel, a.rgb_timestamp, ros2::encode(m));
    }
    progress.update(i + 1);
  }
  put_truth_until(truth.empty() ? 0.0 : truth.back().timestamp);
  if (truth_path_channel) put(truth_path_channel, truth.back().timestamp, ros2::encode(path));
  writer.close();
  progress.finish();
  report.frames = sequence.size();
  report.totals = writer.totals();
  report.folder_bytes = folder_bytes(dataset);
  report.seconds = progress.elapsed_seconds();
  report.topics = channel.topics();
  return report;
}

}  // namespace depot::bag
