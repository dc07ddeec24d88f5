#include "dataset/ros2/messages.h"

#include "dataset/ros2/cdr.h"

namespace depot::ros2 {

namespace {

// rosbag2's layout: the type's own text, then each type it uses after a
// line of 80 '=' and "MSG: package/Type".
std::string with_dependencies(const std::string& own, const std::vector<std::string>& names) {
  static const char* const kTime = "int32 sec\nuint32 nanosec\n";
  static const char* const kHeader = "builtin_interfaces/Time stamp\nstring frame_id\n";
  static const char* const kVector3 = "float64 x\nfloat64 y\nfloat64 z\n";
  static const char* const kQuaternion = "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n";
  static const char* const kPose =
      "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n";
  struct Known {
    const char* name;
    const char* text;
  };
  static const Known kKnown[] = {
      {"std_msgs/Header", kHeader},
      {"builtin_interfaces/Time", kTime},
      {"sensor_msgs/RegionOfInterest",
       "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
      {"geometry_msgs/Transform",
       "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
      {"geometry_msgs/Vector3", kVector3},
      {"geometry_msgs/Point", kVector3},
      {"geometry_msgs/Quaternion", kQuaternion},
      {"geometry_msgs/Pose", kPose},
      {"geometry_msgs/PoseStamped", "std_msgs/Header header\ngeometry_msgs/Pose pose\n"},
      {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
      {"vision_msgs/Detection2D",
       "std_msgs/Header header\nvision_msgs/ObjectHypothesisWithPose[] results\n"
       "vision_msgs/BoundingBox2D bbox\nstring id\n"},
      {"vision_msgs/ObjectHypothesisWithPose",
       "vision_msgs/ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n"},
      {"vision_msgs/ObjectHypothesis", "string class_id\nfloat64 score\n"},
      {"vision_msgs/BoundingBox2D", "vision_msgs/Pose2D center\nfloat64 size_x\nfloat64 size_y\n"},
      {"vision_msgs/Pose2D", "vision_msgs/Point2D position\nfloat64 theta\n"},
      {"vision_msgs/Point2D", "float64 x\nfloat64 y\n"},
  };
  std::string text = own;
  for (const std::string& name : names)
    for (const Known& k : kKnown)
      if (name == k.name) text += std::string(80, '=') + "\nMSG: " + k.name + "\n" + k.text;
  return text;
}

void put(CdrWriter& w, const Time& t) {
  w.i32(t.sec);
  w.u32(t.nanosec);
}
void put(CdrWriter& w, const Header& h) {
  put(w, h.stamp);
  w.string(h.frame_id);
}
void put(CdrWriter& w, const Eigen::Vector3d& v) {
  w.f64(v.x());
  w.f64(v.y());
  w.f64(v.z());
}
void put(CdrWriter& w, const Eigen::Quaterniond& q) {
  w.f64(q.x());
  w.f64(q.y());
  w.f64(q.z());
  w.f64(q.w());
}
void put(CdrWriter& w, const PoseStamped& p) {
  put(w, p.header);
  put(w, p.position);
  put(w, p.orientation);
}

Header take_header(CdrReader& r) {
  Header h;
  h.stamp.sec = r.i32();
  h.stamp.nanosec = r.u32();
  h.frame_id = r.string();
  return h;
}
Eigen::Vector3d take_vector(CdrReader& r) {
  const double x = r.f64(), y = r.f64();
  return {x, y, r.f64()};
}
Eigen::Quaterniond take_quaternion(CdrReader& r) {
  const double x = r.f64(), y = r.f64(), z = r.f64();
  return {r.f64(), x, y, z};  // Eigen's constructor takes w first
}

}  // namespace

Time time_of(uint64_t nanoseconds) {
  return {static_cast<int32_t>(nanoseconds / 1000000000u),
          static_cast<uint32_t>(nanoseconds % 1000000000u)};
}

uint64_t nanoseconds_of(Time t) {
  return static_cast<uint64_t>(t.sec) * 1000000000u + t.nanosec;
}

const MessageType& image_type() {
  static const MessageType t{
      "sensor_msgs/msg/Image",
      with_dependencies("std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\n"
                        "uint8 is_bigendian\nuint32 step\nuint8[] data\n",
                        {"std_msgs/Header", "builtin_interfaces/Time"})};
  return t;
}

const MessageType& camera_info_type() {
  static const MessageType t{
      "sensor_msgs/msg/CameraInfo",
      with_dependencies(
          "std_msgs/Header header\nuint32 height\nuint32 width\n"
          "string distortion_model\nfloat64[] d\nfloat64[9] k\nfloat64[9] r\n"
          "float64[12] p\nuint32 binning_x\nuint32 binning_y\n"
          "sensor_msgs/RegionOfInterest roi\n",
          {"std_msgs/Header", "builtin_interfaces/Time", "sensor_msgs/RegionOfInterest"})};
  return t;
}

const MessageType& tf_message_type() {
  static const MessageType t{
      "tf2_msgs/msg/TFMessage",
      with_dependencies(
          "geometry_msgs/TransformStamped[] transforms\n",
          {"geometry_msgs/TransformStamped", "std_msgs/Header", "builtin_interfaces/Time",
           "geometry_msgs/Transform", "geometry_msgs/Vector3", "geometry_msgs/Quaternion"})};
  return t;
}

const MessageType& pose_stamped_type() {
  static const MessageType t{
      "geometry_msgs/msg/PoseStamped",
      with_dependencies("std_msgs/Header header\ngeometry_msgs/Pose pose\n",
                        {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/Pose",
                         "geometry_msgs/Point", "geometry_msgs/Quaternion"})};
  return t;
}

const MessageType& path_type() {
  static const MessageType t{
      "nav_msgs/msg/Path",
      with_dependencies("std_msgs/Header header\ngeometry_msgs/PoseStamped[] poses\n",
                        {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseStamped",
                         "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion"})};
  return t;
}

const MessageType& detection_array_type() {
  static const MessageType t{
      "vision_msgs/msg/Detection2DArray",
      with_dependencies(
          "std_msgs/Header header\nvision_msgs/Detection2D[] detections\n",
          {"std_msgs/Header", "builtin_interfaces/Time", "vision_msgs/Detection2D",
           "vision_msgs/ObjectHypothesisWithPose", "vision_msgs/ObjectHypothesis",
           "geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose", "geometry_msgs/Point",
           "geometry_msgs/Quaternion", "vision_msgs/BoundingBox2D", "vision_msgs/Pose2D",
           "vision_msgs/Point2D"})};
  return t;
}

std::string encode(const Image& m) {
  CdrWriter w;
  put(w, m.header);
  w.u32(m.height);
  w.u32(m.width);
  w.string(m.encoding);
  w.u8(m.is_bigendian);
  w.u32(m.step);
  w.byte_sequence(m.data.data(), m.data.size());
  return std::move(w.bytes());
}

std::string encode(const CameraInfo& m) {
  CdrWriter w;
  put(w, m.header);
  w.u32(m.height);
  w.u32(m.width);
  w.string(m.distortion_model);
  w.sequence_length(m.d.size());
  for (double v : m.d) w.f64(v);
  for (double v : m.k) w.f64(v);
  for (double v : m.r) w.f64(v);
  for (double v : m.p) w.f64(v);
  w.u32(m.binning_x);
  w.u32(m.binning_y);
  for (int i = 0; i < 4; ++i) w.u32(0);  // roi: the full image
  w.boolean(false);
  return std::move(w.bytes());
}

std::string encode(const TFMessage& m) {
  CdrWriter w;
  w.sequence_length(m.transforms.size());
  for (const TransformStamped& t : m.transforms) {
    put(w, t.header);
    w.string(t.child_frame_id);
    put(w, t.translation);
    put(w, t.rotation);
  }
  return std::move(w.bytes());
}

std::string encode(const PoseStamped& m) {
  CdrWriter w;
  put(w, m);
  return std::move(w.bytes());
}

std::string encode(const Path& m) {
  CdrWriter w;
  put(w, m.header);
  w.sequence_length(m.poses.size());
  for (const PoseStamped& p : m.poses) put(w, p);
  return std::move(w.bytes());
}

std::string encode(const Detection2DArray& m) {
  CdrWriter w;
  put(w, m.header);
  w.sequence_length(m.detections.size());
  for (const Detection2D& d : m.detections) {
    put(w, d.header);
    w.sequence_length(1);  // results: one hypothesis
    w.string(d.class_id);
    w.f64(d.score);
    put(w, Eigen::Vector3d::Zero().eval());  // pose: none (a 2-D detection)
    put(w, Eigen::Quaterniond::Identity());
    for (int i = 0; i < 36; ++i) w.f64(0.0);
    w.f64(d.centre_x);  // bbox.center.position
    w.f64(d.centre_y);
    w.f64(0.0);  // bbox.center.theta
    w.f64(d.size_x);
    w.f64(d.size_y);
    w.string(d.id);
  }
  return std::move(w.bytes());
}

std::string without_msg(const std::string& type) {
  const size_t at = type.find("/msg/");
  return at == std::string::npos ? type : type.substr(0, at) + type.substr(at + 4);
}

Time header_stamp(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  return take_header(r).stamp;
}

Image decode_image(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  Image m;
  m.header = take_header(r);
  m.height = r.u32();
  m.width = r.u32();
  m.encoding = r.string();
  m.is_bigendian = r.u8();
  m.step = r.u32();
  m.data = r.byte_sequence();
  return m;
}

CameraInfo decode_camera_info(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  CameraInfo m;
  m.header = take_header(r);
  m.height = r.u32();
  m.width = r.u32();
  m.distortion_model = r.string();
  m.d.resize(r.sequence_length());
  for (double& v : m.d) v = r.f64();
  for (double& v : m.k) v = r.f64();
  for (double& v : m.r) v = r.f64();
  for (double& v : m.p) v = r.f64();
  m.binning_x = r.u32();
  m.binning_y = r.u32();
  return m;
}

TFMessage decode_tf_message(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  TFMessage m;
  m.transforms.resize(r.sequence_length());
  for (TransformStamped& t : m.transforms) {
    t.header = take_header(r);
    t.child_frame_id = r.string();
    t.translation = take_vector(r);
    t.rotation = take_quaternion(r);
  }
  return m;
}

PoseStamped decode_pose_stamped(const std::string& cdr, const std::string& where) {
  CdrReader r(cdr, where);
  PoseStamped p;
  p.header = take_header(r);
  p.position = take_vector(r);
  p.orientation = take_quaternion(r);
  return p;
}

}  // namespace depot::ros2
