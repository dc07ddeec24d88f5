#include "sim/dataset/truth_files.h"

namespace depot::sim {

std::vector<dataset::ObjectPoseRecord> object_pose_records(const FrameTruth& truth) {
  std::vector<dataset::ObjectPoseRecord> records;
  for (const ObjectState& s : truth.objects)
    records.push_back({truth.rgb_timestamp, s.id, s.pose, s.moving});
  return records;
}

dataset::ObjectsFile objects_file(const std::string& scenario_name,
                                  const std::vector<Instance>& instances,
                                  const ClassTable& classes) {
  dataset::ObjectsFile file;
  file.scenario = scenario_name;
  for (const Instance& inst : instances) {
    dataset::ObjectRecord r;
    r.id = inst.id;
    r.name = inst.name;
    r.class_name = inst.class_name;
    r.category = category_name(inst.category);
    r.kind = instance_kind_name(inst.kind);
    r.yolo_class = classes.yolo_index(inst.class_name);
    r.pose = inst.pose;
    r.extent = inst.extent;
    r.asset = inst.asset;
    file.objects.push_back(std::move(r));
  }
  return file;
}

dataset::DatasetInfo scenario_info(const Scenario& scenario, const std::string& generator) {
  dataset::DatasetInfo info;
  info.generator = generator;
  info.scenario = scenario.name;
  info.seed = scenario.seed;
  info.world_seed = scenario.world_seed();
  info.dynamic_load = scenario.dynamic_load;
  info.actors_style = scenario.actors_style;
  info.props_style = scenario.props_style;
  info.motion = scenario.motion.type;
  return info;
}

}  // namespace depot::sim
