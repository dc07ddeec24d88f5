#include "dataset/object_poses.h"

#include <cmath>
#include <fstream>

#include "common/error.h"
#include "common/text_records.h"
#include "common/tum_io.h"
#include "dataset/dataset_files.h"
#include "dataset/format_version.h"
#include "dataset/text_fields.h"

namespace depot::dataset {
namespace {

ObjectPoseRecord parse_record(const std::vector<std::string>& f, const std::string& where) {
  if (f.size() != 10)
    fail(where, "expected 10 fields (timestamp id tx ty tz qx qy qz qw moving), found " +
                    std::to_string(f.size()));
  ObjectPoseRecord r;
  r.timestamp = parse_number_field(f[0], "timestamp", where);
  const long id = parse_integer_field(f[1], "id", where);
  if (id < 1 || id > 65535) fail(where, "id " + f[1] + " is not an instance id (1..65535)");
  r.id = static_cast<int>(id);
  static const char* const names[] = {"tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  double v[7];
  for (int i = 0; i < 7; ++i) v[i] = parse_number_field(f[2 + i], names[i], where);
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (std::abs(q.norm() - 1.0) > kQuaternionNormTolerance)
    fail(where, "quaternion norm " + std::to_string(q.norm()) + " is not 1");
  q.normalize();
  r.pose = make_pose(q, Eigen::Vector3d(v[0], v[1], v[2]));
  r.moving = parse_flag_field(f[9], "moving", where);
  return r;
}

}  // namespace

std::string object_poses_header(const std::string& scenario_name) {
  return "# per-frame poses of pushables and actors (dataset frame); moving = moved >1 mm or >0.1 "
         "deg\n" +
         file_header_line(scenario_name) + "# timestamp id tx ty tz qx qy qz qw moving\n";
}

std::string format_object_pose(const ObjectPoseRecord& record) {
  std::string line = format_tum_pose({record.timestamp, record.pose});
  // "t x y z qx qy qz qw" -> the id after the timestamp.
  line.insert(line.find(' '), " " + std::to_string(record.id));
  return line + (record.moving ? " 1\n" : " 0\n");
}

void write_object_poses(const std::string& dataset_dir, const std::string& scenario_name,
                        const std::vector<ObjectPoseRecord>& records) {
  std::string text = object_poses_header(scenario_name);
  for (const ObjectPoseRecord& r : records) text += format_object_pose(r);
  write_text_file_atomic(dataset_file(dataset_dir, kObjectPosesFile), text);
}

std::vector<ObjectPoseRecord> read_object_poses(const std::string& dataset_dir) {
  check_format_version(dataset_dir);
  const std::string path = dataset_file(dataset_dir, kObjectPosesFile);
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file (the objects' per-frame poses; not a simulated dataset?)");
  std::vector<ObjectPoseRecord> records;
  for_each_record(in, path, [&](const std::string& where, const std::vector<std::string>& f) {
    records.push_back(parse_record(f, where));
  });
  if (in.bad()) fail(path, "read error");
  return records;
}

}  // namespace depot::dataset
