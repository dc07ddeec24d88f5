#include "dataset/objects.h"

#include <set>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"
#include "dataset/json_file.h"

namespace depot::dataset {
namespace {

nlohmann::json pose_json(const Pose& p) {
  Eigen::Quaterniond q(p.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;  // one canonical sign, for stable files
  const auto& t = p.translation();
  return {{"t", {t.x(), t.y(), t.z()}}, {"q_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

const nlohmann::json& object_member(const nlohmann::json& o, const char* key,
                                    const std::string& where) {
  const auto it = o.find(key);
  if (it == o.end()) fail(where, std::string("'") + key + "' is missing");
  if (!it->is_object()) fail(where, std::string("'") + key + "' is not a JSON object");
  return *it;
}

Pose read_pose(const nlohmann::json& o, const std::string& where) {
  const nlohmann::json& pose = object_member(o, "pose", where);
  const std::vector<double> t = numbers_member(pose, "t", 3, where + ": pose");
  const std::vector<double> q = numbers_member(pose, "q_xyzw", 4, where + ": pose");
  Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  const double norm = rotation.norm();
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance)
    fail(where, "pose quaternion norm " + std::to_string(norm) + " is not 1");
  rotation.normalize();
  return make_pose(rotation, Eigen::Vector3d(t[0], t[1], t[2]));
}

Eigen::AlignedBox3d read_extent(const nlohmann::json& o, const std::string& where) {
  const nlohmann::json& extent = object_member(o, "extent", where);
  const std::vector<double> lo = numbers_member(extent, "min", 3, where + ": extent");
  const std::vector<double> hi = numbers_member(extent, "max", 3, where + ": extent");
  return Eigen::AlignedBox3d(Eigen::Vector3d(lo[0], lo[1], lo[2]),
                             Eigen::Vector3d(hi[0], hi[1], hi[2]));
}

ObjectRecord read_object(const nlohmann::json& o, const std::string& where) {
  ObjectRecord r;
  const long long id = integer_member(o, "id", where);
  if (id < 1 || id > 65535)
    fail(where, "id " + std::to_string(id) + " is not an instance id (1..65535)");
  r.id = static_cast<int>(id);
  r.name = string_member(o, "name", where);
  r.class_name = string_member(o, "class", where);
  r.category = string_member(o, "category", where);
  r.kind = string_member(o, "kind", where);
  r.yolo_class = static_cast<int>(integer_member(o, "yolo_class", where));
  r.pose = read_pose(o, where);
  r.extent = read_extent(o, where);
  if (o.contains("asset")) r.asset = string_member(o, "asset", where);
  return r;
}

}  // namespace

std::string format_objects(const ObjectsFile& file) {
  nlohmann::json objects = nlohmann::json::array();
  for (const ObjectRecord& r : file.objects) {
    nlohmann::json o(
        {{"id", r.id},
         {"name", r.name},
         {"class", r.class_name},
         {"category", r.category},
         {"kind", r.kind},
         {"yolo_class", r.yolo_class},
         {"pose", pose_json(r.pose)},
         {"extent", {{"min", vector_json(r.extent.min())}, {"max", vector_json(r.extent.max())}}}});
    if (!r.asset.empty()) o["asset"] = r.asset;
    objects.push_back(std::move(o));
  }
  const nlohmann::json doc = {{"scenario", file.scenario}, {"instances", objects}};
  return doc.dump(1) + "\n";
}

void write_objects(const std::string& dataset_dir, const ObjectsFile& file) {
  write_text_file_atomic(dataset_file(dataset_dir, kObjectsFile), format_objects(file));
}

ObjectsFile read_objects(const std::string& dataset_dir) {
  check_format_version(dataset_dir);
  const std::string path = dataset_file(dataset_dir, kObjectsFile);
  const nlohmann::json doc =
      read_json_file(path, "the dataset's objects; not a simulated dataset?");
  ObjectsFile file;
  file.scenario = string_member(doc, "scenario", path);
  const auto instances = doc.find("instances");
  if (instances == doc.end() || !instances->is_array())
    fail(path, "'instances' is missing or not a list");
  std::set<int> ids;
  for (size_t i = 0; i < instances->size(); ++i) {
    const std::string where = path + ": instance " + std::to_string(i + 1);
    ObjectRecord r = read_object((*instances)[i], where);
    if (!ids.insert(r.id).second) fail(where, "id " + std::to_string(r.id) + " is listed twice");
    file.objects.push_back(std::move(r));
  }
  return file;
}

}  // namespace depot::dataset
