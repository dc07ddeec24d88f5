#pragma once
// A trajectory recorded in a ROS 2 bag: geometry_msgs/PoseStamped messages
// on a topic (a depot bag's ground truth: /depot/ground_truth/pose), or the
// transforms to one child frame on a tf2_msgs/TFMessage topic (/tf), as TUM
// poses stamped by their headers.
#include <string>
#include <vector>

#include "common/tum_io.h"

namespace depot::ros2 {

struct BagTrajectorySource {
  std::string topic;        // "" = the depot truth topic
  std::string child_frame;  // for TFMessage topics ("" = the depot truth camera)
};

// Throws depot::Error "<bag>: ..." for a missing topic, another message
// type, or no pose at all.
std::vector<StampedPose> read_bag_trajectory(const std::string& bag,
                                             const BagTrajectorySource& source = {});

// A TUM trajectory file, or a bag's trajectory for a path ending in ".mcap":
// what `depot eval` reads as its reference.
std::vector<StampedPose> read_trajectory(const std::string& path);

}  // namespace depot::ros2
