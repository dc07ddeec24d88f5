#pragma once
// object_poses.txt: the pose of every pushable and actor in every frame, and
// whether it moved since the previous frame. One line per object and frame:
//
//   timestamp id tx ty tz qx qy qz qw moving
//
// (a TUM pose with the instance id after the timestamp; moving = moved more
// than 1 mm or 0.1 degree).
#include <string>
#include <vector>

#include "common/pose.h"

namespace depot::dataset {

struct ObjectPoseRecord {
  double timestamp = 0;          // the frame's rgb timestamp
  int id = 0;                    // instance id (objects.json)
  Pose pose = Pose::Identity();  // in the dataset frame
  bool moving = false;
};

// The comment lines that open the file.
std::string object_poses_header(const std::string& scenario_name);
// One line, with its newline.
std::string format_object_pose(const ObjectPoseRecord& record);
// Writes `dataset_dir`/object_poses.txt atomically: the header, then the
// records in the given order (frame by frame).
void write_object_poses(const std::string& dataset_dir, const std::string& scenario_name,
                        const std::vector<ObjectPoseRecord>& records);

// Reads `dataset_dir`/object_poses.txt after checking the dataset's format
// version; records in file order. Throws depot::Error "<path>:<line>: ..."
// for a malformed line (field count, numbers, id, quaternion norm, flag).
std::vector<ObjectPoseRecord> read_object_poses(const std::string& dataset_dir);

}  // namespace depot::dataset
