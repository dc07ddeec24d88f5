#pragma once
// Text forms of the ground truth shared by full datasets and truth-only
// exports: per-frame object poses and the objects file.
#include <string>
#include <vector>

#include "sim/scenario/class_table.h"
#include "sim/scene/scene_model.h"
#include "sim/world/simulated_sequence.h"

namespace depot::sim {

// Header of object_poses.txt (after the file line).
std::string object_poses_header();
// The object_poses.txt lines of one frame: "timestamp id tx ty tz qx qy qz qw moving".
std::string object_pose_lines(const FrameTruth& truth);
// objects.json: every instance with class, category, kind, pose and extent.
std::string objects_json(const std::string& scenario_name, const std::vector<Instance>& instances,
                         const ClassTable& classes);

}  // namespace depot::sim
