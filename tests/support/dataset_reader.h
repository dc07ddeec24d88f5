#pragma once
// Test-side reading of a written dataset: calibration, ground truth, images,
// objects and per-frame object states. The truth files are read by the
// dataset library (dataset/), never by the simulator's code, so tests check
// the files, not the writer.
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "common/pose.h"
#include "common/testing/temp_path.h"
#include "common/tum_io.h"
#include "dataset/calibration.h"
#include "dataset/objects.h"

namespace depot::test {

using Calibration = dataset::CameraCalibration;

using ObjectInfo = dataset::ObjectRecord;

struct ObjectPose {
  Pose pose = Pose::Identity();
  bool moving = false;
};

struct Dataset {
  std::string root;
  Calibration calibration;
  std::vector<Association> frames;
  std::vector<StampedPose> groundtruth;
  std::vector<StampedFile> labels;
  std::map<int, ObjectInfo> objects;
  // per frame index: id -> pose/moving
  std::vector<std::map<int, ObjectPose>> object_poses;

  cv::Mat depth_metres(size_t frame) const;  // CV_32F
  cv::Mat labels_image(size_t frame) const;  // CV_16U
  cv::Mat rgb(size_t frame) const;
  const ObjectInfo& object(const std::string& name) const;
};

Dataset read_dataset(const std::string& root);

// A path that does not exist yet, inside this test process's own temporary
// folder (removed when the process exits).
using testkit::temp_path;

// Writes `text` to a new temp_path(tag) + ".yaml" and returns its path.
std::string write_yaml(const std::string& tag, const std::string& text);

// Runs a shell command, returning exit code; stdout/stderr captured.
int run_command(const std::string& command, std::string* output);

// Byte comparison of two folder trees; returns "" when identical, else the
// first difference.
std::string compare_trees(const std::string& a, const std::string& b);

}  // namespace depot::test
