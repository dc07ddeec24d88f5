#pragma once
// Where a depot dataset's streams lie in a ROS 2 bag: topic and frame names,
// owned here so the exporter (tools/bag) and the SLAM's bag reader
// (slam/io/mcap_sequence.h) agree. The camera topics are those of the
// realsense2_camera and openni drivers, so a user's own recording reads with
// the defaults; the truth lives under /depot and in frames of its own, so it
// never fights a SLAM system's tf tree.
namespace depot::ros2 {

inline constexpr const char* kColourTopic = "/camera/color/image_raw";
inline constexpr const char* kColourInfoTopic = "/camera/color/camera_info";
inline constexpr const char* kDepthTopic = "/camera/depth/image_raw";
inline constexpr const char* kDepthInfoTopic = "/camera/depth/camera_info";
inline constexpr const char* kTfTopic = "/tf";
inline constexpr const char* kTfStaticTopic = "/tf_static";
inline constexpr const char* kLabelsTopic = "/depot/instances/image_raw";
inline constexpr const char* kBoxesTopic = "/depot/boxes";
inline constexpr const char* kObjectsTopic = "/depot/objects/tf";
inline constexpr const char* kTruthPoseTopic = "/depot/ground_truth/pose";
inline constexpr const char* kTruthPathTopic = "/depot/ground_truth/path";

// The world of the truth and the camera's true pose in it (/tf); the optical
// frames of the images hang from the latter (/tf_static, identity: the
// ground truth is the colour camera's pose and depth is registered to it).
inline constexpr const char* kWorldFrame = "depot_world";
inline constexpr const char* kTruthCameraFrame = "depot_camera_truth";
inline constexpr const char* kColourFrame = "camera_color_optical_frame";
inline constexpr const char* kDepthFrame = "camera_depth_optical_frame";

// Colour and depth within this of each other make one frame (TUM's
// associate.py default).
inline constexpr double kMaxColourDepthGap = 0.02;

}  // namespace depot::ros2
