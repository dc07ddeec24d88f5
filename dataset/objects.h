#pragma once
// objects.json: every instance of the scene with its class, category, kind,
// YOLO class, initial pose and extent. Instance ids are the values of the
// label images (labels/) and the ids of object_poses.txt and boxes.txt.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "common/pose.h"

namespace depot::dataset {

struct ObjectRecord {
  int id = 0;  // 1..65535 (0 is "no instance" in a label image)
  std::string name;
  std::string class_name;        // "class"
  std::string category;          // e.g. "static", "dynamic"
  std::string kind;              // e.g. "static", "actor", "pushable"
  int yolo_class = -1;           // index in classes.txt, -1 when not detectable
  Pose pose = Pose::Identity();  // world pose (initial, for moving ones)
  Eigen::AlignedBox3d extent;    // bounds in the instance's own frame
  std::string asset;             // catalogue entry it is drawn from; "" for primitives
};

struct ObjectsFile {
  std::string scenario;
  std::vector<ObjectRecord> objects;  // in id order as written
};

// The file's text (pretty-printed; quaternions normalised with w >= 0).
std::string format_objects(const ObjectsFile& file);
// Writes `dataset_dir`/objects.json atomically.
void write_objects(const std::string& dataset_dir, const ObjectsFile& file);

// Reads `dataset_dir`/objects.json after checking the dataset's format
// version. Throws depot::Error naming the file (and the instance) when it is
// missing or malformed, or an id is out of range or listed twice.
ObjectsFile read_objects(const std::string& dataset_dir);

}  // namespace depot::dataset
