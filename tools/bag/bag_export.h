#pragma once
// A dataset folder (TUM RGB-D, simulated or real) written as a ROS 2 bag in
// MCAP: the topics of dataset/ros2/bag_layout.h, every message stamped with
// the dataset's own timestamps, streamed frame by frame (memory stays flat).
//
//   /camera/color/image_raw     sensor_msgs/Image rgb8
//   /camera/depth/image_raw     sensor_msgs/Image 32FC1, metres: the datasets'
//                               depth has 0.2 mm steps (PNG / 5000), which
//                               16UC1 millimetres would round; 32FC1 holds
//                               every value the folder's reader gives, so a
//                               run on the bag equals a run on the folder
//   /camera/{color,depth}/camera_info   with each image (plumb_bob)
//   /tf_static, /tf             depot_world -> depot_camera_truth (the ground
//                               truth) -> the optical frames (identity)
//   /depot/ground_truth/pose    geometry_msgs/PoseStamped, each truth pose
//   /depot/ground_truth/path    nav_msgs/Path, all of them, once at the end
//   /depot/instances/image_raw  sensor_msgs/Image 16UC1 instance ids
//   /depot/boxes                vision_msgs/Detection2DArray: class_id the
//                               class, id "<instance id>" or "<id> moving",
//                               score visible_pixels / box area
//   /depot/objects/tf           tf2_msgs/TFMessage: depot_world ->
//                               depot_object_<id> for every object
// The truth topics come from the files a simulated dataset has; a real
// folder gives only what it holds.
#include <cstdint>
#include <string>

#include "dataset/mcap/mcap_records.h"
#include "dataset/mcap/mcap_writer.h"

namespace depot::bag {

struct BagExportOptions {
  mcap::Compression compression = mcap::Compression::kZstd;
  bool progress = true;
};

struct BagExportReport {
  size_t frames = 0;
  mcap::WriterTotals totals;
  uint64_t folder_bytes = 0;  // the dataset folder's files, for the ratio
  double seconds = 0;
  std::vector<std::string> topics;
};

// Throws depot::Error naming the file at fault; leaves no partial bag.
BagExportReport export_bag(const std::string& dataset, const std::string& bag_path,
                           const BagExportOptions& options = {});

}  // namespace depot::bag
