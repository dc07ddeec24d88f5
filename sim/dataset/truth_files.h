#pragma once
// The simulator's ground truth as the dataset library's records
// (dataset/): what full datasets and truth-only exports both write.
#include <string>
#include <vector>

#include "dataset/dataset_info.h"
#include "dataset/object_poses.h"
#include "dataset/objects.h"
#include "sim/scenario/class_table.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/scene_model.h"
#include "sim/world/simulated_sequence.h"

namespace depot::sim {

// The object_poses.txt records of one frame.
std::vector<dataset::ObjectPoseRecord> object_pose_records(const FrameTruth& truth);
// objects.json: every instance with class, category, kind, pose and extent.
dataset::ObjectsFile objects_file(const std::string& scenario_name,
                                  const std::vector<Instance>& instances,
                                  const ClassTable& classes);
// info.json's members that come from the scenario (the writers add the
// frames and what only they know).
dataset::DatasetInfo scenario_info(const Scenario& scenario, const std::string& generator);

}  // namespace depot::sim
