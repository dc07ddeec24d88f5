#pragma once
// The ROS 2 messages a depot bag carries, as plain structs, with their
// ros2msg definitions (each with the definitions it depends on, as rosbag2
// stores them, so a reader decodes them without ROS installed) and their CDR
// encoding and decoding. Field names and order are the ROS 2 Humble ones.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace depot::ros2 {

// A message type's name as MCAP's schema names it and its ros2msg text.
struct MessageType {
  std::string name;
  std::string definition;
};

struct Time {
  int32_t sec = 0;
  uint32_t nanosec = 0;
};
// Nanoseconds since the epoch and back.
Time time_of(uint64_t nanoseconds);
uint64_t nanoseconds_of(Time t);

struct Header {
  Time stamp;
  std::string frame_id;
};

// sensor_msgs/msg/Image: `data` holds `height` rows of `step` bytes.
struct Image {
  Header header;
  uint32_t height = 0, width = 0;
  std::string encoding;  // rgb8, bgr8, 16UC1, 32FC1, mono16 (REP 118 / sensor_msgs)
  uint8_t is_bigendian = 0;
  uint32_t step = 0;
  std::string data;
};

// sensor_msgs/msg/CameraInfo (distortion "plumb_bob": k1 k2 p1 p2 k3).
struct CameraInfo {
  Header header;
  uint32_t height = 0, width = 0;
  std::string distortion_model = "plumb_bob";
  std::vector<double> d;
  std::array<double, 9> k{};
  std::array<double, 9> r{};
  std::array<double, 12> p{};
  uint32_t binning_x = 0, binning_y = 0;
  // roi: all zero (the full image).
};

// geometry_msgs/msg/TransformStamped: the pose of `child_frame_id` in
// header.frame_id.
struct TransformStamped {
  Header header;
  std::string child_frame_id;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};
// tf2_msgs/msg/TFMessage.
struct TFMessage {
  std::vector<TransformStamped> transforms;
};

// geometry_msgs/msg/PoseStamped.
struct PoseStamped {
  Header header;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};
// nav_msgs/msg/Path.
struct Path {
  Header header;
  std::vector<PoseStamped> poses;
};

// vision_msgs/msg/Detection2D (vision_msgs 4, Humble) with one hypothesis:
// an axis-aligned box (centre and size in pixels), its class and score, and
// `id` (the tracking id: here the instance id).
struct Detection2D {
  Header header;
  std::string class_id;
  double score = 1.0;
  double centre_x = 0, centre_y = 0, size_x = 0, size_y = 0;
  std::string id;
};
// vision_msgs/msg/Detection2DArray.
struct Detection2DArray {
  Header header;
  std::vector<Detection2D> detections;
};

const MessageType& image_type();
const MessageType& camera_info_type();
const MessageType& tf_message_type();
const MessageType& pose_stamped_type();
const MessageType& path_type();
const MessageType& detection_array_type();

std::string encode(const Image& m);
std::string encode(const CameraInfo& m);
std::string encode(const TFMessage& m);
std::string encode(const PoseStamped& m);
std::string encode(const Path& m);
std::string encode(const Detection2DArray& m);

// "sensor_msgs/Image" for "sensor_msgs/msg/Image": ROS 1 style, as some
// writers name ROS 2 schemas.
std::string without_msg(const std::string& type);
// The header stamp of a message that opens with a std_msgs/Header (Image,
// CameraInfo, PoseStamped, ...), read without decoding the rest.
Time header_stamp(const std::string& cdr, const std::string& where);

// Each throws depot::Error "<where>: ..." for a message that does not parse.
Image decode_image(const std::string& cdr, const std::string& where);
CameraInfo decode_camera_info(const std::string& cdr, const std::string& where);
TFMessage decode_tf_message(const std::string& cdr, const std::string& where);
PoseStamped decode_pose_stamped(const std::string& cdr, const std::string& where);

}  // namespace depot::ros2
