#include "sim/dataset/truth_files.h"

#include <nlohmann/json.hpp>

#include "common/tum_io.h"

namespace depot::sim {
namespace {

nlohmann::json pose_json(const Pose& p) {
  Eigen::Quaterniond q(p.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  const auto& t = p.translation();
  return {{"t", {t.x(), t.y(), t.z()}}, {"q_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

}  // namespace

std::string object_poses_header() {
  return "# per-frame poses of pushables and actors (dataset frame); moving = moved >1 mm or >0.1 "
         "deg\n";
}

std::string object_pose_lines(const FrameTruth& truth) {
  std::string out;
  for (const ObjectState& s : truth.objects) {
    std::string line = format_tum_pose({truth.rgb_timestamp, s.pose});
    // "t x y z qx qy qz qw" -> insert the id after the timestamp.
    line.insert(line.find(' '), " " + std::to_string(s.id));
    out += line + (s.moving ? " 1\n" : " 0\n");
  }
  return out;
}

std::string objects_json(const std::string& scenario_name, const std::vector<Instance>& instances,
                         const ClassTable& classes) {
  nlohmann::json objects = nlohmann::json::array();
  for (const Instance& inst : instances) {
    nlohmann::json o(
        {{"id", inst.id},
         {"name", inst.name},
         {"class", inst.class_name},
         {"category", category_name(inst.category)},
         {"kind", instance_kind_name(inst.kind)},
         {"yolo_class", classes.yolo_index(inst.class_name)},
         {"pose", pose_json(inst.pose)},
         {"extent",
          {{"min", {inst.extent.min().x(), inst.extent.min().y(), inst.extent.min().z()}},
           {"max", {inst.extent.max().x(), inst.extent.max().y(), inst.extent.max().z()}}}}});
    if (!inst.asset.empty()) o["asset"] = inst.asset;
    objects.push_back(std::move(o));
  }
  nlohmann::json doc = {{"scenario", scenario_name}, {"instances", objects}};
  return doc.dump(1) + "\n";
}

}  // namespace depot::sim
