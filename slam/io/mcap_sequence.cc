#include "slam/io/mcap_sequence.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/tum_association.h"
#include "dataset/mcap/mcap_records.h"
#include "dataset/ros2/messages.h"
#include "slam/io/tum_sequence.h"

namespace depot::slam {

namespace {

// The channel on `topic` with the message type `type`: a missing topic or
// one of another type or encoding is one error naming it.
uint16_t channel_of(const mcap::Reader& reader, const std::string& topic, const std::string& type,
                    const std::string& what) {
  const mcap::Channel* c = reader.channel(topic);
  if (!c) {
    std::string topics;
    for (const auto& [id, other] : reader.channels())
      topics += (topics.empty() ? "" : ", ") + other.topic;
    fail(reader.path(), "no " + what + " topic " + topic +
                            " (the bag has: " + (topics.empty() ? "no topics" : topics) +
                            "; name it with --" + what + "-topic)");
  }
  const auto schema = reader.schemas().find(c->schema_id);
  const std::string schema_name = schema == reader.schemas().end() ? "" : schema->second.name;
  const std::string encoding = schema == reader.schemas().end() ? "" : schema->second.encoding;
  if (c->message_encoding != "cdr")
    fail(reader.path(),
         topic + ": messages are '" + c->message_encoding + "', not ROS 2 CDR ('cdr')");
  if (schema_name != type && schema_name != ros2::without_msg(type))
    fail(reader.path(), topic + ": messages are '" + schema_name + "', not " + type);
  if (encoding != "ros2msg" && encoding != "ros2idl")
    fail(reader.path(),
         topic + ": unknown schema encoding '" + encoding + "' (known: ros2msg, ros2idl)");
  return c->id;
}

cv::Mat image_matrix(const ros2::Image& m, int type, size_t pixel_bytes, const std::string& where) {
  if (m.is_bigendian) fail(where, "big-endian image data is not supported");
  if (m.width == 0 || m.height == 0) fail(where, "empty image");
  if (m.step < m.width * pixel_bytes || m.data.size() < size_t(m.step) * m.height)
    fail(where,
         fmt::format("{}x{} {} image needs {} bytes, the message has {} (step {})", m.width,
                     m.height, m.encoding, size_t(m.step) * m.height, m.data.size(), m.step));
  return cv::Mat(static_cast<int>(m.height), static_cast<int>(m.width), type,
                 const_cast<char*>(m.data.data()), m.step);
}

}  // namespace

McapSequence::McapSequence(const std::string& path, BagTopics topics)
    : path_(path), topics_(std::move(topics)), reader_(std::make_unique<mcap::Reader>(path)) {
  if (topics_.colour.empty()) topics_.colour = ros2::kColourTopic;
  if (topics_.depth.empty()) topics_.depth = ros2::kDepthTopic;
  if (topics_.colour_info.empty()) topics_.colour_info = ros2::kColourInfoTopic;
  const uint16_t colour = channel_of(*reader_, topics_.colour, ros2::image_type().name, "colour");
  const uint16_t depth = channel_of(*reader_, topics_.depth, ros2::image_type().name, "depth");
  const mcap::Channel* info = reader_->channel(topics_.colour_info);
  const uint16_t info_id =
      info ? channel_of(*reader_, topics_.colour_info, ros2::camera_info_type().name, "camera-info")
           : 0;
  // Stamps from the images' headers (a recorder's log time is when the
  // message arrived, not when the camera saw it).
  std::vector<std::pair<double, mcap::MessageRef>> colours, depths;
  for (const mcap::MessageRef& ref : reader_->messages()) {
    if (ref.channel_id == info_id && !camera_info_) camera_info_ = ref;
    if (ref.channel_id != colour && ref.channel_id != depth) continue;
    const mcap::Message m = reader_->read(ref);
    const std::string where = path_ + " (" + reader_->channels().at(ref.channel_id).topic + ")";
    const ros2::Time stamp = ros2::header_stamp(m.data, where);
    (ref.channel_id == colour ? colours : depths)
        .emplace_back(mcap::seconds_of(ros2::nanoseconds_of(stamp)), ref);
  }
  if (colours.empty()) fail(path_, "no message on the colour topic " + topics_.colour);
  if (depths.empty()) fail(path_, "no message on the depth topic " + topics_.depth);
  const auto by_time = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::stable_sort(colours.begin(), colours.end(), by_time);
  std::stable_sort(depths.begin(), depths.end(), by_time);
  std::vector<double> colour_t, depth_t;
  for (const auto& c : colours) colour_t.push_back(c.first);
  for (const auto& d : depths) depth_t.push_back(d.first);
  for (const TimestampMatch& m : associate(colour_t, depth_t))
    frames_.push_back({colours[m.reference_index].first, colours[m.reference_index].second,
                       depths[m.estimate_index].second});
  if (frames_.empty())
    fail(path_, fmt::format("colour and depth are not synchronised: no colour image has a depth "
                            "image within {} s (colour {:.6f}-{:.6f}, depth {:.6f}-{:.6f})",
                            ros2::kMaxColourDepthGap, colour_t.front(), colour_t.back(),
                            depth_t.front(), depth_t.back()));
}

std::string McapSequence::colour_location(size_t i) const {
  return fmt::format("{} {} at {:.6f}", path_, topics_.colour, frames_.at(i).timestamp);
}

void McapSequence::load(size_t i, cv::Mat& bgr, cv::Mat& depth_metres) const {
  const Frame& f = frames_.at(i);
  const std::string colour_where = colour_location(i);
  const ros2::Image colour = ros2::decode_image(reader_->read(f.colour).data, colour_where);
  if (colour.encoding == "rgb8")
    cv::cvtColor(image_matrix(colour, CV_8UC3, 3, colour_where), bgr, cv::COLOR_RGB2BGR);
  else if (colour.encoding == "bgr8")
    image_matrix(colour, CV_8UC3, 3, colour_where).copyTo(bgr);
  else if (colour.encoding == "mono8")
    cv::cvtColor(image_matrix(colour, CV_8UC1, 1, colour_where), bgr, cv::COLOR_GRAY2BGR);
  else
    fail(colour_where,
         "unknown colour encoding '" + colour.encoding + "' (known: rgb8, bgr8, mono8)");
  const std::string depth_where = fmt::format("{} {} at {:.6f}", path_, topics_.depth, f.timestamp);
  const ros2::Image depth = ros2::decode_image(reader_->read(f.depth).data, depth_where);
  if (depth.encoding == "32FC1")
    image_matrix(depth, CV_32FC1, 4, depth_where).copyTo(depth_metres);
  else if (depth.encoding == "16UC1" || depth.encoding == "mono16")
    image_matrix(depth, CV_16UC1, 2, depth_where).convertTo(depth_metres, CV_32F, 1.0 / 1000.0);
  else
    fail(depth_where, "unknown depth encoding '" + depth.encoding +
                          "' (known: 16UC1 and mono16 in mm, 32FC1 in m)");
  if (depth_metres.size() != bgr.size())
    fail(depth_where, fmt::format("depth is {}x{}, colour {}x{}", depth_metres.cols,
                                  depth_metres.rows, bgr.cols, bgr.rows));
}

std::optional<dataset::CameraCalibration> McapSequence::recorded_camera(
    const dataset::CameraCalibration& defaults) const {
  if (!camera_info_) return std::nullopt;
  const std::string where = path_ + " (" + topics_.colour_info + ")";
  const ros2::CameraInfo info = ros2::decode_camera_info(reader_->read(*camera_info_).data, where);
  LensCoefficients lens;
  if (!info.d.empty()) {
    if (info.distortion_model != "plumb_bob" && info.distortion_model != "rational_polynomial")
      fail(where, "unknown distortion model '" + info.distortion_model + "' (known: plumb_bob)");
    const auto d = [&](size_t k) { return k < info.d.size() ? info.d[k] : 0.0; };
    if (info.distortion_model == "rational_polynomial" && (d(5) != 0 || d(6) != 0 || d(7) != 0))
      fail(where, "rational_polynomial distortion with k4-k6 is not supported");
    lens = {d(0), d(1), d(2), d(3), d(4)};
  }
  return dataset::calibration_of_intrinsics(defaults, static_cast<int>(info.width),
                                            static_cast<int>(info.height), info.k[0], info.k[4],
                                            info.k[2], info.k[5], lens, where);
}

std::unique_ptr<RgbdSequence> open_sequence(const std::string& path, const BagTopics& topics) {
  if (path.size() > 5 && path.compare(path.size() - 5, 5, ".mcap") == 0)
    return std::make_unique<McapSequence>(path, topics);
  return std::make_unique<TumSequence>(path);
}

}  // namespace depot::slam
